#ifndef bsmpm_collapse_detector_h
#define bsmpm_collapse_detector_h

#include <deal.II/base/parameter_handler.h>

#include <boost/serialization/string.hpp>

#include <map>
#include <string>

namespace bsmpm
{
  using namespace dealii;

  /**
   * Decides when a load-controlled run of a nonlinear material has reached
   * its limit load (section "Limit load", doc/limit-loads.md).
   *
   * Under a prescribed load a perfectly plastic body collapses at its limit
   * load: the tangent stiffness falls to zero and the displacement grows
   * without bound. In the discrete scene that shows in one of two ways:
   *
   * - the Newton iterations of a load increment do not converge even after
   *   the increment was cut 'Nonlinear solver/Maximum step cuts' times;
   * - they converge, but the increment moves the body far more per unit of
   *   load than before: the moved points stiffen the model again (their new
   *   quadrature), so that Newton can follow a mechanism through a step.
   *
   * The second is measured by the flexibility of every converged increment,
   * the largest nodal displacement of the increment divided by its load
   * increment, |du|_max / d(lambda), relative to that of the first
   * increment (elastic, or nearly: a load step must be small enough for
   * that). This ratio is the inverse of Bergan's current stiffness
   * parameter (Bergan et al. 1978, "Solution techniques for non-linear
   * finite element problems", IJNME 12, 1677-1696). Collapse is declared
   * when it exceeds 'Flexibility ratio'.
   *
   * The limit load factor reported is the last load factor that converged
   * with a ratio below the limit, with the bracket [that factor, the load
   * factor of the failed or too flexible increment].
   */
  class CollapseDetector
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Switches the detector on or off for a scene: 'auto' is on for a
     * @p nonlinear material when no curve @p prescribes_displacement (then
     * the load factor scales the loads, and a collapse is a limit load;
     * under a prescribed displacement the run follows the mechanism).
     * A stage's @p stage_mode "on" or "off" overrides the scene's; its
     * "default" keeps it. Every call starts a new reference (the first
     * increment after it). The load factors the detector reports are
     * those of the stage that starts at the load path's @p stage_start
     * (LoadStages): the path's lambda minus it.
     */
    void
    initialize(const bool         nonlinear,
               const bool         prescribes_displacement,
               const std::string &stage_mode  = "default",
               const double       stage_start = 0);

    bool
    active() const
    {
      return is_active;
    }

    /**
     * A load increment from @p lambda to @p lambda + @p delta converged in
     * load step @p step with the largest nodal displacement increment
     * @p displacement. Returns whether this declares collapse.
     */
    bool
    converged_increment(const unsigned int step,
                        const double       lambda,
                        const double       delta,
                        const double       displacement);

    /** The Newton iterations of the load increment from @p lambda by
     * @p delta (already cut as far as allowed) failed in load step
     * @p step, because of @p why: declares collapse. */
    void
    failed_increment(const unsigned int step,
                     const double       lambda,
                     const double       delta,
                     const std::string &why);

    bool
    collapsed() const
    {
      return has_collapsed;
    }

    /** The last load factor reached without collapse. */
    double
    limit_load_factor() const
    {
      return lower;
    }

    /** Why collapse was declared, for people and summary.json. */
    const std::string &
    reason() const
    {
      return why_collapsed;
    }

    /**
     * The figures of the detector as quantities: 'flexibility_ratio' of
     * the last increment, and after a collapse 'limit_load_factor',
     * 'limit_load_lower' and 'limit_load_upper' (the bracket).
     */
    void
    record(std::map<std::string, double> &quantities) const;

    /** The flexibility ratio beyond which collapse is declared. */
    double
    ratio_limit() const
    {
      return flexibility_limit;
    }

    /** What the run has seen so far (its reference flexibility, the
     * bracket of the limit load, the stage it watches), for checkpoints. */
    template <class Archive>
    void
    serialize(Archive &archive, const unsigned int)
    {
      archive &reference &last_ratio &lower &upper &has_collapsed &why_collapsed
        &offset &is_active;
    }

  private:
    std::string mode = "auto";
    /** The load path's lambda where the stage began (initialize()). */
    double offset            = 0;
    double flexibility_limit = 20;
    bool   is_active         = false;

    /** |du|_max / d(lambda) of the first increment that moved the body. */
    double reference = 0;
    /** The ratio of the last converged increment to the reference. */
    double last_ratio = 0;
    /** Load factor reached without collapse. */
    double lower = 0;
    /** Load factor of the increment that collapsed. */
    double      upper         = 0;
    bool        has_collapsed = false;
    std::string why_collapsed;
  };
} // namespace bsmpm

#endif
