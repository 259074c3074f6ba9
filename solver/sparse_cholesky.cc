#include "solver/sparse_cholesky.h"

#include <cholmod.h>

#include <Eigen/SparseCholesky>

#include "solver/serial_openmp.h"

// OpenBLAS (libopenblas-serial-dev) serves the BLAS and LAPACK calls of
// CHOLMOD's supernodal factorisation. Debian's libceres also pulls in ATLAS
// (libf77blas), and whichever library the process loads first answers every
// dgemm_/dpotrf_ call; with ATLAS the 36,300-DOF bar's quasi-static solve
// took 3.15 s, with OpenBLAS 1.67 s (4 iterations, the same iterates). This
// direct call makes libopenblas a library the programs need, so the dynamic
// linker finds it before Ceres's dependencies; it also keeps a threaded
// OpenBLAS (libopenblas0-pthread) on one thread (measured 1.89 s with its
// default 2 threads against 1.60 s with 1: the supernodes here are small).
extern "C" void openblas_set_num_threads(int threads);

namespace ipstep {
namespace {

// A non-owning CHOLMOD view of an Eigen column-major lower triangle.
cholmod_sparse View(const Eigen::SparseMatrix<double>& lower) {
  cholmod_sparse a{};
  a.nrow = static_cast<size_t>(lower.rows());
  a.ncol = static_cast<size_t>(lower.cols());
  a.nzmax = static_cast<size_t>(lower.nonZeros());
  a.p = const_cast<int*>(lower.outerIndexPtr());
  a.i = const_cast<int*>(lower.innerIndexPtr());
  a.x = const_cast<double*>(lower.valuePtr());
  a.nz = nullptr;
  a.z = nullptr;
  a.stype = -1;  // symmetric, lower triangle stored
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  return a;
}

class CholmodCholesky : public SparseCholesky {
 public:
  explicit CholmodCholesky(FillOrdering ordering) : ordering_(ordering) {
    openblas_set_num_threads(1);
    cholmod_start(&common_);
    common_.print = 0;  // no messages on stdout (a normal run is quiet)
    common_.quick_return_if_not_posdef = 1;
    // Supernodal (dense BLAS kernels) where the factor's flops per nonzero
    // pay for them, simplicial otherwise (CHOLMOD's own switch): measured, the
    // two match Eigen's SimplicialLDLT on the small built-in scenes
    // (projected_newton, 20 steps: cloth 3.7 against 3.5 ms/step,
    // twisted_bar_3d 4.6 against 4.3) and beat it from about 10^4 unknowns
    // (cloth grid 40: 18 against 23 ms/step, hanging_square grid 41: 43
    // against 60, ball_drop_3d: 17 against 24).
    common_.supernodal = CHOLMOD_AUTO;
    // LL^T also when simplicial (CHOLMOD's simplicial default is LDL^T, which
    // factorises indefinite matrices without a word): a non-positive pivot
    // is the definiteness test the Newton methods rely on.
    common_.final_ll = 1;
    common_.nmethods = 1;
    common_.method[0].ordering = ordering == FillOrdering::kAmd ? CHOLMOD_AMD : CHOLMOD_METIS;
    common_.postorder = 1;
  }
  ~CholmodCholesky() override {
    if (factor_ != nullptr) cholmod_free_factor(&factor_, &common_);
    cholmod_finish(&common_);
  }

  bool Analyze(const Eigen::SparseMatrix<double>& lower,
               const std::vector<int>* permutation) override {
    SerialOpenMp serial;
    if (factor_ != nullptr) cholmod_free_factor(&factor_, &common_);
    cholmod_sparse a = View(lower);
    given_ = permutation != nullptr && static_cast<int>(permutation->size()) == lower.rows();
    if (given_) {
      common_.method[0].ordering = CHOLMOD_GIVEN;
      factor_ = cholmod_analyze_p(&a, const_cast<int*>(permutation->data()), nullptr, 0, &common_);
    } else {
      common_.method[0].ordering = ordering_ == FillOrdering::kAmd ? CHOLMOD_AMD : CHOLMOD_METIS;
      factor_ = cholmod_analyze(&a, &common_);
    }
    return factor_ != nullptr && common_.status >= CHOLMOD_OK;
  }

  Result Factorize(const Eigen::SparseMatrix<double>& lower) override {
    if (factor_ == nullptr) return Result::kFailure;
    SerialOpenMp serial;
    cholmod_sparse a = View(lower);
    factored_ = false;
    cholmod_factorize(&a, factor_, &common_);
    if (common_.status == CHOLMOD_NOT_POSDEF || factor_->minor < factor_->n) {
      return Result::kNotPositiveDefinite;
    }
    if (common_.status < CHOLMOD_OK) return Result::kFailure;
    factored_ = true;
    return Result::kSuccess;
  }

  bool Solve(const Eigen::VectorXd& rhs, Eigen::VectorXd* solution) override {
    if (!factored_) return false;
    cholmod_dense b{};
    b.nrow = static_cast<size_t>(rhs.size());
    b.ncol = 1;
    b.nzmax = b.nrow;
    b.d = b.nrow;
    b.x = const_cast<double*>(rhs.data());
    b.z = nullptr;
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    SerialOpenMp serial;
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, factor_, &b, &common_);
    if (x == nullptr) return false;
    *solution = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x->x), rhs.size());
    cholmod_free_dense(&x, &common_);
    return solution->allFinite();
  }

  std::string Description() const override {
    const bool supernodal = factor_ != nullptr && factor_->is_super;
    return std::string("CHOLMOD ") + (supernodal ? "supernodal" : "simplicial") + " LL^T, " +
           (given_                            ? "nested dissection (METIS) of the nodes"
            : ordering_ == FillOrdering::kAmd ? "AMD"
                                              : "nested dissection (METIS)") +
           " ordering";
  }

  double FactorNonZeros() const override { return common_.lnz; }

 private:
  FillOrdering ordering_;
  cholmod_common common_{};
  cholmod_factor* factor_ = nullptr;
  bool factored_ = false;
  bool given_ = false;
};

class EigenLdlt : public SparseCholesky {
 public:
  bool Analyze(const Eigen::SparseMatrix<double>& lower, const std::vector<int>*) override {
    ldlt_.analyzePattern(lower);
    return ldlt_.info() == Eigen::Success;
  }
  Result Factorize(const Eigen::SparseMatrix<double>& lower) override {
    ldlt_.factorize(lower);
    if (ldlt_.info() != Eigen::Success) return Result::kFailure;
    return ldlt_.vectorD().minCoeff() > 0.0 ? Result::kSuccess : Result::kNotPositiveDefinite;
  }
  bool Solve(const Eigen::VectorXd& rhs, Eigen::VectorXd* solution) override {
    *solution = ldlt_.solve(rhs);
    return solution->allFinite();
  }
  std::string Description() const override { return "Eigen SimplicialLDLT, AMD ordering"; }
  double FactorNonZeros() const override {
    return static_cast<double>(ldlt_.matrixL().nestedExpression().nonZeros());
  }

 private:
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt_;
};

}  // namespace

FillOrdering ChooseOrdering(int dimension, int unknowns) {
  return dimension == 3 && unknowns >= kNestedDissectionMinDofs ? FillOrdering::kNestedDissection
                                                                : FillOrdering::kAmd;
}

const char* SparseLibraryName(SparseLibrary library) {
  return library == SparseLibrary::kSuiteSparse ? "SUITE_SPARSE" : "EIGEN_SPARSE";
}

const char* FillOrderingName(FillOrdering ordering) {
  switch (ordering) {
    case FillOrdering::kAutomatic:
      return "AUTOMATIC";
    case FillOrdering::kAmd:
      return "AMD";
    case FillOrdering::kNestedDissection:
      return "NESDIS";
  }
  return "AUTOMATIC";
}

std::unique_ptr<SparseCholesky> SparseCholesky::Create(SparseLibrary library,
                                                       FillOrdering ordering) {
  if (library == SparseLibrary::kEigen) return std::make_unique<EigenLdlt>();
  return std::make_unique<CholmodCholesky>(ordering);
}

}  // namespace ipstep
