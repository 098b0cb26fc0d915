#include <bsmpm/boundary/boundary_curves.h>
#include <bsmpm/boundary/boundary_point_spacing.h>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace bsmpm
{
  void
  BoundaryPointSpacing::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Point spacing");
    prm.declare_entry(
      "Adapt",
      "true",
      Patterns::Bool(),
      "Whether tracking points are inserted where a curve stretches and "
      "removed where its points crowd, after every converged load "
      "increment (curves of tracking points only, not those through "
      "material points). A curve whose points keep their starting spacing "
      "to within a factor 1.5 is never changed.");
    prm.declare_entry(
      "Insert above",
      "0.5",
      Patterns::Double(0.),
      "A segment longer than this fraction of the cell size h that has "
      "also stretched to more than 1.5 times its starting length gets a "
      "new point at the middle of its parameter range on the current "
      "spline, its state (stress, strain, ...) the mean of its "
      "neighbours'.");
    prm.declare_entry(
      "Remove below",
      "0.1",
      Patterns::Double(0.),
      "A point one of whose segments is shorter than this fraction of h "
      "and than 1/1.5 of its starting length is removed (never an end of "
      "an open chain, a corner, an end of a condition's range i-j or a "
      "point where the chain turns by more than 30 degrees). Must be below "
      "half of 'Insert above'.");
    prm.leave_subsection();
  }



  void
  BoundaryPointSpacing::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Point spacing");
    adapt        = prm.get_bool("Adapt");
    insert_above = prm.get_double("Insert above");
    remove_below = prm.get_double("Remove below");
    prm.leave_subsection();
    // A removal leaves a segment of up to twice the removal length, which
    // must not be split again at once.
    AssertThrow(!adapt || 2 * remove_below < insert_above,
                ExcMessage("Boundary curves/Point spacing: 'Remove below' (" +
                           std::to_string(remove_below) +
                           ") must be less than half of 'Insert above' (" +
                           std::to_string(insert_above) +
                           "), or points removed would be inserted again."));
  }



  BoundaryPointSpacing::Plan
  BoundaryPointSpacing::plan(const BoundaryCurve &curve, const double h) const
  {
    Plan               plan;
    const auto        &x = curve.positions;
    const auto        &X = curve.initial_positions;
    const unsigned int n = x.size();
    if (!adapt || n < 2 || X.size() != n || !curve.spline)
      return plan;
    const unsigned int n_segments = curve.n_segments();
    const auto         next = [&](const unsigned int k) { return (k + 1) % n; };
    std::vector<double> length(n_segments), start_length(n_segments);
    for (unsigned int s = 0; s < n_segments; ++s)
      {
        length[s]       = x[next(s)].distance(x[s]);
        start_length[s] = X[next(s)].distance(X[s]);
      }

    // Removals: the points that may go, the most crowded first.
    std::vector<bool> keep(n, false);
    if (!curve.closed)
      keep[0] = keep[n - 1] = true;
    else
      keep[0] = true;
    for (const unsigned int c : curve.corners)
      if (c < n)
        keep[c] = true;
    for (const auto &condition : curve.conditions)
      if (condition.has_range())
        {
          keep[condition.first_segment % n] = true;
          keep[condition.end_segment % n]   = true;
        }
    const double cos_30 = std::sqrt(3.) / 2;
    // The most crowded first, by lengths rounded to 1e-10 h: a homogeneous
    // deformation leaves the segments equally long but for round-off, and
    // round-off (that of the number of processes, say) must not decide
    // which points go and so how many; equal lengths go in the order of
    // the points.
    std::vector<std::tuple<long long, unsigned int>> candidates;
    if (!curve.closed || n > 4)
      for (unsigned int k = 0; k < n; ++k)
        {
          if (keep[k])
            continue;
          const unsigned int before = k > 0 ? k - 1 : n - 1; // segment
          const unsigned int after  = k;                     // segment
          const Tensor<1, 2> a      = x[k] - x[(k + n - 1) % n];
          const Tensor<1, 2> b      = x[next(k)] - x[k];
          if (a * b < cos_30 * a.norm() * b.norm())
            continue; // a turn: removing the point would cut it off
          const unsigned int s =
            length[before] <= length[after] ? before : after;
          const double merged = x[next(k)].distance(x[(k + n - 1) % n]);
          if (length[s] < remove_below * h &&
              length[s] * stretch_before_split < start_length[s] &&
              merged < insert_above * h)
            candidates.emplace_back(std::llround(length[s] / (1e-10 * h)), k);
        }
    std::sort(candidates.begin(), candidates.end());
    std::vector<bool> removed(n, false);
    for (const auto &[d, k] : candidates)
      if (!removed[(k + n - 1) % n] && !removed[next(k)])
        removed[k] = true;
    for (unsigned int k = 0; k < n; ++k)
      if (removed[k])
        plan.removed_points.push_back(k);

    // Insertions: stretched segments whose two points both stay.
    for (unsigned int s = 0; s < n_segments; ++s)
      if (!removed[s] && !removed[next(s)] && length[s] > insert_above * h &&
          length[s] > stretch_before_split * start_length[s])
        plan.split_segments.push_back(s);
    return plan;
  }
} // namespace bsmpm
