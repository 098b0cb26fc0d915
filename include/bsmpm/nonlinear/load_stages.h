#ifndef bsmpm_load_stages_h
#define bsmpm_load_stages_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <bsmpm/base/load_level.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

namespace bsmpm
{
  using namespace dealii;

  /**
   * The stages of an analysis (section "Stages", doc/stages.md): a sequence
   * of load paths, each with its own load steps, that start from the state
   * the one before left. Stage k says the multipliers of the gravity and of
   * the other loads at its end; during the stage they go linearly from their
   * values at the end of stage k - 1 (0, or a gravity of 1 where the ground
   * starts with its initial stress) to those. The ground's weight first,
   * then the works: stage 1 with Gravity factor 1 and Load factor 0, stage 2
   * with both 1.
   *
   * One stage is the short form: Loading/Load steps, both multipliers equal
   * to the load factor t of the step (t = n / Load steps).
   *
   * The load path is parametrised by tau: stage k covers tau in [k - 1, k],
   * its own fraction s = tau - (k - 1). The load stepper, the collapse
   * detector and the Newton solver work in tau; level() turns it into the
   * multipliers, and the step table, summary.json and the output say the
   * stage and s.
   */
  class LoadStages
  {
  public:
    static constexpr unsigned int max_stages = 10;

    /** One stage as the parameters give it. */
    struct Stage
    {
      std::string  name;
      unsigned int load_steps = 1;
      /** Multipliers at the stage's end. */
      LoadLevel end;
      /** Whether the points' displacements restart from zero (their stress
       * and state kept) at the stage's start. */
      bool reset_displacements = false;
      /** "default" (Limit load/Detect collapse), "on" or "off". */
      std::string detect_collapse = "default";
      /** The polygon whose material the stage removes (Excavation); empty
       * for none. */
      std::vector<Point<2>> excavation;
      /** Whether the excavated region is bounded by the closed B-spline
       * through the points of #excavation, not the polygon. */
      bool excavation_spline = false;
      /** The names of the bodies that the stage builds (Bodies). */
      std::vector<std::string> construction;
    };

    /** One load step of the whole run. */
    struct Step
    {
      /** The stage, from 1. */
      unsigned int stage = 1;
      /** The path parameter at the step's start and end. */
      double from = 0;
      double to   = 0;
      /** Whether it is the stage's first step. */
      bool first_of_stage = false;
    };

    static void
    declare_parameters(ParameterHandler &prm);

    /** Reads the stages (and Loading/Load steps for one). With
     * @p gravity_at_start the body force is on from the start (the ground
     * starts with its initial stress): the gravity multiplier is 1 at
     * tau = 0, and 1 throughout in the short form. */
    void
    parse_parameters(ParameterHandler &prm, const bool gravity_at_start);

    unsigned int
    n_stages() const
    {
      return stages.size();
    }

    /** Whether the scene has more than one stage. */
    bool
    staged() const
    {
      return stages.size() > 1;
    }

    /** How the multipliers grow along stage @p k, per unit of the load
     * path: its end values less those it starts from (release: 0). What
     * displacement control scales in the stage it controls, the last. */
    LoadLevel
    slope(const unsigned int k) const
    {
      const LoadLevel &before = k == 1 ? start : stages[k - 2].end;
      const LoadLevel &after  = stages[k - 1].end;
      return {after.gravity - before.gravity, after.loads - before.loads, 0.};
    }

    const Stage &
    stage(const unsigned int k) const
    {
      return stages[k - 1];
    }

    /** The stage's name, or "stage k" if it has none. */
    std::string
    stage_name(const unsigned int k) const;

    /** Load steps of all stages. */
    unsigned int
    n_load_steps() const;

    /** The last step of every stage but the last (none in the short
     * form). */
    std::set<unsigned int>
    stage_ends() const;

    /** Load step @p n (from 1) of the whole run. */
    Step
    step(const unsigned int n) const;

    /** The multipliers at path parameter @p tau. Beyond the last stage's
     * end (displacement control) they go on along its line. */
    LoadLevel
    level(const double tau) const;

    /** The share of its weight that a body built in stage @p k (1: there
     * from the start, at once) carries at @p tau: 0 before the stage, its
     * fraction during it, 1 after. */
    static double
    weight_share(const double tau, const unsigned int k)
    {
      return k == 1 ? 1. : std::clamp(fraction(tau, k), 0., 1.);
    }

    /** The fraction of stage @p k reached at @p tau. */
    static double
    fraction(const double tau, const unsigned int k)
    {
      return tau - (k - 1.);
    }

  private:
    std::vector<Stage> stages;
    /** The multipliers at tau = 0. */
    LoadLevel start;
  };
} // namespace bsmpm

#endif
