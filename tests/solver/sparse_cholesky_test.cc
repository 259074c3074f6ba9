// The sparse Cholesky factorisations of solver/sparse_cholesky.h against a
// dense reference: the same solution from every library and ordering, a
// matrix that is not positive definite reported as such, the symbolic
// analysis reused after a failed factorisation, and a given permutation.
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "solver/sparse_cholesky.h"

namespace ipstep {
namespace {

// The 2D grid Laplacian (n x n nodes, 2 unknowns per node) plus `shift` on
// the diagonal and 0.3 between a node's two unknowns, as the lower triangle:
// positive definite for shift > 0.3.
Eigen::SparseMatrix<double> GridMatrix(int n, double shift) {
  std::vector<Eigen::Triplet<double>> triplets;
  const int unknowns = 2 * n * n;
  auto id = [n](int i, int j, int k) { return 2 * (j * n + i) + k; };
  std::vector<double> diagonal(unknowns, shift);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < 2; ++k) {
        if (i + 1 < n) {
          triplets.emplace_back(id(i + 1, j, k), id(i, j, k), -1.0);
          diagonal[id(i, j, k)] += 1.0;
          diagonal[id(i + 1, j, k)] += 1.0;
        }
        if (j + 1 < n) {
          triplets.emplace_back(id(i, j + 1, k), id(i, j, k), -1.0);
          diagonal[id(i, j, k)] += 1.0;
          diagonal[id(i, j + 1, k)] += 1.0;
        }
      }
      // Couple the node's two unknowns.
      triplets.emplace_back(id(i, j, 1), id(i, j, 0), 0.3);
    }
  }
  for (int d = 0; d < unknowns; ++d) triplets.emplace_back(d, d, diagonal[d]);
  Eigen::SparseMatrix<double> lower(unknowns, unknowns);
  lower.setFromTriplets(triplets.begin(), triplets.end());
  lower.makeCompressed();
  return lower;
}

Eigen::VectorXd DenseSolve(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXd& b) {
  const Eigen::MatrixXd l = Eigen::MatrixXd(lower);
  const Eigen::MatrixXd full = l + l.transpose() - Eigen::MatrixXd(l.diagonal().asDiagonal());
  return full.ldlt().solve(b);
}

struct Case {
  SparseLibrary library;
  FillOrdering ordering;
};
const Case kCases[] = {{SparseLibrary::kSuiteSparse, FillOrdering::kAmd},
                       {SparseLibrary::kSuiteSparse, FillOrdering::kNestedDissection},
                       {SparseLibrary::kEigen, FillOrdering::kAmd}};

TEST(SparseCholesky, EveryLibraryAndOrderingSolvesAsTheDenseReference) {
  const Eigen::SparseMatrix<double> matrix = GridMatrix(12, 0.5);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd b(matrix.rows());
  for (int i = 0; i < b.size(); ++i) b[i] = uniform(random);
  const Eigen::VectorXd expected = DenseSolve(matrix, b);
  for (const Case& c : kCases) {
    auto cholesky = SparseCholesky::Create(c.library, c.ordering);
    ASSERT_TRUE(cholesky->Analyze(matrix)) << cholesky->Description();
    ASSERT_EQ(cholesky->Factorize(matrix), SparseCholesky::Result::kSuccess);
    Eigen::VectorXd x;
    ASSERT_TRUE(cholesky->Solve(b, &x));
    EXPECT_LT((x - expected).lpNorm<Eigen::Infinity>(), 1e-10 * expected.lpNorm<Eigen::Infinity>())
        << cholesky->Description();
    EXPECT_GT(cholesky->FactorNonZeros(), matrix.nonZeros() - 1);
  }
}

// An indefinite matrix with the analysed pattern is reported (not solved), and
// the same analysis then factorises a definite one correctly: CHOLMOD stops
// at the first non-positive pivot, and the factor must not be left unusable.
TEST(SparseCholesky, IndefiniteIsReportedAndTheAnalysisIsReused) {
  const Eigen::SparseMatrix<double> definite = GridMatrix(10, 0.5);
  Eigen::SparseMatrix<double> indefinite = definite;
  for (int k = 0; k < indefinite.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(indefinite, k); it; ++it) {
      if (it.row() == it.col() && it.row() == 57) it.valueRef() = -5.0;
    }
  }
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(definite.rows(), -1.0, 2.0);
  const Eigen::VectorXd expected = DenseSolve(definite, b);
  for (const Case& c : kCases) {
    auto cholesky = SparseCholesky::Create(c.library, c.ordering);
    ASSERT_TRUE(cholesky->Analyze(definite));
    EXPECT_EQ(cholesky->Factorize(indefinite), SparseCholesky::Result::kNotPositiveDefinite)
        << cholesky->Description();
    ASSERT_EQ(cholesky->Factorize(definite), SparseCholesky::Result::kSuccess);
    Eigen::VectorXd x;
    ASSERT_TRUE(cholesky->Solve(b, &x));
    EXPECT_LT((x - expected).lpNorm<Eigen::Infinity>(), 1e-10 * expected.lpNorm<Eigen::Infinity>())
        << cholesky->Description();
  }
}

// A given elimination order (here: the unknowns reversed) is used as given:
// the same solution, and the factor's fill is that order's, not AMD's.
TEST(SparseCholesky, GivenPermutation) {
  const Eigen::SparseMatrix<double> matrix = GridMatrix(10, 0.5);
  std::vector<int> reversed(matrix.rows());
  for (int i = 0; i < matrix.rows(); ++i) reversed[i] = static_cast<int>(matrix.rows()) - 1 - i;
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(matrix.rows());
  auto given = SparseCholesky::Create(SparseLibrary::kSuiteSparse, FillOrdering::kNestedDissection);
  auto amd = SparseCholesky::Create(SparseLibrary::kSuiteSparse, FillOrdering::kAmd);
  ASSERT_TRUE(given->Analyze(matrix, &reversed));
  ASSERT_TRUE(amd->Analyze(matrix));
  ASSERT_EQ(given->Factorize(matrix), SparseCholesky::Result::kSuccess);
  Eigen::VectorXd x;
  ASSERT_TRUE(given->Solve(b, &x));
  EXPECT_LT((x - DenseSolve(matrix, b)).lpNorm<Eigen::Infinity>(), 1e-10);
  // The reversed grid order is a banded one: more fill than AMD's.
  EXPECT_GT(given->FactorNonZeros(), amd->FactorNonZeros());
  EXPECT_NE(given->Description().find("of the nodes"), std::string::npos);
}

TEST(SparseCholesky, AutomaticOrdering) {
  EXPECT_EQ(ChooseOrdering(2, 1000000), FillOrdering::kAmd);
  EXPECT_EQ(ChooseOrdering(3, kNestedDissectionMinDofs - 1), FillOrdering::kAmd);
  EXPECT_EQ(ChooseOrdering(3, kNestedDissectionMinDofs), FillOrdering::kNestedDissection);
}

}  // namespace
}  // namespace ipstep
