#ifndef bsmpm_contact_law_h
#define bsmpm_contact_law_h

namespace bsmpm
{
  /**
   * The contact law at one place where a boundary curve meets a rigid body
   * (doc/contact.md): the pressure and the tangential traction as
   * functions of the gap, the slip of the increment and what the last
   * increment left there, with their derivatives. It knows no grid, curve
   * or body: the contact terms (ContactTerms) apply it to a piece's mean
   * gap and slip (one pressure per cell) or at each Gauss point (pressures
   * at the grid lines), and a law of another shape changes here only.
   *
   * Normal: the penalty eps on the gap g, shifted by the augmented
   * Lagrangian's multiplier lambda (zero for the plain penalty),
   *
   *   p = max(0, lambda - eps g)   while g <= lambda / eps (+ round-off).
   *
   * Tangential: Coulomb's return map on the slip s of the increment
   * relative to the body, from the traction t_prev of the last increment,
   * regularized by the same penalty while sticking,
   *
   *   t_trial = t_prev - eps s,
   *   t_T     = t_trial                  if |t_trial| <= mu p (stick),
   *           = mu p sign(t_trial)       otherwise (slip);
   *
   * a rough surface has mu = rough_friction_coefficient (10: it slides
   * only where it barely touches, and its traction stays continuous as a
   * place starts or stops touching) and the smoothed law
   * t_T = mu p tanh(t_trial / (mu p)), without the kink between sticking
   * and sliding; a smooth one has t_T = 0.
   * The traction on the curve is p n + t_T t, n the rigid outline's
   * outward normal and t = (-n_y, n_x); s is the slip along t.
   */
  class ContactLaw
  {
  public:
    /** How the normal condition is imposed ('Contact/Method'). */
    enum class Method
    {
      penalty,             ///< p = max(0, -eps g)
      augmented_lagrangian ///< p = max(0, lambda - eps g), lambda updated
    };

    /** The friction coefficient of a rough surface: no sliding where it
     * presses, a bound that keeps the traction continuous where a place
     * starts or stops touching. */
    static constexpr double rough_friction_coefficient = 10;

    /** How the rigid surface resists sliding ('Rigid body N/Friction'). */
    enum class Friction
    {
      smooth,     ///< no tangential traction
      frictional, ///< Coulomb: |t_T| <= mu p_N, sliding beyond
      rough       ///< Coulomb with mu = rough_friction_coefficient, smoothed
    };

    /** What the last increment (and, for the multiplier, the last
     * augmentation) left at the place. */
    struct State
    {
      /** The augmented Lagrangian's lambda (ignored by the penalty). */
      double multiplier = 0;
      /** t_prev: the tangential traction of the last increment. */
      double previous_tangential = 0;
    };

    /** The traction at one gap and slip, and its derivatives. */
    struct Traction
    {
      /** Whether the place takes part: its gap is below lambda / eps (or
       * touches within round-off, with p = 0). Where not, everything
       * below is zero. */
      bool   active     = false;
      bool   sliding    = false;
      double pressure   = 0; ///< p >= 0
      double tangential = 0; ///< t_T
      /** dp/dg: -eps wherever active (also where p is zero within
       * round-off). */
      double d_pressure_d_gap = 0;
      /** dt_T/ds: -eps while sticking, zero while sliding (Coulomb; the
       * smoothed rough law has all three derivatives). */
      double d_tangential_d_slip = 0;
      /** dt_T/dt_prev: one while sticking, zero while sliding. */
      double d_tangential_d_previous = 0;
      /** dt_T/dp: mu sign(t_trial) while sliding, zero while sticking. */
      double d_tangential_d_pressure = 0;

      /** dt_T/dg, through the pressure: nonzero only while sliding
       * (Coulomb) or wherever a rough surface touches (smoothed). */
      double
      d_tangential_d_gap() const
      {
        return d_tangential_d_pressure * d_pressure_d_gap;
      }

      /** Whether the place's tangent is symmetric: dt_T/dg is zero (the
       * normal gap does not drive the tangential traction). */
      bool
      symmetric() const
      {
        return d_tangential_d_pressure == 0.;
      }
    };

    /**
     * @p penalty: eps. @p friction_coefficient: mu (used by frictional
     * surfaces only). @p touching_tolerance: a gap up to which a place
     * still counts as touching with zero pressure, so that a body resting
     * on a rigid one is held from the first Newton iteration.
     */
    ContactLaw(const Method   method,
               const double   penalty,
               const Friction friction,
               const double   friction_coefficient,
               const double   touching_tolerance);

    /** The traction at gap @p gap and slip @p slip of the increment. */
    Traction
    evaluate(const double gap, const double slip, const State &state) const;

    /** t_prev - eps s, the elastic predictor of the return map. The
     * contact terms also take it of the normal components, where the
     * outline turns and t turns with n. */
    double
    trial_traction(const double previous, const double slip) const
    {
      return previous - eps * slip;
    }

    double
    penalty() const
    {
      return eps;
    }

    /** Whether the surface takes a tangential traction at all. */
    bool
    has_friction() const
    {
      return friction != Friction::smooth;
    }

  private:
    Method   method;
    double   eps;
    Friction friction;
    double   mu;
    double   touching_tolerance;
  };
} // namespace bsmpm

#endif
