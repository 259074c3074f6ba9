#include "contact/pair_kinds.h"

#include "contact/pairs/box_edge_pairs.h"
#include "contact/pairs/edge_edge_pairs.h"
#include "contact/pairs/edge_obstacle_pairs.h"
#include "contact/pairs/face_obstacle_pairs.h"
#include "contact/pairs/node_obstacle_pairs.h"
#include "contact/pairs/point_edge_pairs.h"
#include "contact/pairs/point_triangle_pairs.h"

namespace ipstep {

std::vector<std::unique_ptr<PairSet>> MakePairSets(const PairSetContext& context, bool self_contact,
                                                   const double* initial,
                                                   const double* self_kappa) {
  std::vector<std::unique_ptr<PairSet>> sets;
  PairSetContext self = context;
  if (self_kappa != nullptr) self.kappa = self_kappa;
  sets.push_back(std::make_unique<NodeObstaclePairs>(context));
  sets.push_back(std::make_unique<EdgeObstaclePairs>(context));
  // Faces before box edges: the order the terms are added and the barrier
  // gradient summed in (the two were one kind).
  sets.push_back(std::make_unique<FaceObstaclePairs>(context));
  sets.push_back(std::make_unique<BoxEdgePairs>(context));
  if (self_contact) {
    if (self.dimension == 2) sets.push_back(std::make_unique<PointEdgePairs>(self, initial));
    if (self.dimension == 3) sets.push_back(std::make_unique<PointTrianglePairs>(self));
    if (self.dimension == 3) sets.push_back(std::make_unique<EdgeEdgePairs>(self, initial));
  }
  return sets;
}

}  // namespace ipstep
