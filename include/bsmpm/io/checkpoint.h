#ifndef bsmpm_checkpoint_h
#define bsmpm_checkpoint_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <bsmpm/geometry/background_grid.h>
#include <bsmpm/io/output_writer.h>
#include <bsmpm/io/run_summary.h>
#include <bsmpm/points/material_points.h>

#include <set>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Checkpoints of a run and resuming from them.
   *
   * A checkpoint is a directory <Output/Directory>/checkpoint-<step> that
   * holds everything a run needs to go on after load step <step>:
   *
   * - `triangulation*`: the grid and, attached to its cells, every particle
   *   (material and tracking points, so the curves' points too) with its
   *   position, reference position, id and all properties, written by
   *   deal.II's own serialisation (p::d::Triangulation::save() after
   *   ParticleHandler::prepare_for_serialization()), so that a run may also
   *   resume on another number of processes;
   * - `state`: a binary archive with the format version, the number of
   *   properties per point, the step, the ParticleHandler's counters, the
   *   summary so far, the records of the ParaView series written and the
   *   weak cells the system matrix was made for (its pattern depends on
   *   the steps before);
   * - `parameters.prm`: every parameter of the run.
   *
   * Everything else a step needs is either rebuilt from the parameters in
   * the same way as at the start (the tracked point ids, the curves' slots
   * and initial positions, which depend only on the initial state) or
   * recomputed every step from the points.
   *
   * A checkpoint is written into checkpoint-<step>.tmp and renamed when
   * complete, so a run killed while writing leaves the previous checkpoint
   * intact; the last two are kept.
   */
  class Checkpoint
  {
  public:
    explicit Checkpoint(const MPI_Comm communicator);

    /** Declares `Output/Checkpoint interval`. */
    static void
    declare_parameters(ParameterHandler &prm);

    /** Reads the interval and the output directory, and keeps the text of
     * every parameter for the checkpoints. */
    void
    parse_parameters(ParameterHandler &prm);

    /** Whether a checkpoint follows load step @p step of @p n_steps (never
     * after the last). */
    bool
    writes_step(const unsigned int step, const unsigned int n_steps) const;

    /** The last steps of the stages of a staged scene (LoadStages): with
     * checkpoints on, each is written and kept, to resume a later stage
     * from it with changed parameters. */
    void
    keep_stage_ends(const std::set<unsigned int> &steps)
    {
      stage_ends = steps;
    }

    /** Writes the checkpoint after load step @p step (collective).
     * @p weak_cells are this process's part of the weak cells the system
     * matrix was last made for (SystemAssembly::weak_cells_of_last_matrix()).
     */
    void
    write(const unsigned int         step,
          const BackgroundGrid      &grid,
          MaterialPoints            &points,
          const RunSummary          &summary,
          const OutputWriter        &output,
          const std::vector<CellId> &weak_cells,
          const std::string         &scene_state);

    /**
     * The checkpoint to resume from: @p path itself if it is one, or the
     * complete checkpoint with the largest step in the directory @p path.
     * Throws with a message if there is none.
     */
    static std::string
    find(const std::string &path);

    /**
     * Reads the parameters of the checkpoint @p directory into @p prm. The
     * output directory becomes the one that holds the checkpoint, so that
     * the resumed run continues its series wherever it was moved.
     */
    static void
    read_parameters(const std::string &directory, ParameterHandler &prm);

    /** Throws unless the parameter @p path ("Section/Name") may be changed
     * with --set when resuming from the checkpoint @p directory whose
     * parameters @p prm holds: those of the output, the number of stages
     * and those of the stages after the checkpoint's (LoadStages). */
    static void
    check_resume_override(const std::string &path,
                          const std::string &directory,
                          ParameterHandler  &prm);

    /** Makes the next run resume from the checkpoint @p directory. */
    void
    resume_from(const std::string &directory);

    bool
    resuming() const
    {
      return !resume_directory.empty();
    }

    /** The saved triangulation to load instead of refining the coarse grid
     * (BackgroundGrid::create()); empty unless resuming. */
    std::string
    triangulation_file() const;

    /**
     * Replaces the points (generated as at the start, so that every id,
     * tracked slot and initial position is the same) with those of the
     * checkpoint. Call after BackgroundGrid::create() with
     * triangulation_file() and before the triangulation changes.
     */
    void
    read_points(MaterialPoints &points) const;

    /** Restores the summary, the series records and the weak cells of
     * every process that the matrix was last made for; returns the step of
     * the checkpoint. */
    unsigned int
    read_state(RunSummary          &summary,
               OutputWriter        &output,
               std::vector<CellId> &weak_cells) const;

    /** The scene's state that write() was given (a binary archive of
     * where the next Newton iterations start and of the contact), empty
     * if none. */
    std::string
    read_scene_state() const;

  private:
    MPI_Comm     communicator;
    unsigned int interval = 0;
    std::string  output_directory;
    std::string  parameters;
    std::string  resume_directory;
    /** Name of the checkpoint this run wrote last (or resumed from): kept
     * when the next one is written, every other one removed. */
    std::string previous;
    /** The last steps of the stages (keep_stage_ends()). */
    std::set<unsigned int> stage_ends;
  };
} // namespace bsmpm

#endif
