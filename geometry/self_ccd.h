// Continuous collision detection of 3D self-contact pairs by additive
// conservative advancement (the idea of Li et al. 2021, "Codimensional
// Incremental Potential Contact", additive CCD; derived and written here).
//
// Four points move linearly, x_i(s) = x_i + s D_i, s in [0, 1]: a point p
// against a triangle [a, b, c], or an edge [a0, a1] against an edge [b0, b1].
// The distance between the primitives does not change under a common
// translation, so subtract the mean displacement D_bar from every D_i. Every
// point of a primitive is a convex combination of its vertices, so relative
// to D_bar it moves by at most l_A = max over its vertices of |D_i - D_bar|
// per unit s; the two closest points approach each other by at most
// L = l_A + l_B per unit s, hence
//   d(s + h) >= d(s) - L h   for h >= 0.
// From a fraction s with d(s) > goal, every fraction up to s + (d(s) - goal) / L
// is proved to keep d >= goal; the algorithm advances by exactly that, and
// stops either
//  * when s would pass 1: no impact (kNoImpact),
//  * when d(s) - goal <= kAdvanceTolerance (d(0) - goal): it returns s, a
//    fraction proved to keep d >= goal > margin over [0, s] (and the true
//    first time the goal is reached is later: the result is never late), or
//  * after kMaxAdvances steps (a long tangential slide at a small gap): it
//    returns the s reached, which is still proved safe, only early.
// Goal: margin + kGapFraction (d(0) - margin), i.e. the pair is allowed to
// close 90 % of its gap above the margin in one motion (as the obstacle pairs,
// Obstacle::kEdgeGapFraction), so the fraction returned is strictly before
// the margin is reached; 0 if d(0) <= margin. Distances are exact
// (PointTriangleDistance, SegmentSegmentDistance), so a configuration where
// the primitives meet has d = 0 <= goal: no pass-through can be missed (the
// bound holds for any motion, including degenerate and parallel ones).
#pragma once

#include <Eigen/Core>

namespace ipstep {

constexpr double kSelfNoImpact = 2.0;
constexpr double kGapFraction = 0.1;
constexpr double kAdvanceTolerance = 1e-3;
constexpr int kMaxAdvances = 100000;

// Point p0 -> p1 against the triangle [a0, b0, c0] -> [a1, b1, c1].
double PointTriangleTimeOfImpact(const Eigen::Vector3d& p0, const Eigen::Vector3d& a0,
                                 const Eigen::Vector3d& b0, const Eigen::Vector3d& c0,
                                 const Eigen::Vector3d& p1, const Eigen::Vector3d& a1,
                                 const Eigen::Vector3d& b1, const Eigen::Vector3d& c1,
                                 double margin);

// Edge [a0, a1] against the edge [b0, b1], moving to the *_end positions.
double EdgeEdgeTimeOfImpact(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                            const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                            const Eigen::Vector3d& a0_end, const Eigen::Vector3d& a1_end,
                            const Eigen::Vector3d& b0_end, const Eigen::Vector3d& b1_end,
                            double margin);

}  // namespace ipstep
