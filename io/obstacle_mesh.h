// Contact obstacles (contact/obstacle.h) as a mesh for pictures, at time t
// (moving obstacles at their position): 2D planes as segments, circles and
// boxes as polygons; 3D planes as quads, spheres as triangles, boxes as six
// quads. Planes are drawn as a patch of half-width `extent` around the point of
// the plane closest to `centre`. Cell data "obstacle": the obstacle's index.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "contact/obstacle.h"
#include "io/vtk_unstructured_grid.h"

namespace ipstep {

VtkMesh ObstacleMesh(const ObstacleList& obstacles, double t, const Eigen::Vector3d& centre,
                     double extent);

}  // namespace ipstep
