#include <deal.II/base/utilities.h>

#include <bsmpm/verification/verification.h>

#include <cmath>
#include <iomanip>
#include <sstream>

namespace bsmpm
{
  void
  Verification::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Verification");
    prm.declare_entry("Bounds",
                      "",
                      Patterns::Anything(),
                      "Comma-separated bounds on errors and quantities that "
                      "the run must meet, e.g. 'R_sigma_yy <= 1e-14, "
                      "tip_deflection >= 2.5'. A failed bound makes the run "
                      "exit with an error after writing its output.");
    prm.leave_subsection();
  }



  void
  Verification::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Verification");
    const std::string text = prm.get("Bounds");
    prm.leave_subsection();

    bounds.clear();
    for (const auto &item : Utilities::split_string_list(text, ','))
      {
        if (item.empty())
          continue;
        const bool        upper = item.find("<=") != std::string::npos;
        const std::size_t pos   = item.find(upper ? "<=" : ">=");
        AssertThrow(pos != std::string::npos,
                    ExcMessage("Verification: bound '" + item +
                               "' must read 'name <= value' or "
                               "'name >= value'."));
        Bound bound;
        bound.name  = Utilities::trim(item.substr(0, pos));
        bound.upper = upper;
        try
          {
            bound.value = Utilities::string_to_double(
              Utilities::trim(item.substr(pos + 2)));
          }
        catch (...)
          {
            AssertThrow(false,
                        ExcMessage("Verification: bound '" + item +
                                   "' has no number after the operator."));
          }
        // A bound of inf always holds and one of NaN never does.
        AssertThrow(std::isfinite(bound.value),
                    ExcMessage("Verification: bound '" + item +
                               "' is not a finite number."));
        bounds.push_back(bound);
      }
  }



  std::vector<std::string>
  Verification::check(const std::map<std::string, double> &values,
                      std::ostream                        &out) const
  {
    std::vector<std::string> failed;
    if (!bounds.empty())
      out << "\nverification\n";
    for (const auto &b : bounds)
      {
        std::ostringstream line;
        line << "  " << b.name << ' ' << (b.upper ? "<=" : ">=") << ' '
             << std::scientific << std::setprecision(2) << b.value << ": ";
        const auto it = values.find(b.name);
        if (it == values.end())
          {
            line << "not computed by this run";
            failed.push_back(b.name);
          }
        else
          {
            const bool ok =
              std::isfinite(it->second) &&
              (b.upper ? it->second <= b.value : it->second >= b.value);
            line << (ok ? "passed" : "FAILED");
            if (!ok)
              {
                std::ostringstream value;
                value << std::scientific << std::setprecision(6) << it->second;
                line << " (value " << value.str() << ")";
                failed.push_back(b.name);
              }
          }
        out << line.str() << '\n';
      }
    return failed;
  }
} // namespace bsmpm
