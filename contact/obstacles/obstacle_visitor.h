// Double dispatch on an obstacle's shape (Obstacle::Accept), for code that
// must know the concrete shape but lives above contact/ (io/ draws them).
#pragma once

namespace ipstep {

class PlaneObstacle;
class SphereObstacle;
class BoxObstacle;

class ObstacleVisitor {
 public:
  virtual ~ObstacleVisitor() = default;
  virtual void Visit(const PlaneObstacle& plane) = 0;
  virtual void Visit(const SphereObstacle& sphere) = 0;
  virtual void Visit(const BoxObstacle& box) = 0;
};

}  // namespace ipstep
