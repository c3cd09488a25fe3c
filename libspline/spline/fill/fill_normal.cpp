// The thin-plate energy of a patch space, as rows or as its Gram matrix assembled point by point
// in triangle blocks, and the solve of a patch's normal equations.
#include <Eigen/CholmodSupport>
#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <numeric>
#include <optional>

#include "ricci/flow/serial_blas.h"
#include "ricci/mesh/errors.h"
#include "ricci/util/cross2d.h"
#include "spline/fill/fill_system.h"
#include "spline/tessellate/parallel_for.h"

namespace spline::fill_detail {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

// The thin-plate quadrature points of one triangle where the partition of unity holds, each
// with its functions (ascending function_index) and their weighted second derivatives
// sqrt(weight * area * w) (f_xx, sqrt 2 f_xy, f_yy): the three rows of the point, by column.
struct ThinPlatePoints {
  std::vector<int> functions;
  std::vector<Eigen::Vector3d> rows;  ///< beside functions
  std::vector<int> starts{0};         ///< point p's entries: [starts[p], starts[p + 1])
};

// `candidates`: triangles whose functions may reach triangle k, ascending (nullptr: the space's
// own search per point).
ThinPlatePoints thin_plate_points(const PlanarDmsSpace& space, int k, double weight,
                                  const std::vector<QuadraturePoint>& rule,
                                  const std::vector<int>* candidates) {
  const double factors[3] = {1.0, std::sqrt(2.0), 1.0};
  const auto& t = space.triangulation();
  const Eigen::Vector3i v = t.triangles[static_cast<std::size_t>(k)];
  const Eigen::Vector2d a = t.positions[v[0]], b = t.positions[v[1]], c = t.positions[v[2]];
  const double area = 0.5 * std::abs(ricci::cross2d(b - a, c - a));
  ThinPlatePoints points;
  std::vector<BasisSample> basis;
  for (const auto& q : rule) {
    const double root = std::sqrt(weight * area * q.weight);
    const Eigen::Vector2d u = q.bary[0] * a + q.bary[1] * b + q.bary[2] * c;
    if (candidates != nullptr) {
      basis.clear();
      space.evaluate_basis_of(u, *candidates, TieBreak{}, BasisDerivatives::second, basis);
    } else {
      basis = space.evaluate_basis(u);
    }
    // Near the grid's outer rim functions are missing: there the spline reproduces no affine
    // map, so an affine patch would pay thin-plate energy and bend to avoid it (measured: a
    // planar hole's parametric patch tilted 6 degrees). Those points are left out, and so are
    // points where the second derivatives do not sum to zero: just inside a missing function's
    // support its value is below the partition test's rounding while its curvature is not.
    double sum = 0.0;
    Eigen::Vector3d curvature_sum = Eigen::Vector3d::Zero();
    double curvature_scale = 0.0;
    for (const auto& s : basis) {
      sum += s.jet.value;
      const Eigen::Vector3d h(s.jet.hessian[0], s.jet.hessian[1], s.jet.hessian[2]);
      curvature_sum += h;
      curvature_scale += h.cwiseAbs().sum();
    }
    if (std::abs(sum - 1.0) > 1e-9) continue;
    if (curvature_sum.cwiseAbs().maxCoeff() > 1e-9 * curvature_scale) continue;
    for (const auto& s : basis) {
      points.functions.push_back(space.function_index(s.triangle, s.beta));
      points.rows.push_back(root * Eigen::Vector3d(factors[0] * s.jet.hessian[0],
                                                   factors[1] * s.jet.hessian[1],
                                                   factors[2] * s.jet.hessian[2]));
    }
    points.starts.push_back(static_cast<int>(points.functions.size()));
  }
  return points;
}

// The triangles sharing a vertex with triangle k (k too), ascending: every triangle whose
// functions reach into k. A vertex's knots lie within half the smallest inradius of its
// triangles, less than its distance to the edges opposite it in them (over twice the inradius),
// so the clouds' hull of a triangle J meets k only near a vertex J shares with k.
std::vector<int> vertex_star_triangles(const PlanarTriangulation& t,
                                       const std::vector<std::vector<int>>& stars, int k) {
  std::vector<int> result;
  const Eigen::Vector3i& corners = t.triangles[static_cast<std::size_t>(k)];
  for (int corner = 0; corner < 3; ++corner) {
    const auto& star = stars[static_cast<std::size_t>(corners[corner])];
    result.insert(result.end(), star.begin(), star.end());
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

// The upper block triangle of a symmetric matrix whose unknowns come in groups of `size` (a
// triangle's functions): block (I, J), I <= J, dense, entry (I size + a, J size + b) at
// a size + b. Block rows grow independently, so threads owning disjoint rows may add at once.
class BlockRows {
 public:
  BlockRows(int groups, int size)
      : size_(size), columns_(static_cast<std::size_t>(groups)), values_(columns_.size()) {}

  // Block (row, column), row <= column, added as zeros when new.
  double* block(int row, int column) {
    auto& columns = columns_[static_cast<std::size_t>(row)];
    auto& values = values_[static_cast<std::size_t>(row)];
    const std::size_t area = static_cast<std::size_t>(size_) * size_;
    const auto found = std::find(columns.begin(), columns.end(), column);
    const std::size_t slot = static_cast<std::size_t>(found - columns.begin());
    if (found == columns.end()) {
      columns.push_back(column);
      values.resize(values.size() + area, 0.0);
    }
    return values.data() + slot * area;
  }

  // The matrix with both triangles, entries that stayed exactly zero left out, plus `extra`
  // (square, of groups * size columns, compressed with ascending rows) when given: its entries
  // are added as Eigen's sparse sum would (extra + 0 and 0 + block where only one has the entry,
  // extra + block where both), so the sum is Eigen's to the bit. Block columns in parallel.
  [[nodiscard]] Sparse symmetric(const Sparse* extra = nullptr) const;

 private:
  // By block column J: the blocks (I, J) above the diagonal, I ascending; by block row: its
  // blocks ordered by column.
  struct Index {
    std::vector<std::vector<const double*>> above;
    std::vector<std::vector<int>> above_rows;
    std::vector<std::vector<int>> order;
  };
  [[nodiscard]] Index index() const;
  // One block column's entries, column by column, rows ascending.
  struct Entries {
    std::vector<int> rows;
    std::vector<double> values;
    std::vector<int> ends;  ///< column b's entries end at ends[b]
  };
  [[nodiscard]] Entries block_column(int j, const Index& index, const Sparse* extra) const;

  int size_;
  std::vector<std::vector<int>> columns_;
  std::vector<std::vector<double>> values_;
};

BlockRows::Index BlockRows::index() const {
  const std::size_t area = static_cast<std::size_t>(size_) * size_;
  Index index;
  index.above.resize(columns_.size());
  index.above_rows.resize(columns_.size());
  index.order.resize(columns_.size());
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    const auto& columns = columns_[i];
    auto& o = index.order[i];
    o.resize(columns.size());
    std::iota(o.begin(), o.end(), 0);
    std::sort(o.begin(), o.end(), [&](int x, int y) { return columns[x] < columns[y]; });
    for (int slot : o) {
      const auto j = static_cast<std::size_t>(columns[static_cast<std::size_t>(slot)]);
      if (j == i) continue;
      index.above[j].push_back(values_[i].data() + static_cast<std::size_t>(slot) * area);
      index.above_rows[j].push_back(static_cast<int>(i));
    }
  }
  return index;
}

BlockRows::Entries BlockRows::block_column(int j, const Index& index, const Sparse* extra) const {
  const auto g = static_cast<std::size_t>(j);
  const std::size_t area = static_cast<std::size_t>(size_) * size_;
  const auto& columns = columns_[g];
  Entries out;
  std::size_t expected = (index.above[g].size() + columns.size()) * area;
  if (extra != nullptr) {
    const Eigen::Index first = static_cast<Eigen::Index>(j) * size_;
    expected += static_cast<std::size_t>(extra->outerIndexPtr()[first + size_] -
                                         extra->outerIndexPtr()[first]);
  }
  out.rows.reserve(expected);
  out.values.reserve(expected);
  for (int b = 0; b < size_; ++b) {
    std::optional<Sparse::InnerIterator> other;
    if (extra != nullptr) other.emplace(*extra, j * size_ + b);
    // extra's entries above `row` first, then row's sum.
    const auto put = [&](int row, double value) {
      for (; other && *other && other->row() < row; ++*other) {
        out.rows.push_back(static_cast<int>(other->row()));
        out.values.push_back(other->value() + 0.0);
      }
      if (other && *other && other->row() == row) {
        // A block entry of exactly zero is no entry: Eigen adds its own 0 (+0.0).
        out.rows.push_back(row);
        out.values.push_back(other->value() + (value != 0.0 ? value : 0.0));
        ++*other;
      } else if (value != 0.0) {
        out.rows.push_back(row);
        out.values.push_back(extra != nullptr ? 0.0 + value : value);
      }
    };
    for (std::size_t k = 0; k < index.above[g].size(); ++k) {
      const double* block = index.above[g][k];
      const int i = index.above_rows[g][k];
      for (int a = 0; a < size_; ++a) put(i * size_ + a, block[a * size_ + b]);
    }
    for (int slot : index.order[g]) {  // (j, J), J >= j: transposed
      const double* block = values_[g].data() + static_cast<std::size_t>(slot) * area;
      const int i = columns[static_cast<std::size_t>(slot)];
      for (int a = 0; a < size_; ++a)
        put(i * size_ + a, i == j ? block[a * size_ + b] : block[b * size_ + a]);
    }
    put(std::numeric_limits<int>::max(), 0.0);  // the rest of extra's column
    out.ends.push_back(static_cast<int>(out.rows.size()));
  }
  return out;
}

Sparse BlockRows::symmetric(const Sparse* extra) const {
  const Index blocks = index();
  std::vector<Entries> by_group(columns_.size());
  parallel_for(by_group.size(), 0, [&](std::size_t g) {
    by_group[g] = block_column(static_cast<int>(g), blocks, extra);
  });
  std::vector<std::size_t> first(by_group.size() + 1, 0);
  for (std::size_t g = 0; g < by_group.size(); ++g)
    first[g + 1] = first[g] + by_group[g].rows.size();
  const int n = static_cast<int>(columns_.size()) * size_;
  Sparse matrix(n, n);
  matrix.resizeNonZeros(static_cast<Eigen::Index>(first.back()));
  parallel_for(by_group.size(), 0, [&](std::size_t g) {
    Entries& in = by_group[g];
    std::copy(in.rows.begin(), in.rows.end(), matrix.innerIndexPtr() + first[g]);
    std::copy(in.values.begin(), in.values.end(), matrix.valuePtr() + first[g]);
    for (int b = 0; b < size_; ++b) {
      const std::size_t column = g * static_cast<std::size_t>(size_) + static_cast<std::size_t>(b);
      matrix.outerIndexPtr()[column + 1] = static_cast<int>(first[g] + in.ends[b]);
    }
    in = Entries{};
  });
  matrix.outerIndexPtr()[0] = 0;
  return matrix;
}

// Adds one point's products rows_f . rows_g to the blocks whose row `owner` accepts: pairs of
// the point's triangles (runs of its functions, ascending), the diagonal block in full.
template <class Owner>
void add_point(const ThinPlatePoints& points, int p, int size, const Owner& owner,
               BlockRows& blocks) {
  const int begin = points.starts[static_cast<std::size_t>(p)];
  const int end = points.starts[static_cast<std::size_t>(p) + 1];
  for (int r = begin; r < end;) {
    const int row_group = points.functions[r] / size;
    int r_end = r;
    while (r_end < end && points.functions[r_end] / size == row_group) ++r_end;
    if (owner(row_group)) {
      for (int c = r; c < end;) {
        const int column_group = points.functions[c] / size;
        int c_end = c;
        while (c_end < end && points.functions[c_end] / size == column_group) ++c_end;
        double* block = blocks.block(row_group, column_group);
        for (int x = r; x < r_end; ++x) {
          double* line = block + (points.functions[x] % size) * size;
          for (int y = c; y < c_end; ++y)
            line[points.functions[y] % size] += points.rows[x].dot(points.rows[y]);
        }
        c = c_end;
      }
    }
    r = r_end;
  }
}

}  // namespace

void add_thin_plate_rows(System& system, const PlanarDmsSpace& space, double weight) {
  const auto rule = thin_plate_rule();
  std::vector<ThinPlatePoints> per_triangle(static_cast<std::size_t>(space.triangle_count()));
  parallel_for(per_triangle.size(), 0, [&](std::size_t k) {
    per_triangle[k] = thin_plate_points(space, static_cast<int>(k), weight, rule, nullptr);
  });
  for (const ThinPlatePoints& points : per_triangle) {
    for (std::size_t p = 0; p + 1 < points.starts.size(); ++p) {
      for (int r = 0; r < 3; ++r) {
        const int row = system.next_row();
        for (int e = points.starts[p]; e < points.starts[p + 1]; ++e)
          system.entries.emplace_back(row, points.functions[e], points.rows[e][r]);
        system.targets.push_back(Eigen::Vector3d::Zero());
      }
    }
  }
}

namespace {

// thin_plate_normal with `plus` asked for only when the blocks are summed: plus() may still be
// in the making (on another thread) while the points are evaluated.
template <class Plus>
Sparse thin_plate_normal_plus(const PlanarDmsSpace& space, double weight, const Plus& plus,
                              const std::vector<char>* plain) {
  const auto rule = thin_plate_rule();
  const auto plain_rule = thin_plate_plain_rule();
  const int size = space.functions_per_triangle();
  const int triangles = space.triangle_count();
  BlockRows blocks(triangles, size);
  const PlanarTriangulation& t = space.triangulation();
  std::vector<std::vector<int>> stars(t.positions.size());
  for (int k = 0; k < triangles; ++k) {
    const Eigen::Vector3i& corners = t.triangles[static_cast<std::size_t>(k)];
    for (int corner = 0; corner < 3; ++corner)
      stars[static_cast<std::size_t>(corners[corner])].push_back(k);
  }
  // Chunks of triangles: their points evaluated in parallel, then added by block row, each
  // worker owning the rows of its residue class, in triangle and point order. So the sums do
  // not depend on the number of threads.
  constexpr int kChunk = 512;
  std::vector<ThinPlatePoints> chunk(kChunk);
  for (int first = 0; first < triangles; first += kChunk) {
    const int count = std::min(kChunk, triangles - first);
    parallel_for(static_cast<std::size_t>(count), 0, [&](std::size_t k) {
      const int triangle = first + static_cast<int>(k);
      const std::vector<int> candidates = vertex_star_triangles(t, stars, triangle);
      const bool plain_here = plain != nullptr && (*plain)[static_cast<std::size_t>(triangle)];
      chunk[k] = thin_plate_points(space, triangle, weight, plain_here ? plain_rule : rule,
                                   &candidates);
    });
    const int workers = parallel_thread_count(0, static_cast<std::size_t>(count) * rule.size());
    run_workers(workers, [&](int worker) {
      const auto owner = [&](int group) { return group % workers == worker; };
      for (int k = 0; k < count; ++k) {
        const ThinPlatePoints& points = chunk[static_cast<std::size_t>(k)];
        for (int p = 0; p + 1 < static_cast<int>(points.starts.size()); ++p)
          add_point(points, p, size, owner, blocks);
      }
    });
  }
  return blocks.symmetric(plus());
}

}  // namespace

Sparse thin_plate_normal(const PlanarDmsSpace& space, double weight, const Sparse* plus,
                         const std::vector<char>* plain) {
  return thin_plate_normal_plus(space, weight, [plus] { return plus; }, plain);
}

NormalEquations normal_equations(const System& system, const PlanarDmsSpace& space,
                                 double thin_plate, const std::vector<char>* plain) {
  Sparse a(system.next_row(), space.function_count());
  a.setFromTriplets(system.entries.begin(), system.entries.end());
  Eigen::MatrixX3d b(system.next_row(), 3);
  for (int i = 0; i < system.next_row(); ++i) b.row(i) = system.targets[i].transpose();
  NormalEquations result;
  result.rhs = a.transpose() * b;
  if (!(thin_plate > 0.0)) {
    result.matrix = a.transpose() * a;
    return result;
  }
  // A^T A (one core) made while the thin plate's points are evaluated; added at its end.
  Sparse ata;
  std::future<void> product = std::async(std::launch::async, [&] { ata = a.transpose() * a; });
  result.matrix = thin_plate_normal_plus(
      space, thin_plate,
      [&product, &ata] {
        product.get();
        return &ata;
      },
      plain);
  return result;
}

Eigen::MatrixXd solve_normal_equations(const Sparse& normal, const Eigen::MatrixXd& rhs,
                                       const std::string& what) {
  Eigen::CholmodSupernodalLLT<Sparse> solver;
  solver.cholmod().print = 0;
  // AMD alone orders. CHOLMOD's default also runs METIS when AMD's factor looks costly, as it
  // does here: genus3_100k's cone patch (57,580 functions, 4.9M nonzeros) took 0.78 s to order
  // that way against 0.11 s with AMD, to factorise in 0.59 s instead of 0.71 s (one BLAS
  // thread).
  solver.cholmod().nmethods = 1;
  solver.cholmod().method[0].ordering = CHOLMOD_AMD;
  solver.analyzePattern(normal);
  // One BLAS thread (serial_blas.h), also for the largest patches. OpenBLAS hands each call
  // over to its second thread and waits for it by sched_yield; next to other busy processes
  // each such wait lasts their time slices: helmet.off's parametric cone patch beside two
  // CPU-bound processes spent 67-77 s of wall for 7 s of CPU in its fill with two threads
  // (docs/design-notes.md, "The fill's BLAS on one thread"). On a quiet machine the second
  // thread saved ~28% on the largest (block.off's 188k unknowns, 18.5 -> 13.4 s).
  const ricci::SerialBlasScope serial;
  // CHOLMOD's own OpenMP loops on this thread, as in ricci's SymmetricFactorization
  // (serial_blas.h says why).
  const ricci::SerialOpenMpScope serial_openmp;
  solver.factorize(normal);
  if (solver.info() != Eigen::Success) {
    throw ricci::SolverError("fill_rim: the normal equations of the " + what +
                             " are not positive definite");
  }
  Eigen::MatrixXd x = solver.solve(rhs);
  // One step of iterative refinement: the seam weights make the matrix ill-conditioned.
  x += solver.solve(Eigen::MatrixXd(rhs - normal * x));
  if (!x.allFinite())
    throw ricci::SolverError("fill_rim: the patch solve produced non-finite control points");
  return x;
}

}  // namespace spline::fill_detail
