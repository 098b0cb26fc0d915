#ifndef bsmpm_run_summary_h
#define bsmpm_run_summary_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <bsmpm/io/output_writer.h>
#include <bsmpm/nonlinear/load_step_record.h>
#include <bsmpm/verification/verification.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace bsmpm
{
  /**
   * What a run reports: sizes, a line per load step, errors against the exact
   * solution, scene-specific quantities and the time per phase. Written as
   * summary.json for scripts and printed as a table for people.
   */
  struct RunSummary
  {
    /** A load step: its number, what the solver did (LoadStepRecord) and
     * the scene's quantities after it. */
    struct Step : LoadStepRecord
    {
      unsigned int number = 0;
      /** Its stage (LoadStages), from 1; load_factor is the stage's own. */
      unsigned int stage = 1;
      /** The scene's quantities after this step (support reactions, the
       * probe, ...): load-displacement curves. */
      std::map<std::string, double> quantities;
    };

    std::string        scene;
    unsigned long long n_cells           = 0;
    unsigned long long n_dofs            = 0;
    unsigned long long n_material_points = 0;
    unsigned long long n_tracking_points = 0;
    unsigned int       load_steps        = 0;
    /** Whether the steps are Newton iterations (nonlinear material). */
    bool                          nonlinear = false;
    std::vector<Step>             steps;
    std::map<std::string, double> errors;
    std::map<std::string, double> quantities;
    std::map<std::string, double> timing;
    /** "running" while steps are being added, "completed" once finish()
     * wrote the record, "failed" after record_failure(). */
    std::string status = "running";
    /** A run that stopped at its limit load (CollapseDetector): why. */
    std::string limit_load_reason;
    /** A strength reduction (StrengthReduction): every trial factor. */
    struct Trial
    {
      double      factor      = 1;
      bool        collapsed   = false;
      double      load_factor = 0;
      std::string reason;
      std::string directory;
    };
    std::vector<Trial> trials;
    /** A failed run: the load step it failed in and the message. */
    unsigned int failed_step = 0;
    std::string  error;

    /** JSON with numbers as numbers (full precision), NaN and inf as null. */
    void
    write_json(std::ostream &out) const;

    /** The header lines: scene and sizes. */
    void
    print_header(std::ostream &out) const;

    /** One line of the load-step table (with the table head before step 1). */
    void
    print_step(std::ostream &out, const Step &step) const;

    /**
     * Adds a finished load step: its line in the step table, flushed so that
     * a log that goes to a file holds every finished step even if the run is
     * killed, and summary.json with the steps so far (written atomically), so
     * that a run that is killed or fails keeps the record of what it did.
     */
    void
    record_step(const Step                       &step,
                const OutputWriter               &output,
                const dealii::ConditionalOStream &pcout);

    /**
     * A run that stops with an error in load step @p step: summary.json
     * with the steps done, status "failed", the step and @p message.
     */
    void
    record_failure(const unsigned int  step,
                   const std::string  &message,
                   const OutputWriter &output);

    /** Increments accepted at their best iterate (Nonlinear solver/Stall
     * tolerance): how many and the largest residual into the quantities,
     * and a note through @p pcout, where there are any. */
    void
    report_stalled_increments(const dealii::ConditionalOStream &pcout);

    /** Errors and quantities, one per line, six significant digits. */
    void
    print_results(std::ostream &out) const;

    /** Adds the wall time of every section of @p timer and @p total_seconds
     * as "total" to the timing (a resumed run adds its part). */
    void
    add_timing(const dealii::TimerOutput &timer, const double total_seconds);

    /**
     * The end of a run: adds the timing, prints the results and the
     * checks of @p verification against the errors and quantities, writes
     * summary.json through @p output, prints @p timer's sections if
     * Output asks for them, and throws if a check failed.
     */
    void
    finish(const Verification               &verification,
           const OutputWriter               &output,
           const dealii::TimerOutput        &timer,
           const double                      total_seconds,
           const dealii::ConditionalOStream &pcout,
           const MPI_Comm                    communicator);
  };
} // namespace bsmpm

#endif
