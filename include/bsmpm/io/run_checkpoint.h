#ifndef bsmpm_run_checkpoint_h
#define bsmpm_run_checkpoint_h

#include <bsmpm/assembly/system_assembly.h>
#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/contact/curve_contact.h>
#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/io/checkpoint.h>
#include <bsmpm/io/output_writer.h>
#include <bsmpm/io/run_summary.h>
#include <bsmpm/linear_algebra/linear_solver.h>
#include <bsmpm/nonlinear/collapse_detector.h>
#include <bsmpm/nonlinear/increment_solver.h>
#include <bsmpm/points/material_points.h>

#include <functional>
#include <string>

namespace bsmpm
{
  using namespace dealii;

  /**
   * What a run writes into its checkpoints and takes back when it resumes,
   * beyond what Checkpoint reads and writes (the grid, the points, the
   * summary and the series records): the weak cells the system matrix was
   * made for (SystemAssembly), what the next load step starts from
   * (IncrementSolver::Memory), the collapse detector's history, the linear
   * solver's choice of method and the contact's state (the same on every
   * process), and the curves' chains with the tracked list (where points
   * were inserted or removed), the last six as one binary archive. What
   * cannot be kept
   * (factors, multigrid hierarchies, CG's first guess) the run drops when
   * it writes a checkpoint (LinearSolver::drop_reused_state()), so that
   * on one process a resumed run is bitwise the run left alone.
   */
  class RunCheckpoint
  {
  public:
    /** What is saved and restored; all owned by the caller. */
    struct Parts
    {
      const BackgroundGrid &grid;
      MaterialPoints       &points;
      BoundaryCurves       &curves;
      SystemAssembly       &assembly;
      IncrementSolver      &increment_solver;
      CollapseDetector     &collapse_detector;
      LinearSolver         &linear_solver;
      /** Contact with rigid bodies, or null. */
      CurveContact *contact;
    };

    RunCheckpoint(Checkpoint &checkpoint, const Parts &parts);

    /** Writes the checkpoint after load step @p step with the summary
     * @p so_far (collective). */
    void
    write(const unsigned int  step,
          const RunSummary   &so_far,
          const OutputWriter &output) const;

    /**
     * Restores the summary, the series records of @p output and the state
     * of the parts from the checkpoint being resumed; returns the first
     * load step to run. Refuses checkpoints that cannot be resumed (written
     * by a version that did not keep the curves' chains, after the curves
     * changed their points; rigid bodies without a contact state).
     */
    unsigned int
    resume(RunSummary &summary, OutputWriter &output) const;

    /** Runs @p run, which resumes from the checkpoint @p from; a failure
     * to read its archives becomes a message that names the checkpoint
     * and what to do (boost's own names nothing). */
    static void
    explain_read_errors(const std::string           &from,
                        const std::function<void()> &run);

  private:
    Checkpoint &checkpoint;
    Parts       parts;
  };
} // namespace bsmpm

#endif
