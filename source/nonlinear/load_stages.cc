#include <deal.II/base/utilities.h>

#include <bsmpm/base/parameter_tools.h>
#include <bsmpm/nonlinear/load_stages.h>

#include <algorithm>
#include <cmath>

namespace bsmpm
{
  namespace
  {
    std::string
    stage_section(const unsigned int k)
    {
      return "Stage " + std::to_string(k);
    }
  } // namespace



  void
  LoadStages::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stages");
    prm.declare_entry(
      "Number of stages",
      "1",
      Patterns::Integer(1, max_stages),
      "How many stages the analysis runs, one after the other, each from "
      "the state the one before left (doc/stages.md). 1: the short form, "
      "every load ramped together over Loading/Load steps, and the 'Stage' "
      "subsections unused. At most 10.");
    for (unsigned int k = 1; k <= max_stages; ++k)
      {
        prm.enter_subsection(stage_section(k));
        prm.declare_entry("Name",
                          "",
                          Patterns::Anything(),
                          "A name for the step table and summary.json; "
                          "empty: 'stage k'.");
        prm.declare_entry("Load steps",
                          "10",
                          Patterns::Integer(1, 100000),
                          "Equal steps from the multipliers at the end of "
                          "the stage before to those of this stage.");
        prm.declare_entry(
          "Gravity factor",
          "1",
          Patterns::Double(),
          "Multiplier of Loading/Gravity at the end of the stage, reached "
          "linearly over its load steps from that at the end of the stage "
          "before (0 before stage 1, or 1 with an initial stress).");
        prm.declare_entry(
          "Load factor",
          "1",
          Patterns::Double(),
          "Multiplier at the end of the stage of the curves' tractions, "
          "pressures and prescribed displacements, and the value of t in "
          "the rigid bodies' Displacement and Force, reached linearly over "
          "its load steps from that at the end of the stage before (0 "
          "before stage 1). A stage that only brings the ground's weight "
          "has Load factor 0; a stage that keeps a load where the stage "
          "before left it repeats its factor.");
        prm.declare_entry(
          "Reset displacements",
          "false",
          Patterns::Bool(),
          "Whether the displacements of the points (output, probe, "
          "max_displacement) restart from zero at the start of the stage, "
          "their stresses and state kept: the settlement of a footing "
          "without that of the ground under its own weight.");
        prm.declare_entry(
          "Excavation",
          "",
          Patterns::Anything(),
          "A polygon 'x0, y0; x1, y1; ...' in m whose material the stage "
          "removes at its start: the points inside leave the body, and the "
          "forces they exerted on the rest are released over the stage's "
          "load steps. Empty: none. The cut's face joins a closed curve of "
          "tracking points round the body (in finite strain the one added "
          "round the body region), and a region inside the body (a "
          "tunnel) gets a closed curve of its own; other curves and the "
          "probe must stay more than a cell away from the region.");
        prm.declare_entry(
          "Excavation edge",
          "straight",
          Patterns::Selection("straight|B-spline"),
          "How the points of Excavation bound the region: straight, a "
          "polygon with them as its corners; B-spline, the closed cubic "
          "B-spline through them (a round pit or a tunnel's outline), "
          "whose arc becomes the cut's face without corners.");
        prm.declare_entry(
          "Construction",
          "",
          Patterns::Anything(),
          "Names of further bodies ('Body k/Name', separated by commas) "
          "that the stage builds: their points appear at "
          "the stage's start where their regions say, without stress, and "
          "their weight grows with the stage's load steps. Empty: none. A "
          "body that no stage builds is there from the start.");
        prm.declare_entry(
          "Detect collapse",
          "default",
          Patterns::Selection("default|on|off"),
          "Whether a collapse in this stage ends the run at its limit load "
          "(doc/limit-loads.md): default follows Limit load/Detect "
          "collapse. Each stage measures its flexibility against its own "
          "first increment.");
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }



  void
  LoadStages::parse_parameters(ParameterHandler &prm,
                               const bool        gravity_at_start)
  {
    start.gravity = gravity_at_start ? 1. : 0.;
    start.loads   = 0;
    stages.clear();
    prm.enter_subsection("Stages");
    const unsigned int n = prm.get_integer("Number of stages");
    if (n == 1)
      {
        Stage only;
        prm.leave_subsection();
        prm.enter_subsection("Loading");
        only.load_steps = prm.get_integer("Load steps");
        prm.leave_subsection();
        only.end = {1., 1.};
        stages.push_back(only);
        return;
      }
    for (unsigned int k = 1; k <= n; ++k)
      {
        prm.enter_subsection(stage_section(k));
        Stage stage;
        stage.name                = prm.get("Name");
        stage.load_steps          = prm.get_integer("Load steps");
        stage.end.gravity         = prm.get_double("Gravity factor");
        stage.end.loads           = prm.get_double("Load factor");
        stage.reset_displacements = prm.get_bool("Reset displacements");
        stage.detect_collapse     = prm.get("Detect collapse");
        stage.excavation          = ParameterTools::parse_points(
          prm.get("Excavation"), "Stages/" + stage_section(k) + "/Excavation");
        stage.excavation_spline = prm.get("Excavation edge") == "B-spline";
        for (const std::string &name :
             Utilities::split_string_list(prm.get("Construction")))
          if (!name.empty())
            stage.construction.push_back(name);
        stages.push_back(stage);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }



  std::string
  LoadStages::stage_name(const unsigned int k) const
  {
    return stage(k).name.empty() ? "stage " + std::to_string(k) : stage(k).name;
  }



  unsigned int
  LoadStages::n_load_steps() const
  {
    unsigned int n = 0;
    for (const Stage &s : stages)
      n += s.load_steps;
    return n;
  }



  std::set<unsigned int>
  LoadStages::stage_ends() const
  {
    std::set<unsigned int> ends;
    unsigned int           n = 0;
    for (unsigned int k = 0; k + 1 < stages.size(); ++k)
      ends.insert(n += stages[k].load_steps);
    return ends;
  }



  LoadStages::Step
  LoadStages::step(const unsigned int n) const
  {
    Step         result;
    unsigned int before = 0;
    for (unsigned int k = 1; k <= stages.size(); ++k)
      {
        const unsigned int m = stages[k - 1].load_steps;
        if (n <= before + m || k == stages.size())
          {
            const unsigned int i  = n - before;
            result.stage          = k;
            result.from           = (k - 1.) + (i - 1.) / m;
            result.to             = (k - 1.) + double(i) / m;
            result.first_of_stage = i == 1;
            return result;
          }
        before += m;
      }
    return result;
  }



  LoadLevel
  LoadStages::level(const double tau) const
  {
    // The stage whose interval holds tau (its end belongs to it, so that
    // the last step of a stage sees that stage's end values).
    const unsigned int k =
      std::min<unsigned int>(stages.size(),
                             std::max(1., std::ceil(tau - 1e-12 * (1 + tau))));
    const LoadLevel &before = k == 1 ? start : stages[k - 2].end;
    const LoadLevel &after  = stages[k - 1].end;
    const double     s      = fraction(tau, k);
    return {before.gravity + s * (after.gravity - before.gravity),
            before.loads + s * (after.loads - before.loads),
            stages[k - 1].excavation.empty() ? 0. : 1. - s};
  }
} // namespace bsmpm
