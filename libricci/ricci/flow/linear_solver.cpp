#include "ricci/flow/linear_solver.h"

#include <algorithm>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>

#include "ricci/flow/serial_blas.h"
#include "ricci/mesh/errors.h"
#include "ricci/util/stopwatch.h"

namespace ricci {

std::string to_string(LinearSolver solver) {
  switch (solver) {
    case LinearSolver::automatic:
      return "auto";
    case LinearSolver::eigen_ldlt:
      return "eigen-ldlt";
    case LinearSolver::eigen_llt:
      return "eigen-llt";
    case LinearSolver::cholmod_supernodal:
      return "cholmod-supernodal";
    default: return "cholmod-simplicial";
  }
}

namespace {
using Sparse = Eigen::SparseMatrix<double>;
}  // namespace

struct SymmetricFactorization::Impl {
  // CHOLMOD's BLAS calls run on the calling thread while a factorisation exists: OpenBLAS'
  // spinning workers gain nothing on a surface mesh's small supernodes and, when the cores are
  // busy, made a 100k-vertex factorisation 3-7x slower (docs/design-notes.md, "Serial BLAS").
  SerialBlasScope serial_blas;
  Eigen::SimplicialLDLT<Sparse, Eigen::Lower> eigen_ldlt;
  Eigen::SimplicialLLT<Sparse, Eigen::Lower> eigen_llt;
  Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> cholmod_supernodal;
  Eigen::CholmodSimplicialLDLT<Sparse, Eigen::Lower> cholmod_simplicial;
};

LinearSolver resolve_linear_solver(LinearSolver kind, Eigen::Index unknowns) {
  if (kind != LinearSolver::automatic) return kind;
  return unknowns < 20000 ? LinearSolver::eigen_ldlt : LinearSolver::cholmod_supernodal;
}

SymmetricFactorization::SymmetricFactorization(LinearSolver kind)
    : kind_(kind == LinearSolver::automatic ? LinearSolver::cholmod_supernodal : kind),
      impl_(std::make_unique<Impl>()) {
  // CHOLMOD reports a non-positive-definite matrix on stderr unless told not to; the caller
  // handles the failure (libraries never print).
  impl_->cholmod_supernodal.cholmod().print = 0;
  impl_->cholmod_simplicial.cholmod().print = 0;
}

SymmetricFactorization::~SymmetricFactorization() = default;

void SymmetricFactorization::analyze(const Sparse& lower) {
  switch (kind_) {
    case LinearSolver::eigen_ldlt:
      impl_->eigen_ldlt.analyzePattern(lower);
      break;
    case LinearSolver::eigen_llt:
      impl_->eigen_llt.analyzePattern(lower);
      break;
    case LinearSolver::cholmod_supernodal:
      impl_->cholmod_supernodal.analyzePattern(lower);
      break;
    default: impl_->cholmod_simplicial.analyzePattern(lower); break;
  }
}

bool SymmetricFactorization::factorize(const Sparse& lower) {
  switch (kind_) {
    case LinearSolver::eigen_ldlt:
      impl_->eigen_ldlt.factorize(lower);
      return impl_->eigen_ldlt.info() == Eigen::Success;
    case LinearSolver::eigen_llt:
      impl_->eigen_llt.factorize(lower);
      return impl_->eigen_llt.info() == Eigen::Success;
    case LinearSolver::cholmod_supernodal:
      impl_->cholmod_supernodal.factorize(lower);
      return impl_->cholmod_supernodal.info() == Eigen::Success;
    default:
      impl_->cholmod_simplicial.factorize(lower);
      return impl_->cholmod_simplicial.info() == Eigen::Success;
  }
}

Eigen::VectorXd SymmetricFactorization::solve(const Eigen::VectorXd& rhs) const {
  switch (kind_) {
    case LinearSolver::eigen_ldlt:
      return impl_->eigen_ldlt.solve(rhs);
    case LinearSolver::eigen_llt:
      return impl_->eigen_llt.solve(rhs);
    case LinearSolver::cholmod_supernodal:
      return impl_->cholmod_supernodal.solve(rhs);
    default: return impl_->cholmod_simplicial.solve(rhs);
  }
}

Eigen::MatrixXd SymmetricFactorization::solve_columns(const Eigen::MatrixXd& rhs) const {
  switch (kind_) {
    case LinearSolver::eigen_ldlt:
      return impl_->eigen_ldlt.solve(rhs);
    case LinearSolver::eigen_llt:
      return impl_->eigen_llt.solve(rhs);
    case LinearSolver::cholmod_supernodal:
      return impl_->cholmod_supernodal.solve(rhs);
    default: return impl_->cholmod_simplicial.solve(rhs);
  }
}

bool solve_with_nearby_factorization(const SymmetricFactorization& nearby, const Sparse& lower,
                                     const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
                                     double relative_tolerance) {
  x = nearby.solve(rhs);
  double previous = rhs.norm();
  for (int i = 0; i < 12 && x.allFinite(); ++i) {
    const Eigen::VectorXd residual = rhs - lower.selfadjointView<Eigen::Lower>() * x;
    const double norm = residual.norm();
    // Rounding floors the residual near eps·cond(H)·‖rhs‖ (H is a Laplacian, cond ~ #V), so
    // stop when it stalls; an inexact step with relative residual 1e-8 still converges fast.
    if (norm <= relative_tolerance * rhs.norm()) return true;
    if (!(norm < 0.3 * previous)) return norm <= std::max(1e-8, relative_tolerance) * rhs.norm();
    previous = norm;
    x += nearby.solve(residual);
  }
  return false;
}

std::shared_ptr<SymmetricFactorization> FactorizationCache::get(LinearSolver kind,
                                                                const Sparse& lower,
                                                                double& analysis_seconds) {
  const LinearSolver resolved = resolve_linear_solver(kind, lower.rows());
  const int columns = static_cast<int>(lower.outerSize());
  const int* outer = lower.outerIndexPtr();
  const int* inner = lower.innerIndexPtr();
  const auto nonzeros = static_cast<size_t>(outer[columns]);
  const bool same = factorization_ && factorization_->kind() == resolved &&
                    lower.isCompressed() && outer_.size() == static_cast<size_t>(columns) + 1 &&
                    inner_.size() == nonzeros && std::equal(outer_.begin(), outer_.end(), outer) &&
                    std::equal(inner_.begin(), inner_.end(), inner);
  if (same) {
    ++reuses_;
    return factorization_;
  }
  const Stopwatch clock;
  factorization_ = std::make_shared<SymmetricFactorization>(resolved);
  factorization_->analyze(lower);
  analysis_seconds += clock.seconds();
  ++analyses_;
  if (lower.isCompressed()) {
    outer_.assign(outer, outer + columns + 1);
    inner_.assign(inner, inner + nonzeros);
  } else {
    outer_.clear();  // an uncompressed pattern is never matched: analyse each time
    inner_.clear();
  }
  return factorization_;
}

}  // namespace ricci
