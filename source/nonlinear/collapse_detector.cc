#include <bsmpm/nonlinear/collapse_detector.h>

#include <cmath>
#include <sstream>

namespace bsmpm
{
  void
  CollapseDetector::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Limit load");
    prm.declare_entry(
      "Detect collapse",
      "auto",
      Patterns::Selection("auto|on|off"),
      "Whether the run stops at the limit load of a nonlinear material "
      "(doc/limit-loads.md): when a load increment does not converge even "
      "after the allowed step cuts, or converges with a flexibility ratio "
      "above 'Flexibility ratio'. The run then ends normally (exit code 0) "
      "and summary.json gives limit_load_factor, its bracket and the reason. "
      "'auto': on for a material that yields (not for an elastic one, "
      "also in finite strain: a step it cannot take is an error) unless a "
      "boundary curve "
      "prescribes a displacement (a displacement-controlled run follows the "
      "mechanism, and a failed step is an error).");
    prm.declare_entry(
      "Flexibility ratio",
      "20",
      Patterns::Double(1.),
      "Collapse is declared when a converged load increment moves the body "
      "more than this many times as far per unit load factor as the first "
      "increment: (|du|_max / d lambda) / (|du_1|_max / d lambda_1), du the "
      "nodal displacement increment (the inverse of Bergan's current "
      "stiffness parameter). 20 means a tangent stiffness of 5 % of the "
      "first increment's.");
    prm.leave_subsection();
  }



  void
  CollapseDetector::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Limit load");
    mode              = prm.get("Detect collapse");
    flexibility_limit = prm.get_double("Flexibility ratio");
    prm.leave_subsection();
  }



  void
  CollapseDetector::initialize(const bool         nonlinear,
                               const bool         prescribes_displacement,
                               const std::string &stage_mode,
                               const double       stage_start)
  {
    offset               = stage_start;
    const std::string &m = stage_mode == "default" ? mode : stage_mode;
    is_active =
      m == "on" || (m == "auto" && nonlinear && !prescribes_displacement);
    reference     = 0;
    last_ratio    = 0;
    lower         = 0;
    upper         = 0;
    has_collapsed = false;
    why_collapsed.clear();
  }



  bool
  CollapseDetector::converged_increment(const unsigned int step,
                                        const double       path_lambda,
                                        const double       delta,
                                        const double       displacement)
  {
    // The stage's own load factor.
    const double lambda = path_lambda - offset;
    if (!is_active || has_collapsed || !(delta > 0))
      return has_collapsed;
    const double flexibility = displacement / delta;
    if (reference == 0)
      {
        // The first increment that moves the body sets the scale.
        reference = flexibility;
        lower     = lambda + delta;
        return false;
      }
    last_ratio = flexibility / reference;
    if (last_ratio > flexibility_limit || !std::isfinite(last_ratio))
      {
        has_collapsed = true;
        upper         = lambda + delta;
        std::ostringstream text;
        text << "load step " << step << ": the increment from load factor "
             << lambda << " to " << lambda + delta << " moved the body "
             << last_ratio << " times as far per unit load as the first "
             << "increment (flexibility ratio, limit " << flexibility_limit
             << "): a mechanism";
        why_collapsed = text.str();
        return true;
      }
    lower = lambda + delta;
    return false;
  }



  void
  CollapseDetector::failed_increment(const unsigned int step,
                                     const double       path_lambda,
                                     const double       delta,
                                     const std::string &why)
  {
    const double lambda = path_lambda - offset;
    has_collapsed       = true;
    lower               = lambda;
    upper               = lambda + delta;
    std::ostringstream text;
    text << "load step " << step
         << ": the Newton iterations of the load increment from load factor "
         << lambda << " by " << delta
         << " did not converge after every allowed step cut (" << why << ")";
    why_collapsed = text.str();
  }



  void
  CollapseDetector::record(std::map<std::string, double> &quantities) const
  {
    if (!is_active)
      return;
    quantities["flexibility_ratio"] = last_ratio;
    if (has_collapsed)
      {
        quantities["limit_load_factor"] = lower;
        quantities["limit_load_lower"]  = lower;
        quantities["limit_load_upper"]  = upper;
      }
  }
} // namespace bsmpm
