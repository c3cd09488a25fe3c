#pragma once
// Sparse symmetric factorisation for Newton's method: the pattern is analysed once (ordering,
// symbolic factorisation) and only the numeric factorisation is redone per iteration.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace ricci {

/// Which sparse factorisation Newton uses.
enum class LinearSolver {
  automatic,           ///< measured default: eigen_ldlt below 20k unknowns, else cholmod_supernodal
  eigen_ldlt,          ///< Eigen::SimplicialLDLT (also handles indefinite matrices)
  eigen_llt,           ///< Eigen::SimplicialLLT
  cholmod_supernodal,  ///< CHOLMOD supernodal LLT (BLAS level 3)
  cholmod_simplicial   ///< CHOLMOD simplicial LDLT
};

std::string to_string(LinearSolver solver);

/// The factorisation `automatic` stands for at this size (others are returned as they are): Eigen's
/// LDLT below 20k unknowns, CHOLMOD supernodal above (msp-bench solvers measures both).
[[nodiscard]] LinearSolver resolve_linear_solver(LinearSolver kind, Eigen::Index unknowns);

/// Linear-system work, counted in passes over a sparse factor: numeric factorisations and
/// back-substitutions (a blocked back-substitution of several right-hand sides is one pass).
struct LinearWork {
  int factorizations = 0;      ///< numeric factorisations tried (failed ones too)
  int back_substitutions = 0;  ///< passes over a factor: a blocked solve counts once
  int right_hand_sides = 0;    ///< columns solved for, over all passes
  /// factorizations + back_substitutions: the work in solves of the matrix's size.
  [[nodiscard]] int solves() const { return factorizations + back_substitutions; }
  LinearWork& operator+=(const LinearWork& other) {
    factorizations += other.factorizations;
    back_substitutions += other.back_substitutions;
    right_hand_sides += other.right_hand_sides;
    return *this;
  }
  friend LinearWork operator-(LinearWork a, const LinearWork& b) {
    a.factorizations -= b.factorizations;
    a.back_substitutions -= b.back_substitutions;
    a.right_hand_sides -= b.right_hand_sides;
    return a;
  }
};

/// A factorisation of a symmetric matrix given by its lower triangle (compressed columns).
/// While one exists, the process' OpenBLAS runs on one thread (serial_blas.h).
class SymmetricFactorization {
 public:
  /// Unknowns from which cholmod_supernodal merges fewer supernodes by default (see the
  /// constructor).
  static constexpr Eigen::Index kCompactSupernodesFrom = 400000;

  /// A factorisation of `kind` (automatic: cholmod_supernodal). From `compact_supernodes_from`
  /// unknowns the supernodal analysis relaxes its amalgamation (CHOLMOD's nrelax 4, 8, 16
  /// columns instead of 4, 16, 48): merged supernodes store fewer explicit zeros, the factor
  /// has the same nonzeros and is ~8% smaller at 800k unknowns, its factorisation ~10% slower
  /// (docs/design-notes.md, "Compact supernodes at 1.6M faces"). Results below that size are unchanged.
  explicit SymmetricFactorization(LinearSolver kind,
                                  Eigen::Index compact_supernodes_from = kCompactSupernodesFrom);
  ~SymmetricFactorization();
  SymmetricFactorization(const SymmetricFactorization&) = delete;
  SymmetricFactorization& operator=(const SymmetricFactorization&) = delete;

  /// Symbolic analysis of the pattern; call again only if the pattern changes.
  void analyze(const Eigen::SparseMatrix<double>& lower);
  /// The same with a given fill-reducing ordering (another factorisation's ordering(), of a
  /// matrix of this size whose pattern differs a little, e.g. by flips), which spares the
  /// ordering (most of an analysis on large meshes). Orders afresh when the factor
  /// would have over 1.1 times `fill` nonzeros (the other's fill(); 0: no check), when the
  /// ordering's size differs, and for the kinds other than cholmod_supernodal. Returns whether
  /// the given ordering was kept.
  bool analyze(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXi& ordering,
               double fill);
  /// The analysed fill-reducing ordering (L L^T = A(p, p)); empty except for
  /// cholmod_supernodal.
  [[nodiscard]] Eigen::VectorXi ordering() const;
  /// Nonzeros of the factor predicted by the last analysis that ordered afresh, here or for
  /// the factorisation whose ordering this one took (0 except for cholmod_supernodal).
  [[nodiscard]] double fill() const;
  /// Numbers the analysed factor stores (cholmod_supernodal: L's values, the explicit zeros of
  /// merged supernodes included; 0 for the other kinds and before an analysis).
  [[nodiscard]] double factor_entries() const;
  /// Numeric factorisation. Returns false if it failed (not positive definite, zero pivot).
  bool factorize(const Eigen::SparseMatrix<double>& lower);
  /// Solves with the last successful factorisation.
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  /// Solves for every column of `rhs` at once (blocked back-substitution). From 20k unknowns
  /// (cholmod_supernodal, natural analysis) the columns are split over the pool's threads
  /// (ricci/util/parallel.h), each solving its share with the same factor.
  [[nodiscard]] Eigen::MatrixXd solve_columns(const Eigen::MatrixXd& rhs) const;
  /// solve_columns with the solutions written over `columns` (its right-hand sides): one
  /// block fewer in memory where the columns are split over threads (a block of 12 columns of
  /// 800k unknowns is 77 MB, beside the factor).
  void solve_columns_in_place(Eigen::MatrixXd& columns) const;

  LinearSolver kind() const { return kind_; }
  /// The factorisations and back-substitutions this object has done.
  [[nodiscard]] LinearWork work() const;

 private:
  struct Impl;
  // Whether solve_columns splits these right-hand sides over the pool's threads.
  [[nodiscard]] bool splits(const Eigen::MatrixXd& rhs) const;
  // The columns of b over the pool's threads, their solutions written into x (b may be x).
  void split_solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) const;

  // CHOLMOD's supernode amalgamation for a matrix of this many unknowns.
  void relax_supernodes(Eigen::Index unknowns);

  LinearSolver kind_;
  Eigen::Index compact_supernodes_from_;
  std::unique_ptr<Impl> impl_;
};

/// Adds to `total`, when it goes out of scope, the work `factorization` did since it was made:
/// one caller's share of a factorisation that others use too.
class LinearWorkMeter {
 public:
  LinearWorkMeter(const SymmetricFactorization& factorization, LinearWork& total)
      : factorization_(factorization), total_(total), before_(factorization.work()) {}
  ~LinearWorkMeter() { total_ += factorization_.work() - before_; }
  LinearWorkMeter(const LinearWorkMeter&) = delete;
  LinearWorkMeter& operator=(const LinearWorkMeter&) = delete;

 private:
  const SymmetricFactorization& factorization_;
  LinearWork& total_;
  LinearWork before_;
};

/// Solves H x = rhs (H by its lower triangle) with the factorisation of a nearby matrix F (an
/// earlier Newton step's, same size): x += F⁻¹(rhs - H x), a stationary iteration converging at
/// rate ‖I - F⁻¹H‖. F's pattern may differ from H's (flips). Returns false when it is not fast
/// (then factorise H): each step must cut the residual by 0.3, and it must end below
/// relative_tolerance ‖rhs‖ (1e-8 when rounding stalls it first); it stops early when, at
/// the rate observed, its 12 steps cannot reach that.
/// \pre `nearby` holds a successful factorisation.
[[nodiscard]] bool solve_with_nearby_factorization(const SymmetricFactorization& nearby,
                                                   const Eigen::SparseMatrix<double>& lower,
                                                   const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
                                                   double relative_tolerance = 1e-12);

/// The same system by conjugate gradients preconditioned with `nearby` (x starts at 0): where
/// F⁻¹H has eigenvalues in [1 - d, 1 + d] it gains about d / 2 per step where the stationary
/// iteration gains d, and it converges (more slowly) where d >= 1, e.g. with the factorisation
/// of an earlier, farther iterate. Returns true when the residual is below relative_tolerance
/// ‖rhs‖ within max_steps back-substitutions; false when not (x then holds the last iterate),
/// also as soon as, at the rate observed, the steps left cannot reach it.
/// \pre `nearby` holds a successful factorisation; H symmetric positive definite.
[[nodiscard]] bool solve_by_preconditioned_cg(const SymmetricFactorization& nearby,
                                              const Eigen::SparseMatrix<double>& lower,
                                              const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
                                              double relative_tolerance, int max_steps);

/// Whether FactorizationCache::get offers the cached factorisation's ordering to a new pattern
/// of the same size.
enum class OrderingReuse {
  until_rejected,  ///< until one analysis has rejected it (the cache's own rule)
  offer,           ///< now: the caller knows the pattern is near the cached one
  skip             ///< not now: the caller knows the pattern has drifted far from it
};

/// A factorisation kept across solves whose matrices share one sparsity pattern (the stages of
/// a continuation, retries of a flow on one mesh): the symbolic analysis (ordering, elimination
/// tree, supernodes) runs once. A new pattern of the same size is analysed with the cached
/// factorisation's ordering until one such analysis has rejected it (its fill too large: the
/// pattern drifts away, as under a flow's flips, and each rejection costs a symbolic analysis
/// on top of the fresh one), unless the caller says otherwise (OrderingReuse). One user at a
/// time; not thread-safe.
class FactorizationCache {
 public:
  /// A factorisation of `kind` (resolved by size) analysed for `lower`'s pattern: the cached
  /// one when kind and pattern are the ones it was analysed for, otherwise a new analysis that
  /// replaces the cached one (with its ordering when the size is the same and `reuse` allows).
  /// Adds the time of any analysis to `analysis_seconds`.
  [[nodiscard]] std::shared_ptr<SymmetricFactorization> get(
      LinearSolver kind, const Eigen::SparseMatrix<double>& lower, double& analysis_seconds,
      OrderingReuse reuse = OrderingReuse::until_rejected);
  /// Analyses done and analyses saved so far.
  int analyses() const { return analyses_; }
  int reuses() const { return reuses_; }
  /// Analyses that took the cached factorisation's ordering, and those that tried and ordered
  /// afresh (under until_rejected at most one: no analysis tries after it).
  int orderings_reused() const { return orderings_reused_; }
  int orderings_rejected() const { return orderings_rejected_; }

 private:
  std::shared_ptr<SymmetricFactorization> factorization_;
  std::vector<int> outer_, inner_;
  int analyses_ = 0, reuses_ = 0, orderings_reused_ = 0, orderings_rejected_ = 0;
};

}  // namespace ricci
