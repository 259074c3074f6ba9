// Intersection tests of 3D triangles and segments by orientation predicates,
// independent of the distance and barrier code (the after-step check of
// self-contact, contact/pairs/point_triangle_pairs.h, uses them as a second
// opinion on the distances).
//
// orient(a, b, c, d) = (a - d) . ((b - d) x (c - d)): positive when d is below
// the plane of (a, b, c) oriented counter-clockwise, zero when coplanar.
// Signs are exact for the double inputs (geometry/exact_orientation.h: a
// filtered double evaluation, exact expansion arithmetic when it is not
// certain), so the tests below are exact, degenerate (coplanar, touching)
// configurations included.
//
// Segment [p, q] against the closed triangle [a, b, c] (non-degenerate):
//  * p, q strictly on the same side of the plane: no intersection;
//  * otherwise, not both in the plane: the line pq passes through the closed
//    triangle iff the three orientations orient(p, q, a, b), orient(p, q, b, c),
//    orient(p, q, c, a) do not have strictly opposite signs (the line passes
//    on the inner side of all three edges, or on one of them), and then the
//    segment does, as its ends are on both sides of the plane;
//  * both in the plane: projected to the coordinate plane where the triangle
//    has the largest area, the segment meets the triangle iff an end point is
//    inside or it crosses one of the three edges (2D orientations).
// Two closed triangles intersect iff an edge of one meets the other: if they
// are not coplanar their intersection is a segment of the line common to
// both planes, whose end points are end points of one triangle's interval on
// that line, i.e. points of that triangle's edges; if coplanar, either their
// edges cross or one contains the other, and then the inner one's edges meet
// the outer one.
#pragma once

#include <Eigen/Core>

namespace ipstep {

// Sign (-1, 0, +1) of orient(a, b, c, d).
int Orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& d);

bool SegmentTriangleIntersect(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                              const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c);

bool TrianglesIntersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& b0,
                        const Eigen::Vector3d& c0, const Eigen::Vector3d& a1,
                        const Eigen::Vector3d& b1, const Eigen::Vector3d& c1);

}  // namespace ipstep
