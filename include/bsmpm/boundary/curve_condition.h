#ifndef bsmpm_curve_condition_h
#define bsmpm_curve_condition_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <bsmpm/base/load_level.h>

#include <memory>
#include <string>

namespace bsmpm
{
  using namespace dealii;

  /**
   * What acts on a stretch of a boundary curve: nothing, a traction (paper
   * Sec. 3.4) or a support (paper Sec. 3.5).
   *
   * In a parameter file a condition reads "[i-j:] kind [arguments]", where
   * i-j restricts it to the segments between points i and j of the chain
   * (points numbered from 0 along the chain's direction; the whole chain if
   * absent). On an open chain of N points 0 <= i < j <= N - 1; on a closed
   * one i, j lie in 0 .. N - 1 (j may also be N, point 0 after a full turn)
   * and i != j, and a range with i > j wraps round: segments i .. N - 1 and
   * 0 .. j - 1 (check_range()). The kinds:
   * - free
   * - pressure <p>: p in Pa on the current curve, along the inward normal
   *   (a follower load); a number or an expression of t;
   * - traction <tx>; <ty>: a traction vector in Pa, as expressions of x, y
   *   and t;
   * - exact traction: sigma(x) n from the scene's exact solution;
   * - fixed: u = 0; roller: u . n = 0 (n the normal of the current curve);
   * - displacement exact: u = u_exact(x); displacement <ux>; <uy>: u given
   *   as expressions of x, y and t;
   * - normal displacement <un>: u . n = un (an expression of x, y, t) with n
   *   the outward normal of the body on the current curve, the tangential
   *   component free (a smooth rigid footing pushed into the body has
   *   un < 0); normal displacement exact: u . n = u_exact(x) . n.
   * Loads and prescribed displacements are scaled by the load factor of the
   * step, t, except a load whose expression uses t: that expression is the
   * load at t itself (as a rigid body's Displacement and Force are), so
   * that loads of a staged scene can come on, stay and go in different
   * stages (LoadStages); a prescribed displacement is imposed by its
   * increment over each load increment, so one that uses t also moves only
   * where it changes. Supports are imposed by the curve's Dirichlet method
   * (implicit boundary method or Nitsche's method).
   */
  struct CurveCondition
  {
    enum class Kind
    {
      free,
      pressure,
      traction,
      exact_traction,
      fixed,
      roller,
      displacement,
      normal_displacement
    };

    Kind         kind          = Kind::free;
    unsigned int first_segment = 0;
    unsigned int end_segment   = numbers::invalid_unsigned_int;
    /** The pressure of "pressure <p>" given as a number. */
    double pressure = 0;
    /** Traction of "traction", displacement of "displacement <ux>; <uy>"
     * (two components), normal displacement of "normal displacement <un>"
     * or pressure of "pressure <p>" given as an expression of t (one
     * component); nullptr for "displacement exact", "normal displacement
     * exact" and a pressure given as a number. Expressions of x, y and the
     * load factor t, time dependent in deal.II's sense (t is the parser's
     * time). */
    std::shared_ptr<FunctionParser<2>> function;
    /** Whether the load's expression uses t: it is then the load at the
     * load factor t, not a load to be multiplied by it. */
    bool expression_of_t = false;
    /** The parameter that gave the condition, for messages. */
    std::string where;

    /** The value of the function at @p x. If it is not finite and
     * @p problem is empty, @p problem gets a message that names the
     * parameter and the point (see ParameterTools::throw_if_any()). */
    Tensor<1, 2>
    function_value(const Point<2> &x, std::string &problem) const;

    /** As function_value(), for the one component of "normal displacement
     * <un>". */
    double
    scalar_function_value(const Point<2> &x, std::string &problem) const;

    /**
     * The traction of a load ("pressure", "traction") at the point @p x of
     * the curve, whose outward normal is @p normal there, at the load
     * factor @p t: t times the given load, or the given expression of t at
     * t (see #expression_of_t). Problems as for function_value().
     */
    Tensor<1, 2>
    load_traction(const Point<2>     &x,
                  const Tensor<1, 2> &normal,
                  const double        t,
                  std::string        &problem) const;

    /** The pressure of a "pressure" condition at the load factor @p t, by
     * the rule of load_traction(). */
    double
    pressure_at(const double t) const;

    /**
     * The change of the expression of "displacement <ux>; <uy>" at @p x
     * over @p increment: f(x, to) - f(x, from) for an expression of t,
     * else (to - from) f(x). Problems as for function_value().
     */
    Tensor<1, 2>
    displacement_increment(const Point<2>      &x,
                           const LoadIncrement &increment,
                           std::string         &problem) const;

    /** As displacement_increment(), for the one component of "normal
     * displacement <un>". */
    double
    normal_displacement_increment(const Point<2>      &x,
                                  const LoadIncrement &increment,
                                  std::string         &problem) const;

    /** Parses "[i-j:] kind [arguments]"; @p where names the parameter. */
    static CurveCondition
    parse(const std::string &text, const std::string &where);

    /** Whether the condition has a range "i-j:" (without one it covers
     * the whole chain). */
    bool
    has_range() const
    {
      return end_segment != numbers::invalid_unsigned_int;
    }

    /**
     * Refuses a range that does not fit the chain of @p n_points points
     * (@p closed or not) of the curve @p curve_name: an index beyond the
     * chain, or, on an open chain, a reversed range (j < i), which would
     * otherwise be taken as the range that wraps round a closed chain. The
     * message names the parameter, the range and the valid forms.
     */
    void
    check_range(const unsigned int n_points,
                const bool         closed,
                const std::string &curve_name) const;

    /** Whether the condition covers segment @p k of a chain of
     * @p n_segments segments (ranges may wrap round a closed chain). */
    bool
    covers(const unsigned int k, const unsigned int n_segments) const;

    bool
    is_load() const
    {
      return kind == Kind::pressure || kind == Kind::traction ||
             kind == Kind::exact_traction;
    }

    bool
    is_support() const
    {
      return kind == Kind::fixed || kind == Kind::roller ||
             kind == Kind::displacement || kind == Kind::normal_displacement;
    }

    /** Whether the support holds the normal component only (a roller or a
     * prescribed normal displacement). */
    bool
    holds_normal_component_only() const
    {
      return kind == Kind::roller || kind == Kind::normal_displacement;
    }

    /** Whether the support prescribes a displacement (both components or
     * the normal one). */
    bool
    prescribes_displacement() const
    {
      return kind == Kind::displacement || kind == Kind::normal_displacement;
    }

    /** Whether the support holds both components (not a roller, not a
     * prescribed normal displacement). */
    bool
    holds_both_components() const
    {
      return kind == Kind::fixed || kind == Kind::displacement;
    }

    /** Name of the kind, as in the parameter file. */
    std::string
    kind_name() const;

  private:
    /** The value @p value() gives at the load factor @p t: for an
     * expression of t evaluated there, else t times the given value. */
    template <typename Value>
    auto
    value_at(const double t, const Value &value) const
    {
      if (!expression_of_t)
        return t * value();
      function->set_time(t);
      return value();
    }

    /** The change of the value @p value() gives over @p increment: of the
     * expression of t between its ends, else its growth times the given
     * value. */
    template <typename Value>
    auto
    change_over(const LoadIncrement &increment, const Value &value) const
    {
      if (!expression_of_t)
        return increment.share() * value();
      function->set_time(increment.to);
      const auto to = value();
      function->set_time(increment.from);
      return to - value();
    }
  };
} // namespace bsmpm

#endif
