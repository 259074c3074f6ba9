// The `inertia` Hessian projection of Ceres's newton and dogleg
// (OptimizerOptions::hessian_projection = kInertia): exact Newton steps through
// Ceres wherever the nodes' inertia can carry the terms' negative curvature.
//
// Ceres's model must be a sum of squares, one positive semi-definite block
// per residual block, so an indefinite term Hessian H_t cannot enter it as it
// is; per-term projection (clamp, abs) changes the model and costs Newton its
// quadratic convergence. But the step's Hessian is a sum, and its inertia part
// M/h^2 (w_I m_i I per node) is strongly positive. Write each term's negative
// part N_t = sum_{lambda<0} |lambda| v v^T (H_t = P_t - N_t, P_t, N_t PSD) and
// bound it by a block-diagonal matrix, one block per node:
//   N_t <= k blockdiag(N_t) =: D_t        (k the term's nodes: with N = L L^T
//                                          and y_a = L_a^T x_a, x^T (k
//                                          blockdiag(N) - N) x = k sum |y_a|^2
//                                          - |sum y_a|^2 = sum_{a<b}
//                                          |y_a - y_b|^2 >= 0)
// Then the term's model H_t + D_t = P_t + (D_t - N_t) is PSD, the node's
// inertia model w_I m_i I - sum_t D_t,i is PSD while sum_t D_t,i stays below
// kInertiaBudget w_I m_i I, and the sum of all the models is the exact
// Hessian: Ceres's Levenberg-Marquardt then takes exact Newton steps. A node
// over its budget (stiff compressed terms, little mass, large steps; every
// node of a quasi-static step, which has no inertia) scales its terms' blocks
// by s = budget / lambda_max(sum) (a term by the least s of its nodes), and
// such a term's model is H_t + s D_t with what is left negative clamped, so
// the model is never indefinite and lies between the clamp (s = 0) and the
// exact Hessian (s = 1). The bound's factor k (2 for springs, 4 for a
// tetrahedron) is the price of block-diagonality.
//
// Measured (bench/hessian_projection.sh, docs/benchmarks.md): exact steps on
// the kicked compressed chain (16 -> 2 iterations, tests/solver/
// hessian_projection_test.cc), twisted_bar_3d 2.75 -> 2.0 iterations per step;
// on the hanging square and the cloths the budget binds at most compressed
// nodes (grid 40: 8.75 -> 7.5) and each iteration costs more (one row per
// coordinate, a full eigen-decomposition per absorbed term): an option, not
// the default.
//
// This is our formulation, in the spirit of the "Kinetic Newton" of Longva et
// al. 2023 ("Pitfalls of projection"), which regularises with the mass matrix
// instead of projecting.
#pragma once

#include <Eigen/Core>

#include "core/term.h"
#include "core/term_hessian.h"

namespace ipstep {

// The fraction of a node's inertia w_I m_i its terms' negative curvature may
// take; above it, the node's terms are clamped.
constexpr double kInertiaBudget = 0.9;

using FullMatrix = TermMatrix;
using FullVector = TermVector;

// The term's exact Hessian and gradient over all its coordinates (nodes x
// dimension; pair-difference models expanded to [[K, -K], [-K, K]]).
void FullHessian(const Term& term, int dimension, const TermModel& model, FullMatrix* hessian,
                 FullVector* gradient);

// D_t's blocks (nodes x dimension^2, row-major dimension x dimension each)
// for the exact Hessian `hessian` (full coordinates) of a term with `nodes`
// nodes, from the reduced eigensystem where the model has one and from the
// d x d model K of a pair-difference term (`pair`). False (and no blocks) if
// the Hessian has no negative curvature.
bool NegativeCurvatureBlocks(const TermModel& model, const FullMatrix& hessian, int nodes,
                             int dimension, bool pair, double* blocks);

// Residuals and per-block Jacobian rows (row-major rows x dimension) of a
// positive semi-definite `matrix` over a term's full coordinates carrying
// `gradient`: its eigen-decomposition V diag(l) V^T, l floored at
// kCurvatureFloor max|l|, rows sqrt(l) V^T and residuals V^T g / sqrt(l);
// `rows` rows in all (the rest zero).
void MatrixRows(const FullMatrix& matrix, const FullVector& gradient, int dimension, int rows,
                double* residuals, double** jacobians);

}  // namespace ipstep
