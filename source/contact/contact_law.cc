#include <bsmpm/contact/contact_law.h>

#include <algorithm>
#include <cmath>

namespace bsmpm
{
  ContactLaw::ContactLaw(const Method   method,
                         const double   penalty,
                         const Friction friction,
                         const double   friction_coefficient,
                         const double   touching_tolerance)
    : method(method)
    , eps(penalty)
    , friction(friction)
    , mu(friction_coefficient)
    , touching_tolerance(touching_tolerance)
  {}



  ContactLaw::Traction
  ContactLaw::evaluate(const double gap,
                       const double slip,
                       const State &state) const
  {
    Traction traction;
    // The augmented Lagrangian's pressure max(0, lambda - eps g) acts
    // while the gap is below lambda / eps (zero for the plain penalty).
    const double lambda =
      method == Method::augmented_lagrangian ? state.multiplier : 0.;
    // Touching within round-off counts, with zero pressure: a body that
    // rests on a rigid one (and on nothing else) is held from the first
    // iteration on, which starts from the touching place.
    if (!(gap <= lambda / eps + touching_tolerance))
      return traction;
    traction.active           = true;
    traction.pressure         = std::max(lambda - eps * gap, 0.);
    traction.d_pressure_d_gap = -eps;
    if (friction == Friction::smooth)
      return traction;

    // Sticking stays regularized by the penalty (eps per unit slip, from
    // the traction of the last increment) also with the augmented
    // Lagrangian: augmenting the tangential traction drifted without end
    // along the alternating mode of one pressure per cell (doc/contact.md).
    // A rough surface holds up to rough_friction_coefficient times the
    // pressure: without a bound its stick traction t_prev - eps s jumped
    // from zero to the slip already made where a place started to touch
    // (and back where it let go), a jump of the residual at which Newton
    // repeated the same correction (doc/contact.md).
    const double trial = trial_traction(state.previous_tangential, slip);
    const double coefficient =
      friction == Friction::rough ? rough_friction_coefficient : mu;
    const double limit = coefficient * traction.pressure;
    const double sign  = trial > 0 ? 1. : -1.;
    traction.sliding   = std::abs(trial) > limit;
    if (friction == Friction::rough)
      {
        // A rough surface is Coulomb's law smoothed: t_T = mu p tanh(x),
        // x = t_trial / (mu p). Sticking (|x| << 1) is the penalty's to
        // within x^2 / 3, and the traction turns into mu p without a kink,
        // so Newton does not switch places between sticking and sliding
        // from one iteration to the next where a place barely presses (the
        // deep penetration at h = 0.0625 stopped at step 81 with the kink,
        // completes with this law: doc/contact.md).
        if (!(limit > 0))
          {
            traction.d_tangential_d_pressure = sign * coefficient;
            return traction;
          }
        const double x                   = trial / limit;
        const double th                  = std::tanh(x);
        const double sech                = 1 - th * th;
        traction.tangential              = limit * th;
        traction.d_tangential_d_slip     = -eps * sech;
        traction.d_tangential_d_previous = sech;
        traction.d_tangential_d_pressure = coefficient * (th - x * sech);
        return traction;
      }
    if (traction.sliding)
      {
        // t_T = mu p sign(t_trial): its derivative is p's.
        traction.tangential              = sign * limit;
        traction.d_tangential_d_pressure = sign * coefficient;
      }
    else
      {
        traction.tangential              = trial;
        traction.d_tangential_d_slip     = -eps;
        traction.d_tangential_d_previous = 1;
      }
    return traction;
  }
} // namespace bsmpm
