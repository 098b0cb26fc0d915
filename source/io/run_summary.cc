#include <deal.II/base/mpi.h>

#include <bsmpm/io/run_summary.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace bsmpm
{
  namespace
  {
    std::string
    json_number(const double x)
    {
      if (!std::isfinite(x))
        return "null";
      char buffer[32];
      std::snprintf(buffer, sizeof(buffer), "%.17g", x);
      return buffer;
    }

    std::string
    json_string(const std::string &s)
    {
      std::string quoted = "\"";
      for (const char c : s)
        {
          if (c == '"' || c == '\\')
            quoted += '\\';
          quoted += c;
        }
      return quoted + "\"";
    }

    void
    write_map(std::ostream                        &out,
              const std::string                   &name,
              const std::map<std::string, double> &values,
              const bool                           last = false)
    {
      out << "  " << json_string(name) << ": {";
      bool first = true;
      for (const auto &[key, value] : values)
        {
          out << (first ? "\n" : ",\n") << "    " << json_string(key) << ": "
              << json_number(value);
          first = false;
        }
      out << (values.empty() ? "}" : "\n  }") << (last ? "\n" : ",\n");
    }
  } // namespace



  void
  RunSummary::write_json(std::ostream &out) const
  {
    out << "{\n";
    out << "  \"scene\": " << json_string(scene) << ",\n";
    out << "  \"status\": " << json_string(status) << ",\n";
    if (status == "failed")
      out << "  \"failed_step\": " << failed_step << ",\n"
          << "  \"error\": " << json_string(error) << ",\n";
    if (!limit_load_reason.empty())
      out << "  \"limit_load_reason\": " << json_string(limit_load_reason)
          << ",\n";
    if (!trials.empty())
      {
        out << "  \"strength_reduction_trials\": [";
        for (unsigned int i = 0; i < trials.size(); ++i)
          out << (i == 0 ? "\n" : ",\n")
              << "    {\"factor\": " << json_number(trials[i].factor)
              << ", \"collapsed\": " << (trials[i].collapsed ? "true" : "false")
              << ", \"load_factor\": " << json_number(trials[i].load_factor)
              << ", \"reason\": " << json_string(trials[i].reason)
              << ", \"directory\": " << json_string(trials[i].directory) << "}";
        out << "\n  ],\n";
      }
    out << "  \"n_cells\": " << n_cells << ",\n";
    out << "  \"n_dofs\": " << n_dofs << ",\n";
    out << "  \"n_material_points\": " << n_material_points << ",\n";
    out << "  \"n_tracking_points\": " << n_tracking_points << ",\n";
    out << "  \"load_steps\": " << load_steps << ",\n";
    out << "  \"steps\": [";
    for (unsigned int i = 0; i < steps.size(); ++i)
      {
        const Step &s = steps[i];
        out << (i == 0 ? "\n" : ",\n") << "    {\"step\": " << s.number
            << ", \"stage\": " << s.stage
            << ", \"load_factor\": " << json_number(s.load_factor)
            << ", \"solver\": " << json_string(s.solver)
            << ", \"iterations\": " << s.iterations
            << ", \"refinement_steps\": " << s.refinement_steps
            << ", \"relative_residual\": " << json_number(s.relative_residual)
            << ", \"active_cells\": " << s.n_active_cells;
        if (nonlinear)
          {
            out << ", \"increments\": " << s.increments
                << ", \"yielded_points\": " << s.n_yielded
                << ", \"newton_residuals\": [";
            for (unsigned int k = 0; k < s.newton_residuals.size(); ++k)
              out << (k ? ", " : "") << json_number(s.newton_residuals[k]);
            out << "], \"newton_corrections\": [";
            for (unsigned int k = 0; k < s.newton_corrections.size(); ++k)
              out << (k ? ", " : "") << json_number(s.newton_corrections[k]);
            out << "]";
            if (s.stalled_increments > 0)
              out << ", \"stalled_increments\": " << s.stalled_increments
                  << ", \"stalled_residual\": "
                  << json_number(s.stalled_residual);
          }
        out << ", \"quantities\": {";
        bool first = true;
        for (const auto &[key, value] : s.quantities)
          {
            out << (first ? "" : ", ") << json_string(key) << ": "
                << json_number(value);
            first = false;
          }
        out << "}}";
      }
    out << (steps.empty() ? "],\n" : "\n  ],\n");
    write_map(out, "errors", errors);
    write_map(out, "quantities", quantities);
    write_map(out, "timing", timing, true);
    out << "}\n";
  }



  void
  RunSummary::print_header(std::ostream &out) const
  {
    out << "scene              " << scene << '\n'
        << "cells              " << n_cells << '\n'
        << "dofs               " << n_dofs << '\n'
        << "material points    " << n_material_points << '\n';
    if (n_tracking_points > 0)
      out << "tracking points    " << n_tracking_points << '\n';
    out << "load steps         " << load_steps << '\n';
  }



  void
  RunSummary::print_step(std::ostream &out, const Step &s) const
  {
    if (s.number == 1)
      out << "\n step  load factor  active cells  solver              "
             "iterations  residual"
          << (nonlinear ? "  newton  yielded  |R_k|/|R_0|" : "") << '\n';
    std::ostringstream line;
    line << std::setw(5) << s.number << "  " << std::setw(11) << std::fixed
         << std::setprecision(6) << s.load_factor << "  " << std::setw(12)
         << s.n_active_cells << "  " << std::left << std::setw(18) << s.solver
         << std::right << "  " << std::setw(10)
         << (s.iterations > 0 ? std::to_string(s.iterations) : "-") << "  "
         << std::scientific << std::setprecision(1)
         << (s.relative_residual < 1e-12 ? 0. : s.relative_residual);
    if (nonlinear)
      {
        line << "  " << std::setw(6) << s.newton_residuals.size() - s.increments
             << "  " << std::setw(7) << s.n_yielded << " ";
        if (s.increments > 1)
          line << " (" << s.increments << " increments)";
        else
          for (const double r : s.newton_residuals)
            line << ' ' << std::setprecision(1) << r;
      }
    line << '\n';
    out << line.str() << std::flush;
  }



  void
  RunSummary::record_step(const Step                       &step,
                          const OutputWriter               &output,
                          const dealii::ConditionalOStream &pcout)
  {
    steps.push_back(step);
    if (pcout.is_active())
      print_step(pcout.get_stream(), step);
    output.write_root_file("summary.json",
                           [this](std::ostream &out) { write_json(out); });
  }



  void
  RunSummary::record_failure(const unsigned int  step,
                             const std::string  &message,
                             const OutputWriter &output)
  {
    status      = "failed";
    failed_step = step;
    error       = message;
    // The error being reported may be that the directory cannot be
    // written: then that error is the one to report, not this one's.
    try
      {
        output.write_root_file("summary.json",
                               [this](std::ostream &out) { write_json(out); });
      }
    catch (...)
      {}
  }



  void
  RunSummary::report_stalled_increments(const dealii::ConditionalOStream &pcout)
  {
    // Said at the end as well as in the table: the answer of such a run
    // holds to that residual, not to the Newton tolerance.
    unsigned int n       = 0;
    double       largest = 0;
    for (const auto &s : steps)
      {
        n += s.stalled_increments;
        largest = std::max(largest, s.stalled_residual);
      }
    if (n == 0)
      return;
    quantities["stalled_increments"]   = n;
    quantities["stalled_residual_max"] = largest;
    pcout << "\nNote: " << n
          << " load increment(s) did not converge in their last cut and took "
             "their best iterate (Nonlinear solver/Stall tolerance), the "
             "largest residual "
          << std::setprecision(2) << largest << std::setprecision(6)
          << " of the largest internal force: see the step table.\n";
  }



  void
  RunSummary::print_results(std::ostream &out) const
  {
    const auto print = [&out](const char *title, const auto &values) {
      if (values.empty())
        return;
      out << '\n' << title << '\n';
      // The names in a column as wide as the longest and a space (at
      // least 24), so that no name runs into its value.
      std::size_t width = 24;
      for (const auto &[key, value] : values)
        if (key.find("_at_") == std::string::npos)
          width = std::max(width, key.size() + 1);
      for (const auto &[key, value] : values)
        if (key.find("_at_") == std::string::npos) // places: in the JSON only
          out << "  " << std::left << std::setw(width) << key << std::right
              << std::scientific << std::setprecision(6) << value << '\n';
    };
    print("errors", errors);
    print("quantities", quantities);
    out << std::defaultfloat;
  }


  void
  RunSummary::add_timing(const dealii::TimerOutput &timer,
                         const double               total_seconds)
  {
    for (const auto &[name, seconds] :
         timer.get_summary_data(dealii::TimerOutput::total_wall_time))
      timing[name] += seconds; // a resumed run adds its part
    timing["total"] += total_seconds;
  }



  void
  RunSummary::finish(const Verification               &verification,
                     const OutputWriter               &output,
                     const dealii::TimerOutput        &timer,
                     const double                      total_seconds,
                     const dealii::ConditionalOStream &pcout,
                     const MPI_Comm                    communicator)
  {
    add_timing(timer, total_seconds);

    if (pcout.is_active())
      print_results(pcout.get_stream());

    std::map<std::string, double> checked = errors;
    checked.insert(quantities.begin(), quantities.end());
    std::ostringstream verification_log;
    const auto         failed = verification.check(checked, verification_log);
    pcout << verification_log.str();

    // The summary is the run's record for scripts: written even when the
    // ParaView series are off.
    status = "completed";
    output.write_root_file("summary.json",
                           [this](std::ostream &out) { write_json(out); });

    if (output.print_timing())
      {
        if (dealii::Utilities::MPI::n_mpi_processes(communicator) == 1)
          timer.print_summary();
        else
          timer.print_wall_time_statistics(communicator);
      }

    std::string names;
    for (const auto &name : failed)
      names += (names.empty() ? "" : ", ") + name;
    AssertThrow(failed.empty(),
                dealii::ExcMessage("Verification failed for: " + names + "."));
  }
} // namespace bsmpm
