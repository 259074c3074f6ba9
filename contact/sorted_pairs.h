// The active set of a pair kind (contact/pair_set.h): pairs kept sorted and
// unique, with per-pair data (a lagged closest point, ...) stored alongside,
// and the set emptied by the last Clear() kept for Changed().
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace ipstep {

struct NoPairData {};

// Pair: ordered by operator< and operator==. Data: per-pair payload.
template <class Pair, class Data = NoPairData>
class SortedPairs {
 public:
  void Clear() {
    previous_ = std::move(pairs_);
    pairs_.clear();
    data_.clear();
  }
  // Inserts the pair if new (with `data`); true if it was new.
  bool Insert(const Pair& pair, const Data& data = Data()) {
    auto it = std::lower_bound(pairs_.begin(), pairs_.end(), pair);
    if (it != pairs_.end() && *it == pair) return false;
    data_.insert(data_.begin() + (it - pairs_.begin()), data);
    pairs_.insert(it, pair);
    return true;
  }
  bool Contains(const Pair& pair) const {
    return std::binary_search(pairs_.begin(), pairs_.end(), pair);
  }
  bool Changed() const { return pairs_ != previous_; }

  size_t size() const { return pairs_.size(); }
  bool empty() const { return pairs_.empty(); }
  const Pair& operator[](size_t k) const { return pairs_[k]; }
  const std::vector<Pair>& pairs() const { return pairs_; }
  std::vector<Data>& data() { return data_; }
  const std::vector<Data>& data() const { return data_; }

 private:
  std::vector<Pair> pairs_;
  std::vector<Data> data_;
  std::vector<Pair> previous_;
};

}  // namespace ipstep
