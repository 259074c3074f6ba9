// Sparse Cholesky factorisation of the symmetric Newton matrix for
// projected_newton (solver/projected_newton_solver.h): the symbolic analysis
// (fill-reducing ordering, elimination tree, supernodes) once per sparsity
// pattern, the numeric factorisation once per Newton iteration, so that a
// scene whose terms do not change analyses once for the whole run.
//
// Two libraries:
//  * SUITE_SPARSE (the default): CHOLMOD's LL^T, supernodal (dense BLAS
//    kernels on the supernodes) where the fill is large enough, else
//    simplicial (CHOLMOD's own choice), with a fill-reducing ordering chosen
//    below. CHOLMOD is quiet (Common.print = 0) and stops at the first
//    non-positive pivot (quick_return_if_not_posdef), so a definiteness test
//    on an indefinite matrix costs only the columns up to that pivot.
//  * EIGEN_SPARSE: Eigen's SimplicialLDLT with AMD (column by column, no
//    BLAS): ipstep's earlier solver, kept as the reference.
//
// The matrix is given as its lower triangle, column-major (Eigen's default
// storage), with every diagonal entry present.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace ipstep {

enum class SparseLibrary { kSuiteSparse, kEigen };

// Fill-reducing orderings: approximate minimum degree, or nested dissection
// (METIS through CHOLMOD; SUITE_SPARSE only). kAutomatic picks one from the
// matrix's dimension and size (ChooseOrdering).
enum class FillOrdering { kAutomatic, kAmd, kNestedDissection };

// The automatic choice: nested dissection for 3D meshes of at least
// kNestedDissectionMinDofs unknowns, AMD otherwise (measured in
// docs/benchmarks.md, "Sparse Cholesky").
constexpr int kNestedDissectionMinDofs = 20000;
FillOrdering ChooseOrdering(int dimension, int unknowns);

const char* SparseLibraryName(SparseLibrary library);  // "SUITE_SPARSE", "EIGEN_SPARSE"
const char* FillOrderingName(FillOrdering ordering);   // "AUTOMATIC", "AMD", "NESDIS"

class SparseCholesky {
 public:
  enum class Result { kSuccess, kNotPositiveDefinite, kFailure };

  // ordering: kAmd or kNestedDissection (kAutomatic is resolved by the
  // caller). EIGEN_SPARSE supports kAmd only.
  static std::unique_ptr<SparseCholesky> Create(SparseLibrary library, FillOrdering ordering);

  virtual ~SparseCholesky() = default;
  // Symbolic analysis of lower's pattern; the values are ignored. With a
  // `permutation` (the unknowns in elimination order; SUITE_SPARSE only, the
  // others ignore it) that ordering is used instead of computing one. False
  // on failure (out of memory).
  virtual bool Analyze(const Eigen::SparseMatrix<double>& lower,
                       const std::vector<int>* permutation = nullptr) = 0;
  // Numeric factorisation of a matrix with the analysed pattern.
  virtual Result Factorize(const Eigen::SparseMatrix<double>& lower) = 0;
  // Solves with the last successful factorisation. False if the result is
  // not finite.
  virtual bool Solve(const Eigen::VectorXd& rhs, Eigen::VectorXd* solution) = 0;
  // e.g. "CHOLMOD supernodal LL^T, nested dissection (METIS) ordering".
  virtual std::string Description() const = 0;
  // Nonzeros of the factor after the analysis (0 before).
  virtual double FactorNonZeros() const = 0;
};

}  // namespace ipstep
