// The broad phase of a self-contact pair kind, with its last result kept and
// keyed by the query it answered: the start and end configurations (by
// value) and the growth of the boxes. The contact filter asks the same
// question several times in a row (e.g. the line search's sweep over a motion
// it swept just before, or the checks of one accepted configuration); a
// repeat returns the stored candidates, in the same order, instead of
// rebuilding the BVH and querying it again. Comparing two configurations is a
// linear scan, far below a tree build and one box query per primitive.
#pragma once

#include <algorithm>
#include <vector>

#include "core/scoped_timer.h"

namespace ipstep {

template <class Pair>
class CandidateCache {
 public:
  // Calls f(pair) for every candidate of the query (a, b, grow) over
  // configurations of n coordinates. When it is not the stored query,
  // find(&candidates) computes them first (its wall time added to *seconds).
  template <class Find, class F>
  void ForEach(const double* a, const double* b, int n, double grow, double* seconds,
               const Find& find, const F& f) {
    if (!Matches(a, b, n, grow)) {
      candidates_.clear();
      {
        ScopedTimer timer(seconds);
        find(&candidates_);
      }
      a_.assign(a, a + n);
      b_.assign(b, b + n);
      grow_ = grow;
      valid_ = true;
    }
    for (const Pair& pair : candidates_) f(pair);
  }

 private:
  bool Matches(const double* a, const double* b, int n, double grow) const {
    return valid_ && grow == grow_ && static_cast<int>(a_.size()) == n &&
           std::equal(a, a + n, a_.begin()) && std::equal(b, b + n, b_.begin());
  }

  std::vector<Pair> candidates_;
  std::vector<double> a_, b_;
  double grow_ = 0.0;
  bool valid_ = false;
};

}  // namespace ipstep
