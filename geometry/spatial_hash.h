// Broad phase: a uniform grid over space, stored sparsely in a hash map. Boxes
// (axis-aligned, 2D or 3D) are inserted into every cell they overlap; a query
// returns the ids of boxes sharing a cell with the query box. The work is
// proportional to the number of boxes and of close pairs, not to the square of
// the number of boxes. A box spanning too many cells (a very fast point) is kept
// in a separate list returned by every query.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace ipstep {

class SpatialHash {
 public:
  SpatialHash(int dimension, double cell_size);

  void Clear();
  void Insert(int id, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper);
  // Ids of inserted boxes that may overlap [lower, upper], sorted, without repeats.
  void Query(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
             std::vector<int>* ids) const;

  double cell_size() const { return cell_size_; }

 private:
  static constexpr int64_t kMaxCellsPerBox = 4096;
  bool CellRange(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                 Eigen::Matrix<int64_t, 3, 1>* from, Eigen::Matrix<int64_t, 3, 1>* to) const;
  static int64_t Key(int64_t i, int64_t j, int64_t k);

  int dimension_;
  double cell_size_;
  std::unordered_map<int64_t, std::vector<int>> cells_;
  std::vector<int> oversized_;
};

}  // namespace ipstep
