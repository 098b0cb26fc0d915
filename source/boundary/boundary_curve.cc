#include <bsmpm/boundary/boundary_curve.h>

namespace bsmpm
{
  Voigt
  BoundaryCurve::stress_at(const unsigned int segment, const double u) const
  {
    const auto         range = spline->segment_parameters(segment);
    const unsigned int k1    = (segment + 1) % positions.size();
    const double       f     = (u - range[0]) / (range[1] - range[0]);
    return (1 - f) * stresses[segment] + f * stresses[k1];
  }



  std::vector<double>
  BoundaryCurve::state_at(const unsigned int segment, const double u) const
  {
    using Property           = MaterialPoints::Property;
    const auto         range = spline->segment_parameters(segment);
    const unsigned int k1    = (segment + 1) % positions.size();
    const double       f     = (u - range[0]) / (range[1] - range[0]);
    const auto        &a     = states[segment];
    const auto        &b     = states[k1];
    const auto         at    = [&](const unsigned int k) {
      return (1 - f) * a[k] + f * b[k];
    };
    std::vector<double> props(Property::n_properties_inelastic, 0.);
    props[Property::volume] = 1.;
    for (unsigned int k = 0; k < 4; ++k)
      props[Property::elastic_strain + k] = at(k);
    props[Property::plastic_strain] = at(4);
    props[Property::det_F]          = at(5);
    props[Property::weight]         = 1.;
    return props;
  }



  const CurveCondition *
  BoundaryCurve::condition_of_segment(const unsigned int k) const
  {
    const CurveCondition *found = nullptr;
    for (const auto &c : conditions)
      if (c.covers(k, n_segments()))
        found = &c;
    return (found && found->kind != CurveCondition::Kind::free) ? found :
                                                                  nullptr;
  }



  const CurveCondition *
  BoundaryCurve::rigid_support(const unsigned int k) const
  {
    const unsigned int n    = n_segments();
    const unsigned int none = numbers::invalid_unsigned_int;
    // The ends of an open chain meet other curves, whose points there move
    // with the body: they must stay together.
    if (n == 0 || !spline || (!closed && (k == 0 || k == n)))
      return nullptr;
    const auto previous = [&](const unsigned int j) {
      return j == none ? none : j > 0 ? j - 1 : closed ? n - 1 : none;
    };
    const auto next = [&](const unsigned int j) {
      return j == none ? none : j + 1 < n ? j + 1 : closed ? 0 : none;
    };
    const auto condition = [&](const unsigned int j) -> const CurveCondition * {
      return j == none ? nullptr : condition_of_segment(j);
    };
    // The segments on either side of point k (none beyond the ends of an
    // open chain).
    const unsigned int    before = k > 0 ? k - 1 : closed ? n - 1 : none;
    const unsigned int    after  = k < n ? k : none;
    const CurveCondition *own    = nullptr;
    for (const unsigned int j : {before, after})
      if (const CurveCondition *c = condition(j);
          c != nullptr && c->kind == CurveCondition::Kind::normal_displacement)
        own = c;
    if (own == nullptr)
      return nullptr;
    for (const unsigned int j : {before, after})
      if (const CurveCondition *c = condition(j);
          c != nullptr && c != own && c->is_support())
        return nullptr;
    // The run of the condition's segments through the point: a rigid body
    // if one of its ends meets a segment that is no support.
    unsigned int first = condition(after) == own ? after : before;
    unsigned int last  = first;
    for (unsigned int s = 0; s < n && condition(previous(first)) == own; ++s)
      first = previous(first);
    for (unsigned int s = 0; s < n && condition(next(last)) == own; ++s)
      last = next(last);
    const auto meets_no_support = [&](const unsigned int j) {
      const CurveCondition *c = condition(j);
      return j != none && (c == nullptr || !c->is_support());
    };
    if (!meets_no_support(previous(first)) && !meets_no_support(next(last)))
      return nullptr;
    return own;
  }
} // namespace bsmpm
