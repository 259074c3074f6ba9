// The last broad-phase result of a self-contact pair kind, keyed by the query
// it answered: the start and end configurations (by value) and the growth of
// the boxes. The contact filter asks the same question several times in a row
// (e.g. the line search's sweep over a motion it swept just before, or the
// checks of one accepted configuration); a repeat returns the stored
// candidates, in the same order, instead of rebuilding the BVH and querying it
// again. Comparing two configurations is a linear scan, far below a tree
// build and one box query per primitive.
#pragma once

#include <algorithm>
#include <vector>

namespace ipstep {

template <class Pair>
class CandidateCache {
 public:
  // Whether (a, b, grow), configurations of n coordinates, is the stored query.
  bool Matches(const double* a, const double* b, int n, double grow) const {
    return valid_ && grow == grow_ && static_cast<int>(a_.size()) == n &&
           std::equal(a, a + n, a_.begin()) && std::equal(b, b + n, b_.begin());
  }
  // Records (a, b, grow) as the query `candidates` now answers.
  void Store(const double* a, const double* b, int n, double grow) {
    a_.assign(a, a + n);
    b_.assign(b, b + n);
    grow_ = grow;
    valid_ = true;
  }
  std::vector<Pair> candidates;

 private:
  std::vector<double> a_, b_;
  double grow_ = 0.0;
  bool valid_ = false;
};

}  // namespace ipstep
