#include "geometry/spatial_hash.h"

#include <algorithm>
#include <cmath>

namespace ipstep {

SpatialHash::SpatialHash(int dimension, double cell_size)
    : dimension_(dimension), cell_size_(cell_size > 0.0 ? cell_size : 1.0) {}

void SpatialHash::Clear() {
  cells_.clear();
  oversized_.clear();
}

int64_t SpatialHash::Key(int64_t i, int64_t j, int64_t k) {
  // Large primes mix the three cell coordinates into one key (collisions only
  // merge cells, which is harmless for a broad phase).
  return i * 73856093LL ^ j * 19349663LL ^ k * 83492791LL;
}

bool SpatialHash::CellRange(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                            Eigen::Matrix<int64_t, 3, 1>* from,
                            Eigen::Matrix<int64_t, 3, 1>* to) const {
  int64_t cells = 1;
  for (int k = 0; k < 3; ++k) {
    if (k >= dimension_) {
      (*from)[k] = (*to)[k] = 0;
      continue;
    }
    const double lo = std::floor(lower[k] / cell_size_), hi = std::floor(upper[k] / cell_size_);
    if (!std::isfinite(lo) || !std::isfinite(hi) || hi - lo > kMaxCellsPerBox) return false;
    (*from)[k] = static_cast<int64_t>(lo);
    (*to)[k] = static_cast<int64_t>(hi);
    cells *= (*to)[k] - (*from)[k] + 1;
    if (cells > kMaxCellsPerBox) return false;
  }
  return true;
}

void SpatialHash::Insert(int id, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper) {
  Eigen::Matrix<int64_t, 3, 1> from, to;
  if (!CellRange(lower, upper, &from, &to)) {
    oversized_.push_back(id);
    return;
  }
  for (int64_t i = from[0]; i <= to[0]; ++i)
    for (int64_t j = from[1]; j <= to[1]; ++j)
      for (int64_t k = from[2]; k <= to[2]; ++k) cells_[Key(i, j, k)].push_back(id);
}

void SpatialHash::Query(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                        std::vector<int>* ids) const {
  ids->assign(oversized_.begin(), oversized_.end());
  Eigen::Matrix<int64_t, 3, 1> from, to;
  if (!CellRange(lower, upper, &from, &to)) {
    // The query box itself is huge: every inserted box is a candidate.
    for (const auto& [key, list] : cells_) ids->insert(ids->end(), list.begin(), list.end());
  } else {
    for (int64_t i = from[0]; i <= to[0]; ++i)
      for (int64_t j = from[1]; j <= to[1]; ++j)
        for (int64_t k = from[2]; k <= to[2]; ++k) {
          auto it = cells_.find(Key(i, j, k));
          if (it != cells_.end()) ids->insert(ids->end(), it->second.begin(), it->second.end());
        }
  }
  std::sort(ids->begin(), ids->end());
  ids->erase(std::unique(ids->begin(), ids->end()), ids->end());
}

}  // namespace ipstep
