#include <bsmpm/io/run_checkpoint.h>

#include <boost/archive/archive_exception.hpp>
#include <boost/archive/binary_iarchive.hpp>
#include <boost/archive/binary_oarchive.hpp>
#include <boost/serialization/string.hpp>

#include <sstream>
#include <stdexcept>

namespace bsmpm
{
  RunCheckpoint::RunCheckpoint(Checkpoint &checkpoint, const Parts &parts)
    : checkpoint(checkpoint)
    , parts(parts)
  {}



  void
  RunCheckpoint::write(const unsigned int  step,
                       const RunSummary   &so_far,
                       const OutputWriter &output) const
  {
    // What the next step starts from, the linear solver's choice of
    // method, the contact's state, and the curves' chains with the tracked
    // list (the same on every process).
    std::ostringstream state;
    {
      const IncrementSolver::Memory   memory = parts.increment_solver.memory();
      boost::archive::binary_oarchive archive(state);
      archive << memory << parts.collapse_detector << parts.linear_solver;
      if (parts.contact != nullptr)
        archive << *parts.contact;
      const std::string tracking = parts.points.tracking_state(),
                        chains   = parts.curves.chain_state();
      archive << tracking << chains;
    }
    // A resumed run starts its solves without the factors, hierarchies and
    // first guesses of earlier ones: so does this run from here on.
    parts.linear_solver.drop_reused_state();
    checkpoint.write(step,
                     parts.grid,
                     parts.points,
                     so_far,
                     output,
                     parts.assembly.weak_cells_of_last_matrix(),
                     state.str());
  }



  unsigned int
  RunCheckpoint::resume(RunSummary &summary, OutputWriter &output) const
  {
    std::vector<CellId> weak_cells;
    const unsigned int  first_step =
      checkpoint.read_state(summary, output, weak_cells) + 1;
    parts.assembly.restore_matrix(weak_cells);
    // Checkpoints of earlier versions have no such state: resumed,
    // their next step starts from zero; with rigid bodies they are
    // refused (the friction history is not in them).
    const std::string state = checkpoint.read_scene_state();
    AssertThrow(!state.empty() || parts.contact == nullptr,
                ExcMessage("This checkpoint has no contact state "
                           "(written by a version of bsmpm that did "
                           "not keep it): a run with rigid bodies "
                           "cannot resume from it."));
    if (!state.empty())
      {
        std::istringstream              in(state);
        boost::archive::binary_iarchive archive(in);
        IncrementSolver::Memory         memory;
        archive >> memory >> parts.collapse_detector >> parts.linear_solver;
        parts.increment_solver.restore(memory);
        if (parts.contact != nullptr)
          archive >> *parts.contact;
        // The curves' chains and the tracked list, where the checkpoint
        // has them (versions before kept none and rebuild the curves as
        // at the start).
        std::string tracking, chains;
        try
          {
            archive >> tracking >> chains;
          }
        catch (const boost::archive::archive_exception &)
          {
            tracking.clear();
          }
        if (!tracking.empty())
          {
            parts.points.restore_tracking(tracking);
            parts.curves.restore_chains(chains);
            return first_step;
          }
      }
    // Without the chains in the checkpoint, the curves and the tracked
    // list are rebuilt as at the start, which no longer matches points
    // that were inserted or removed (their records begin with the first
    // change).
    for (const auto &record : summary.steps)
      AssertThrow(record.quantities.count("curve1_points") == 0,
                  ExcMessage("This checkpoint cannot be resumed: the boundary "
                             "curves gained or lost tracking points before it "
                             "(from load step " +
                             std::to_string(record.number) +
                             "), and it was written by a version of bsmpm "
                             "that did not keep them. Resume from an earlier "
                             "checkpoint."));
    return first_step;
  }



  void
  RunCheckpoint::explain_read_errors(const std::string           &from,
                                     const std::function<void()> &run)
  {
    try
      {
        run();
      }
    catch (const boost::archive::archive_exception &e)
      {
        // Reading the checkpoint's archives failed; boost's message
        // ("input stream error") names nothing.
        if (e.code == boost::archive::archive_exception::output_stream_error)
          throw;
        throw std::runtime_error(
          "Checkpoint '" + from +
          "': its files 'state' and 'points' cannot be read: "
          "truncated or damaged (" +
          e.what() + "). Resume from an earlier checkpoint-<step> directory.");
      }
  }
} // namespace bsmpm
