#include "ricci/flow/linear_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>

#include "ricci/flow/serial_blas.h"
#include "ricci/mesh/errors.h"
#include "ricci/util/parallel.h"
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
using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

// CHOLMOD's supernodal LLT, with the ordering it chose readable.
class CholmodSupernodal : public Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> {
 public:
  // Values L stores (supernodal: xsize, padding of merged supernodes included); 0 before an
  // analysis.
  double entries() const {
    return m_cholmodFactor ? static_cast<double>(m_cholmodFactor->xsize) : 0.0;
  }

  // Perm of the analysed factor: L L^T = A(perm, perm); empty before an analysis.
  Eigen::VectorXi ordering() const {
    if (!m_cholmodFactor || !m_cholmodFactor->Perm) return {};
    return Eigen::Map<const Eigen::VectorXi>(static_cast<const int*>(m_cholmodFactor->Perm),
                                             static_cast<Eigen::Index>(m_cholmodFactor->n));
  }

  // x = A^-1 b for the columns [first, first + count) of b into the same columns of x, on the
  // calling thread with a CHOLMOD workspace of its own (the factor is only read).
  void solve_range(const Eigen::MatrixXd& b, Eigen::MatrixXd& x, Eigen::Index first,
                   Eigen::Index count) const {
    const SerialOpenMpScope serial_openmp;
    cholmod_common common;
    cholmod_start(&common);
    common.print = 0;
    cholmod_dense view{};
    view.nrow = static_cast<size_t>(b.rows());
    view.ncol = static_cast<size_t>(count);
    view.nzmax = view.nrow * view.ncol;
    view.d = view.nrow;
    view.x = const_cast<double*>(b.data() + first * b.rows());
    view.xtype = CHOLMOD_REAL;
    view.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* solved = cholmod_solve(CHOLMOD_A, m_cholmodFactor, &view, &common);
    // (b's columns are read by then: x may be b.)
    if (solved) {
      x.middleCols(first, count) =
          Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(solved->x), b.rows(), count);
      cholmod_free_dense(&solved, &common);
    } else {
      x.middleCols(first, count).setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    cholmod_finish(&common);
  }
};

// From this many unknowns a blocked back-substitution with several columns splits them over
// the pool's threads (each pass reads the whole factor; below it the threads cost more than
// they spare: docs/design-notes.md, "Split back-substitutions").
constexpr Eigen::Index kSplitColumnsFrom = 20000;
}  // namespace

struct SymmetricFactorization::Impl {
  // CHOLMOD's BLAS calls run on the calling thread while a factorisation exists: OpenBLAS'
  // spinning workers gain nothing on a surface mesh's small supernodes and, when the cores are
  // busy, made a 100k-vertex factorisation 3-7x slower (docs/design-notes.md, "Serial BLAS").
  SerialBlasScope serial_blas;
  Eigen::SimplicialLDLT<Sparse, Eigen::Lower> eigen_ldlt;
  Eigen::SimplicialLLT<Sparse, Eigen::Lower> eigen_llt;
  CholmodSupernodal cholmod_supernodal;
  Eigen::CholmodSimplicialLDLT<Sparse, Eigen::Lower> cholmod_simplicial;
  // With a given ordering g (analyze with an ordering): CHOLMOD factors B = A(g, g) in its
  // natural order, `given` maps b to b(g) (given * b), given^T back. Size 0 otherwise.
  Permutation given;
  // Nonzeros of L predicted by the last analysis that ordered afresh, of this factorisation or
  // of the one whose ordering it took (CHOLMOD only).
  double fresh_fill = 0.0;
  LinearWork work;

  void count_solve(Eigen::Index columns) {
    ++work.back_substitutions;
    work.right_hand_sides += static_cast<int>(columns);
  }

  // The lower triangle of A(g, g).
  Sparse permuted(const Sparse& lower) const {
    Sparse b(lower.rows(), lower.cols());
    b.selfadjointView<Eigen::Lower>() = lower.selfadjointView<Eigen::Lower>().twistedBy(given);
    return b;
  }
};

LinearSolver resolve_linear_solver(LinearSolver kind, Eigen::Index unknowns) {
  if (kind != LinearSolver::automatic) return kind;
  return unknowns < 20000 ? LinearSolver::eigen_ldlt : LinearSolver::cholmod_supernodal;
}

SymmetricFactorization::SymmetricFactorization(LinearSolver kind,
                                               Eigen::Index compact_supernodes_from)
    : kind_(kind == LinearSolver::automatic ? LinearSolver::cholmod_supernodal : kind),
      compact_supernodes_from_(compact_supernodes_from),
      impl_(std::make_unique<Impl>()) {
  // CHOLMOD reports a non-positive-definite matrix on stderr unless told not to; the caller
  // handles the failure (libraries never print).
  impl_->cholmod_supernodal.cholmod().print = 0;
  impl_->cholmod_simplicial.cholmod().print = 0;
  // AMD alone orders: by default CHOLMOD also runs METIS where AMD's factor looks costly
  // (large meshes), which at 800k unknowns took 4-5 s to save 1-3 s of the factorisation; our
  // factorisations serve a few solves each (docs/design-notes.md, "Memory and orderings at
  // 1.6M faces").
  for (cholmod_common* common : {&impl_->cholmod_supernodal.cholmod(),
                                 &impl_->cholmod_simplicial.cholmod()}) {
    common->nmethods = 1;
    common->method[0].ordering = CHOLMOD_AMD;
  }
}

SymmetricFactorization::~SymmetricFactorization() = default;

void SymmetricFactorization::relax_supernodes(Eigen::Index unknowns) {
  // CHOLMOD's defaults, or at most 8 columns merged into supernodes of 4-16 (not 16-48):
  // measured at 800k unknowns, 80.2M stored values against 86.8M for the same 65.5M nonzeros.
  const bool compact = unknowns >= compact_supernodes_from_;
  cholmod_common& common = impl_->cholmod_supernodal.cholmod();
  common.nrelax[0] = 4;
  common.nrelax[1] = compact ? 8 : 16;
  common.nrelax[2] = compact ? 16 : 48;
}

void SymmetricFactorization::analyze(const Sparse& lower) {
  const SerialOpenMpScope serial_openmp;
  impl_->given = Permutation();
  switch (kind_) {
    case LinearSolver::eigen_ldlt:
      impl_->eigen_ldlt.analyzePattern(lower);
      break;
    case LinearSolver::eigen_llt:
      impl_->eigen_llt.analyzePattern(lower);
      break;
    case LinearSolver::cholmod_supernodal:
      relax_supernodes(lower.rows());
      impl_->cholmod_supernodal.analyzePattern(lower);
      impl_->fresh_fill = impl_->cholmod_supernodal.cholmod().lnz;
      break;
    default: impl_->cholmod_simplicial.analyzePattern(lower); break;
  }
}

bool SymmetricFactorization::analyze(const Sparse& lower, const Eigen::VectorXi& ordering,
                                     double fill) {
  const SerialOpenMpScope serial_openmp;
  if (kind_ != LinearSolver::cholmod_supernodal || ordering.size() != lower.rows()) {
    analyze(lower);
    return false;
  }
  // given * b = b(ordering): its indices are the inverse of `ordering`.
  impl_->given = Permutation(ordering).inverse();
  cholmod_common& common = impl_->cholmod_supernodal.cholmod();
  const int methods = common.nmethods, method = common.method[0].ordering;
  common.nmethods = 1;
  common.method[0].ordering = CHOLMOD_NATURAL;
  relax_supernodes(lower.rows());
  impl_->cholmod_supernodal.analyzePattern(impl_->permuted(lower));
  const double given_fill = common.lnz;
  common.nmethods = methods;
  common.method[0].ordering = method;
  // A pattern too far from the ordering's: order afresh.
  impl_->fresh_fill = fill;
  if (fill > 0 && given_fill > 1.1 * fill) {
    analyze(lower);
    return false;
  }
  return true;
}

Eigen::VectorXi SymmetricFactorization::ordering() const {
  if (kind_ != LinearSolver::cholmod_supernodal) return {};
  const Eigen::VectorXi own = impl_->cholmod_supernodal.ordering();
  if (impl_->given.size() == 0 || own.size() == 0) return own;
  // CHOLMOD ordered B = A(g, g) by q (its postorder): A's order is g(q).
  const Eigen::VectorXi g = Permutation(impl_->given.inverse()).indices();
  Eigen::VectorXi composed(own.size());
  for (Eigen::Index k = 0; k < own.size(); ++k) composed[k] = g[own[k]];
  return composed;
}

double SymmetricFactorization::fill() const { return impl_->fresh_fill; }

double SymmetricFactorization::factor_entries() const {
  return kind_ == LinearSolver::cholmod_supernodal ? impl_->cholmod_supernodal.entries() : 0.0;
}

LinearWork SymmetricFactorization::work() const { return impl_->work; }

bool SymmetricFactorization::factorize(const Sparse& lower) {
  const SerialOpenMpScope serial_openmp;
  ++impl_->work.factorizations;
  switch (kind_) {
    case LinearSolver::eigen_ldlt:
      impl_->eigen_ldlt.factorize(lower);
      return impl_->eigen_ldlt.info() == Eigen::Success;
    case LinearSolver::eigen_llt:
      impl_->eigen_llt.factorize(lower);
      return impl_->eigen_llt.info() == Eigen::Success;
    case LinearSolver::cholmod_supernodal:
      if (impl_->given.size() > 0) {
        impl_->cholmod_supernodal.factorize(impl_->permuted(lower));
      } else {
        impl_->cholmod_supernodal.factorize(lower);
      }
      return impl_->cholmod_supernodal.info() == Eigen::Success;
    default:
      impl_->cholmod_simplicial.factorize(lower);
      return impl_->cholmod_simplicial.info() == Eigen::Success;
  }
}

Eigen::VectorXd SymmetricFactorization::solve(const Eigen::VectorXd& rhs) const {
  const SerialOpenMpScope serial_openmp;
  impl_->count_solve(1);
  switch (kind_) {
    case LinearSolver::eigen_ldlt:
      return impl_->eigen_ldlt.solve(rhs);
    case LinearSolver::eigen_llt:
      return impl_->eigen_llt.solve(rhs);
    case LinearSolver::cholmod_supernodal:
      if (impl_->given.size() > 0) {
        const Eigen::VectorXd permuted_rhs = impl_->given * rhs;
        const Eigen::VectorXd y = impl_->cholmod_supernodal.solve(permuted_rhs);
        return impl_->given.transpose() * y;
      }
      return impl_->cholmod_supernodal.solve(rhs);
    default: return impl_->cholmod_simplicial.solve(rhs);
  }
}

Eigen::MatrixXd SymmetricFactorization::solve_columns(const Eigen::MatrixXd& rhs) const {
  const SerialOpenMpScope serial_openmp;
  impl_->count_solve(rhs.cols());
  switch (kind_) {
    case LinearSolver::eigen_ldlt:
      return impl_->eigen_ldlt.solve(rhs);
    case LinearSolver::eigen_llt:
      return impl_->eigen_llt.solve(rhs);
    case LinearSolver::cholmod_supernodal:
      if (impl_->given.size() > 0) {
        const Eigen::MatrixXd permuted_rhs = impl_->given * rhs;
        const Eigen::MatrixXd y = impl_->cholmod_supernodal.solve(permuted_rhs);
        return impl_->given.transpose() * y;
      }
      if (splits(rhs)) {
        Eigen::MatrixXd x(rhs.rows(), rhs.cols());
        split_solve(rhs, x);
        return x;
      }
      return impl_->cholmod_supernodal.solve(rhs);
    default: return impl_->cholmod_simplicial.solve(rhs);
  }
}

void SymmetricFactorization::solve_columns_in_place(Eigen::MatrixXd& columns) const {
  if (!splits(columns)) {
    columns = solve_columns(columns);
    return;
  }
  impl_->count_solve(columns.cols());
  split_solve(columns, columns);
}

bool SymmetricFactorization::splits(const Eigen::MatrixXd& rhs) const {
  return kind_ == LinearSolver::cholmod_supernodal && impl_->given.size() == 0 &&
         rhs.rows() >= kSplitColumnsFrom && rhs.cols() >= 2;
}

void SymmetricFactorization::split_solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) const {
  const int workers = static_cast<int>(std::min<Eigen::Index>(requested_threads(0), b.cols()));
  // Each worker reads and writes its own columns only, so b and x may be one matrix.
  run_workers(workers, [&](int t) {
    const Eigen::Index first = b.cols() * t / workers, last = b.cols() * (t + 1) / workers;
    impl_->cholmod_supernodal.solve_range(b, x, first, last - first);
  });
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
    // At this rate the steps left (11 - i are checked) cannot reach even the stalled bound:
    // stop now rather than after them (the caller factorises).
    const double reachable = std::max(1e-8, relative_tolerance) * rhs.norm();
    if (i >= 1 && std::log(reachable / norm) / std::log(norm / previous) > 11 - i) return false;
    previous = norm;
    x += nearby.solve(residual);
  }
  return false;
}

bool solve_by_preconditioned_cg(const SymmetricFactorization& nearby, const Sparse& lower,
                                const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
                                double relative_tolerance, int max_steps) {
  x = Eigen::VectorXd::Zero(rhs.size());
  const double goal = relative_tolerance * rhs.norm();
  Eigen::VectorXd r = rhs;
  double first = r.norm();
  if (first <= goal) return true;
  Eigen::VectorXd z = nearby.solve(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  for (int step = 1; step <= max_steps; ++step) {
    const Eigen::VectorXd hp = lower.selfadjointView<Eigen::Lower>() * p;
    const double php = p.dot(hp);
    if (!(php > 0) || !(rz > 0)) return false;  // not positive definite (or rounding)
    const double alpha = rz / php;
    x += alpha * p;
    r -= alpha * hp;
    const double norm = r.norm();
    if (norm <= goal) return x.allFinite();
    // At the mean rate so far, the steps left cannot reach the goal: stop now (not before the
    // third step: the residual of conjugate gradients need not fall at every step).
    const double rate = std::pow(norm / first, 1.0 / step);
    if (step >= 3 && (!(rate < 1) || std::log(goal / norm) / std::log(rate) > max_steps - step)) {
      return false;
    }
    z = nearby.solve(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return false;
}

std::shared_ptr<SymmetricFactorization> FactorizationCache::get(LinearSolver kind,
                                                                const Sparse& lower,
                                                                double& analysis_seconds,
                                                                OrderingReuse reuse) {
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
  // Same size, other pattern (flips): the cached factorisation's ordering serves, and the
  // ordering is most of an analysis on large meshes.
  Eigen::VectorXi ordering;
  double fill = 0.0;
  const bool offered = reuse == OrderingReuse::offer ||
                       (reuse == OrderingReuse::until_rejected && orderings_rejected_ == 0);
  if (factorization_ && factorization_->kind() == resolved && offered &&
      lower.rows() == static_cast<Eigen::Index>(outer_.size()) - 1) {
    ordering = factorization_->ordering();
    fill = factorization_->fill();
  }
  factorization_.reset();  // its factor goes before the new one is made
  factorization_ = std::make_shared<SymmetricFactorization>(resolved);
  if (ordering.size() > 0) {
    ++(factorization_->analyze(lower, ordering, fill) ? orderings_reused_ : orderings_rejected_);
  } else {
    factorization_->analyze(lower);
  }
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
