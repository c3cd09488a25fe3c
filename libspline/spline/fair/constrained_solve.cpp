#include "spline/fair/constrained_solve.h"

#include <Eigen/CholmodSupport>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "ricci/flow/serial_blas.h"
#include "ricci/mesh/errors.h"

namespace spline {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// A row x_i - x_j = 0 (entries +1 and -1 to 1e-12): the pair, else (-1, -1).
std::pair<int, int> merge_pair(const RowSparse& c_rows, int row) {
  std::pair<int, int> out{-1, -1};
  double a = 0.0, b = 0.0;
  int count = 0;
  for (RowSparse::InnerIterator it(c_rows, row); it; ++it) {
    if (it.value() == 0.0) continue;
    if (++count > 2) return {-1, -1};
    (count == 1 ? out.first : out.second) = static_cast<int>(it.index());
    (count == 1 ? a : b) = it.value();
  }
  if (count == 2 && std::abs(a + b) <= 1e-12 && std::abs(std::abs(a) - 1.0) <= 1e-12) return out;
  return {-1, -1};
}

// Class of every unknown after merging the x_i = x_j rows; marks those rows.
std::vector<int> merge_classes(const Sparse& c, std::vector<char>& merged, int& classes) {
  const RowSparse rows = c;
  const int n = static_cast<int>(c.cols());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  merged.assign(static_cast<std::size_t>(c.rows()), 0);
  for (int r = 0; r < c.rows(); ++r) {
    const auto [i, j] = merge_pair(rows, r);
    if (i < 0) continue;
    merged[r] = 1;
    const int a = find_root(parent, i), b = find_root(parent, j);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  std::vector<int> cls(static_cast<std::size_t>(n), -1);
  classes = 0;
  for (int i = 0; i < n; ++i) {
    const int root = find_root(parent, i);
    cls[i] = root == i ? classes++ : cls[root];  // roots are the smallest member: seen first
  }
  return cls;
}

// Lower triangle of P^T K P from the lower triangle of K.
Sparse reduce_lower(const Sparse& k_lower, const std::vector<int>& cls, int classes) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(k_lower.nonZeros()));
  for (int j = 0; j < k_lower.outerSize(); ++j) {
    for (Sparse::InnerIterator it(k_lower, j); it; ++it) {
      const int i = static_cast<int>(it.index());
      if (i < j) continue;
      const int a = cls[i], b = cls[j];
      // An off-diagonal entry stands for K_ij and K_ji: both land on (a, a) when merged.
      const double v = (a == b && i != j) ? 2.0 * it.value() : it.value();
      t.emplace_back(std::max(a, b), std::min(a, b), v);
    }
  }
  Sparse out(classes, classes);
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace

ReducedConstraints reduce_constraints(const Sparse& c) {
  ReducedConstraints out;
  out.rows = c.rows();
  out.unknowns = c.cols();
  std::vector<char> merged;
  out.unknown_class = merge_classes(c, merged, out.classes);
  const std::vector<int>& cls = out.unknown_class;
  std::vector<Eigen::Triplet<double>> t;
  int rows = 0;
  for (int j = 0; j < c.outerSize(); ++j) {
    for (Sparse::InnerIterator it(c, j); it; ++it) {
      if (!merged[it.index()]) t.emplace_back(static_cast<int>(it.index()), cls[j], it.value());
    }
  }
  std::vector<int> row_of(static_cast<std::size_t>(c.rows()), -1);
  for (int r = 0; r < c.rows(); ++r) {
    if (!merged[r]) row_of[r] = rows++;
  }
  for (auto& e : t) e = Eigen::Triplet<double>(row_of[e.row()], e.col(), e.value());
  out.c_r.resize(rows, out.classes);
  out.c_r.setFromTriplets(t.begin(), t.end());
  if (rows > 0) {
    const Sparse ctc = Sparse(out.c_r.transpose()) * out.c_r;
    out.ctc_lower = Sparse(ctc.triangularView<Eigen::Lower>());
  }
  return out;
}

ConstrainedSolution solve_constrained(const Sparse& k_lower, const Eigen::MatrixX3d& b,
                                      const Sparse& c, const Eigen::MatrixX3d& reference,
                                      const ConstrainedSolveOptions& options) {
  return solve_constrained(k_lower, b, c, reduce_constraints(c), reference, options);
}

ConstrainedSolution solve_constrained(const Sparse& k_lower, const Eigen::MatrixX3d& b,
                                      const Sparse& c, const ReducedConstraints& reduced,
                                      const Eigen::MatrixX3d& reference,
                                      const ConstrainedSolveOptions& options) {
  const Eigen::Index n = k_lower.rows();
  if (k_lower.cols() != n || b.rows() != n || c.cols() != n ||
      (reference.rows() != 0 && reference.rows() != n)) {
    throw ricci::InvalidInputError("constrained solve: K " + std::to_string(k_lower.rows()) + "x" +
                                   std::to_string(k_lower.cols()) + ", b " +
                                   std::to_string(b.rows()) + " rows, C " +
                                   std::to_string(c.rows()) + "x" + std::to_string(c.cols()) +
                                   ", reference " + std::to_string(reference.rows()) + " rows");
  }
  if (reduced.rows != c.rows() || reduced.unknowns != n ||
      reduced.unknown_class.size() != static_cast<std::size_t>(n)) {
    throw ricci::InvalidInputError("constrained solve: reduced constraints of a " +
                                   std::to_string(reduced.rows) + "x" +
                                   std::to_string(reduced.unknowns) + " C for a " +
                                   std::to_string(c.rows()) + "x" + std::to_string(c.cols()) +
                                   " one");
  }
  ConstrainedSolution out;
  const std::vector<int>& cls = reduced.unknown_class;
  const int classes = reduced.classes;
  out.reduced_unknowns = classes;
  // Nothing merged (no constraints: the free fit): P = I, and K_r is K's lower triangle itself,
  // not a rebuild through a million triplets (their sort was 2% of a free fit on the Horse row).
  const Sparse k = classes == n ? Sparse(k_lower.triangularView<Eigen::Lower>())
                                : reduce_lower(k_lower, cls, classes);
  Eigen::MatrixX3d br = Eigen::MatrixX3d::Zero(classes, 3), y0 = br;
  Eigen::VectorXd size = Eigen::VectorXd::Zero(classes);
  for (Eigen::Index i = 0; i < n; ++i) {
    br.row(cls[i]) += b.row(i);
    if (reference.rows() != 0) y0.row(cls[i]) += reference.row(i);
    size[cls[i]] += 1.0;
  }
  y0.array().colwise() /= size.array();

  const Sparse& cr = reduced.c_r;
  const auto rows = static_cast<int>(cr.rows());
  out.merged_rows = static_cast<int>(c.rows()) - rows;
  out.remaining_rows = rows;

  const Eigen::MatrixX3d g = br - Eigen::MatrixX3d(k.selfadjointView<Eigen::Lower>() * y0);
  const Eigen::MatrixX3d h = -Eigen::MatrixX3d(cr * y0);
  // One BLAS thread: on these factorisations the second only spins (serial_blas.h).
  const ricci::SerialBlasScope serial_blas;
  const ricci::SerialOpenMpScope serial_openmp;
  Eigen::CholmodSupernodalLLT<Sparse, Eigen::Lower> solver;
  solver.cholmod().print = 0;  // libraries never print; failures are reported by info()
  Eigen::MatrixX3d e;
  if (rows == 0) {
    solver.compute(k);
    if (solver.info() != Eigen::Success) {
      throw ricci::SolverError("constrained solve: CHOLMOD could not factor K (" +
                               std::to_string(classes) + " unknowns)");
    }
    e = solver.solve(g);
  } else {
    double w = options.penalty * k.diagonal().mean();
    for (int attempt = 0;; ++attempt) {
      solver.compute(Sparse(k + w * reduced.ctc_lower));
      if (solver.info() == Eigen::Success) break;
      if (attempt == 3) {
        throw ricci::SolverError("constrained solve: CHOLMOD could not factor K + w C^T C (" +
                                 std::to_string(classes) + " unknowns, w = " + std::to_string(w) +
                                 ")");
      }
      w *= 1e-2;  // rounding made K + w C^T C indefinite: K's small eigenvalues drowned
    }
    out.penalty = w;
    Eigen::MatrixX3d lambda = Eigen::MatrixX3d::Zero(rows, 3);
    const Eigen::MatrixX3d wcth = w * Eigen::MatrixX3d(cr.transpose() * h);
    double previous = std::numeric_limits<double>::infinity();
    for (int it = 0; it < options.max_iterations; ++it) {
      e = solver.solve(Eigen::MatrixX3d(g - cr.transpose() * lambda + wcth));
      if (!e.allFinite()) break;
      const Eigen::MatrixX3d residual = cr * e - h;
      lambda += w * residual;
      out.iterations = it + 1;
      const double scale = std::max((y0 + e).cwiseAbs().maxCoeff(), 1e-300);
      const double size = residual.cwiseAbs().maxCoeff();
      if (size <= options.tolerance * scale) break;
      // Stalled: the factorisation's rounding (cond(K + w C^T C) eps) is the floor.
      if (size > 0.99 * previous) break;
      previous = size;
    }
  }
  if (!e.allFinite()) throw ricci::SolverError("constrained solve: non-finite solution");
  out.x.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) out.x.row(i) = y0.row(cls[i]) + e.row(cls[i]);
  if (c.rows() > 0) out.max_residual = Eigen::MatrixX3d(c * out.x).cwiseAbs().maxCoeff();
  return out;
}

}  // namespace spline
