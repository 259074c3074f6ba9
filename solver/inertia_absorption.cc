#include "solver/inertia_absorption.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace ipstep {

void FullHessian(const Term& term, int dimension, const TermModel& model, FullMatrix* hessian,
                 FullVector* gradient) {
  if (!term.pair_difference) {
    *hessian = model.hessian;
    *gradient = model.gradient;
    return;
  }
  const int d = dimension;
  hessian->resize(2 * d, 2 * d);
  gradient->resize(2 * d);
  for (int a = 0; a < 2 * d; ++a) {
    (*gradient)[a] = (a < d ? -1.0 : 1.0) * model.gradient[a % d];
    for (int b = 0; b < 2 * d; ++b) {
      (*hessian)(a, b) = ((a < d) == (b < d) ? 1.0 : -1.0) * model.hessian(a % d, b % d);
    }
  }
}

bool NegativeCurvatureBlocks(const TermModel& model, const FullMatrix& hessian, int nodes,
                             int dimension, bool pair, double* blocks) {
  const int n = static_cast<int>(hessian.rows());
  FullMatrix negative = FullMatrix::Zero(n, n);
  bool any = false;
  if (model.reduced) {
    // H = sum_k l_k u_k u_k^T with u_k = B^T q_k: the negative part directly.
    for (int k = 0; k < model.reduced_values.size(); ++k) {
      const double l = model.reduced_values[k];
      if (!(l < 0.0)) continue;
      negative.noalias() -=
          l * model.reduced_directions.col(k) * model.reduced_directions.col(k).transpose();
      any = true;
    }
  } else {
    // Pair-difference terms: the negative part of K (d x d), which
    // [[K, -K], [-K, K]] places on both nodes with signs; others: of H.
    const FullMatrix& decomposed = pair ? model.hessian : hessian;
    FullVector values;
    FullMatrix vectors;
    DecomposeSymmetric(decomposed, &values, &vectors);
    const double scale = values.cwiseAbs().maxCoeff();
    const int m = static_cast<int>(decomposed.rows());
    for (int k = 0; k < m; ++k) {
      const double l = values[k];
      // Round-off of a PSD Hessian (translations) is not negative curvature.
      if (!(l < -1e-12 * scale)) continue;
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
          const double sign = !pair || (a < m) == (b < m) ? 1.0 : -1.0;
          negative(a, b) -= sign * l * vectors(a % m, k) * vectors(b % m, k);
        }
      }
      any = true;
    }
  }
  if (!any) return false;
  const int d = dimension;
  for (int b = 0; b < nodes; ++b) {
    for (int i = 0; i < d; ++i) {
      for (int j = 0; j < d; ++j) {
        blocks[b * d * d + i * d + j] = nodes * negative(b * d + i, b * d + j);
      }
    }
  }
  return true;
}

void MatrixRows(const FullMatrix& matrix, const FullVector& gradient, int dimension, int rows,
                double* residuals, double** jacobians) {
  const int n = static_cast<int>(matrix.rows());
  const int blocks = n / dimension;
  FullVector values;
  FullMatrix vectors;
  DecomposeSymmetric(matrix, &values, &vectors);
  const double floor = kCurvatureFloor * std::max(values.cwiseAbs().maxCoeff(), 1e-300);
  for (int i = 0; i < rows; ++i) {
    const bool row = i < n;
    const double lambda = row ? std::max(values[i], floor) : 0.0;
    const double root = std::sqrt(lambda);
    residuals[i] = row && root > 0.0 ? vectors.col(i).dot(gradient) / root : 0.0;
    for (int b = 0; b < blocks; ++b) {
      if (jacobians[b] == nullptr) continue;
      for (int k = 0; k < dimension; ++k) {
        jacobians[b][i * dimension + k] = row ? root * vectors(b * dimension + k, i) : 0.0;
      }
    }
  }
}

}  // namespace ipstep
