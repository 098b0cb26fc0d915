#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <bsmpm/analysis/scene.h>
#include <bsmpm/analysis/strength_reduction.h>
#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/io/error_report.h>
#include <bsmpm/io/output_writer.h>
#include <bsmpm/verification/verification.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace bsmpm
{
  void
  StrengthReduction::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Strength reduction");
    prm.declare_entry(
      "Enabled",
      "false",
      Patterns::Bool(),
      "Find the factor of safety: run the scene's loading repeatedly with "
      "the strength divided by a trial factor F (von Mises: yield stress; "
      "Drucker-Prager: cohesion and tan of the friction and dilation "
      "angles), F found by bisection as the largest that does not collapse "
      "(Limit load/Detect collapse decides collapse; it is switched on for "
      "the trials). summary.json gives factor_of_safety and its bracket.");
    prm.declare_entry("Bracket",
                      "0.5, 4",
                      ParameterTools::point_pattern(),
                      "Lower and upper trial factor 'F_low, F_high' between "
                      "which the factor of safety is sought (F_low < "
                      "F_high). An end that the bisection never tries is "
                      "tried at the end, so that the bracket reported is "
                      "always between a factor that held and one that "
                      "collapsed; where the factor of safety lies outside "
                      "the Bracket, its end is halved or doubled until it "
                      "does (down to 1/64, up to 64).");
    prm.declare_entry("Tolerance",
                      "0.01",
                      Patterns::Double(1e-6, 1),
                      "Bisect until the bracket is narrower than this "
                      "fraction of its lower end.");
    prm.leave_subsection();
  }



  bool
  StrengthReduction::enabled(ParameterHandler &prm)
  {
    prm.enter_subsection("Strength reduction");
    const bool on = prm.get_bool("Enabled");
    prm.leave_subsection();
    return on;
  }



  namespace
  {
    /** Sets @p entry of @p section to @p value and returns the old one. */
    std::string
    exchange(ParameterHandler  &prm,
             const std::string &section,
             const std::string &entry,
             const std::string &value)
    {
      prm.enter_subsection(section);
      const std::string old = prm.get(entry);
      prm.set(entry, value);
      prm.leave_subsection();
      return old;
    }
  } // namespace



  RunSummary
  StrengthReduction::run(ParameterHandler &prm, const MPI_Comm communicator)
  {
    Timer              timer;
    ConditionalOStream pcout(std::cout,
                             Utilities::MPI::this_mpi_process(communicator) ==
                               0);
    prm.enter_subsection("Strength reduction");
    const Point<2> bracket   = ParameterTools::get_point(prm, "Bracket");
    const double   tolerance = prm.get_double("Tolerance");
    prm.leave_subsection();
    prm.enter_subsection("Loading");
    const bool load_control = prm.get("Control") == "load";
    prm.leave_subsection();
    // A trial collapses where load control stops at a limit load; under
    // displacement control no trial would.
    AssertThrow(load_control,
                ExcMessage("Strength reduction needs Loading/Control = load."));
    AssertThrow(bracket[0] > 0 && bracket[1] > bracket[0],
                ExcMessage("Strength reduction/Bracket: give two factors "
                           "0 < F_low < F_high, got " +
                           std::to_string(bracket[0]) + ", " +
                           std::to_string(bracket[1]) + "."));

    // No table of timings per trial; the run's total is in summary.json.
    const std::string timing =
      exchange(prm, "Output", "Timing summary", "false");
    OutputWriter output(communicator);
    output.parse_parameters(prm);
    output.prepare_directory();
    Verification verification;
    verification.parse_parameters(prm);

    RunSummary summary;
    summary.scene = prm.get("Scene name");
    prm.enter_subsection("Output");
    const std::string directory = prm.get("Directory");
    prm.leave_subsection();

    // The trials: their own directories, no bounds (those are on the
    // factor of safety), collapse detection on.
    const std::string bounds =
      exchange(prm, "Verification", "Bounds", std::string());
    const std::string detect =
      exchange(prm, "Limit load", "Detect collapse", "on");

    pcout << "strength reduction of scene " << summary.scene
          << ": factor of safety in [" << bracket[0] << ", " << bracket[1]
          << "] to " << tolerance << " of it\n";
    const auto trial = [&](const double factor) {
      RunSummary::Trial t;
      t.factor = factor;
      std::ostringstream name;
      name << directory << "/trial-" << std::setw(2) << std::setfill('0')
           << summary.trials.size() + 1;
      t.directory = name.str();
      exchange(prm, "Output", "Directory", t.directory);
      Scene scene(communicator);
      scene.quiet();
      scene.reduce_strength(factor);
      scene.parse_parameters(prm);
      scene.run();
      t.collapsed   = scene.collapse().collapsed();
      t.load_factor = t.collapsed ? scene.collapse().limit_load_factor() : 1.;
      t.reason      = scene.collapse().reason();
      summary.trials.push_back(t);
      summary.n_cells           = scene.summary().n_cells;
      summary.n_dofs            = scene.summary().n_dofs;
      summary.n_material_points = scene.summary().n_material_points;
      summary.load_steps        = scene.summary().load_steps;
      pcout << "  trial " << std::setw(2) << summary.trials.size()
            << ": F = " << std::fixed << std::setprecision(4) << factor
            << std::defaultfloat << "  "
            << (t.collapsed ?
                  "collapsed at load factor " + std::to_string(t.load_factor) :
                  std::string("holds the full load"))
            << "\n"
            << std::flush;
      return t.collapsed;
    };

    // The bisection keeps a factor that held (low) and one that collapsed
    // (high). An end of the Bracket that the bisection never tried is tried
    // at the end; one on the wrong side (the scene collapses at F_low: its
    // factor of safety is below the Bracket; it holds at F_high) is moved
    // outwards, halved or doubled, and the bisection goes on, so that the
    // bracket reported always lies between a factor that held and one that
    // collapsed.
    constexpr double lowest = 1. / 64, highest = 64;
    double           low = bracket[0], high = bracket[1];
    bool             low_tried = false, high_tried = false;
    const auto       bisect = [&]() {
      while (high - low > tolerance * low)
        {
          const double factor = (low + high) / 2;
          if (trial(factor))
            {
              high       = factor;
              high_tried = true;
            }
          else
            {
              low       = factor;
              low_tried = true;
            }
        }
    };
    try
      {
        bisect();
        while (!low_tried)
          {
            if (!trial(low))
              {
                low_tried = true;
                break;
              }
            AssertThrow(low > lowest,
                        ExcMessage(
                          "Strength reduction: the scene collapses even "
                          "with its strength multiplied by " +
                          std::to_string(1 / low) +
                          ": it cannot stand whatever its strength. Check "
                          "its loads and supports."));
            high       = low;
            high_tried = true;
            low /= 2;
            pcout << "  the factor of safety is below the Bracket: F = " << high
                  << " collapses, trying down to F = " << low << "\n";
            bisect();
          }
        while (!high_tried)
          {
            if (trial(high))
              {
                high_tried = true;
                break;
              }
            AssertThrow(high < highest,
                        ExcMessage(
                          "Strength reduction: the scene holds even with its "
                          "strength divided by " +
                          std::to_string(high) +
                          ": it does not fail by loss of strength (check "
                          "that its material yields)."));
            low       = high;
            low_tried = true;
            high *= 2;
            pcout << "  the factor of safety is above the Bracket: F = " << low
                  << " holds, trying up to F = " << high << "\n";
            bisect();
          }
      }
    catch (const std::exception &e)
      {
        // deal.II's exceptions are std::exceptions too.
        const auto *deal = dynamic_cast<const ExceptionBase *>(&e);
        exchange(prm, "Output", "Directory", directory);
        exchange(prm, "Verification", "Bounds", bounds);
        exchange(prm, "Limit load", "Detect collapse", detect);
        exchange(prm, "Output", "Timing summary", timing);
        summary.record_failure(summary.trials.size(),
                               deal ? message_of(*deal) : e.what(),
                               output);
        throw;
      }
    exchange(prm, "Output", "Directory", directory);
    exchange(prm, "Verification", "Bounds", bounds);
    exchange(prm, "Limit load", "Detect collapse", detect);
    exchange(prm, "Output", "Timing summary", timing);

    summary.quantities["factor_of_safety"]       = low;
    summary.quantities["factor_of_safety_lower"] = low;
    summary.quantities["factor_of_safety_upper"] = high;
    summary.quantities["trials"]                 = summary.trials.size();
    summary.limit_load_reason =
      "the largest strength reduction factor that holds the full load; "
      "the next collapsed";
    pcout << "factor of safety " << low << " (holds), " << high
          << " collapses\n";

    TimerOutput no_timer(MPI_COMM_SELF,
                         pcout,
                         TimerOutput::never,
                         TimerOutput::wall_times);
    summary.finish(
      verification, output, no_timer, timer.wall_time(), pcout, communicator);
    return summary;
  }
} // namespace bsmpm
