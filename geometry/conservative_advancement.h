// Conservative advancement, the time-of-impact search used where a path has
// no closed form (3D faces and box edges against obstacle features, and
// everything against a rotating obstacle): gap(s) is the distance of a
// primitive whose points move by at most `bound` per unit of the path
// fraction s in [0, 1], relative to the obstacle feature it is measured from.
//
// Target (as in IPC's advancement): the first s at which the gap falls to
// goal = max(margin, fraction d(0)); 0 if d(0) <= margin; `no_impact` if the
// gap stays above the goal over the whole path. From s the gap stays above
// the goal up to s + (d(s) - goal) / bound, so s advances by that until the
// gap is within 1 % of d(0) - goal above the goal (returns s: the first
// fraction not proved safe; every fraction below it is), the path is covered
// (no_impact), or max_advances advances are used (returns s).
#pragma once

#include <algorithm>

namespace ipstep {

template <class Gap>
double ConservativeAdvancement(const Gap& gap, double bound, double margin, double fraction,
                               int max_advances, double no_impact) {
  const double d0 = gap(0.0);
  if (!(d0 > margin)) return 0.0;
  const double goal = std::max(margin, fraction * d0);
  if (!(bound > 0.0) || d0 - bound > goal) return no_impact;
  // Stop once the gap is this close to the goal: the remaining advances would
  // shrink geometrically while the primitive approaches at less than `bound`.
  const double close = goal + 1e-2 * (d0 - goal);
  double s = 0.0, d = d0;
  for (int advance = 0; advance < max_advances; ++advance) {
    // From s to s' every point moves by at most bound (s' - s), so the gap
    // stays >= d - bound (s' - s) >= goal.
    s += (d - goal) / bound;
    if (s >= 1.0) return no_impact;
    d = gap(s);
    if (d <= close) return s;
  }
  return s;
}

}  // namespace ipstep
