#include "spline/basis/planar_space.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "ricci/mesh/errors.h"
#include "spline/basis/multi_index.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

// The grid cell of coordinate c (in cells, finite or infinite), clamped to [0, count - 1] in
// double: converting a far point's cell to int first overflows (undefined behaviour).
int clamped_cell(double c, int count) {
  return static_cast<int>(std::clamp(std::floor(c), 0.0, static_cast<double>(count - 1)));
}

}  // namespace

PlanarDmsSpace::PlanarDmsSpace(PlanarTriangulation triangulation, std::vector<KnotCloud> clouds)
    : triangulation_(std::move(triangulation)), clouds_(std::move(clouds)) {
  validate(triangulation_);
  if (clouds_.size() != triangulation_.positions.size()) {
    throw ricci::InvalidInputError("planar DMS space: " + std::to_string(clouds_.size()) +
                                   " knot clouds for " +
                                   std::to_string(triangulation_.positions.size()) + " vertices");
  }
  degree_ = clouds_.empty() ? 0 : clouds_[0].degree();
  if (degree_ < 1 || degree_ > kMaxDmsDegree) {
    throw ricci::InvalidInputError("planar DMS space: degree " + std::to_string(degree_) +
                                   " outside 1.." + std::to_string(kMaxDmsDegree));
  }
  for (std::size_t v = 0; v < clouds_.size(); ++v) {
    if (clouds_[v].degree() != degree_ || clouds_[v].knots[0] != triangulation_.positions[v]) {
      throw ricci::InvalidInputError("planar DMS space: knot cloud of vertex " +
                                     std::to_string(v) +
                                     " has another degree or does not start at its vertex");
    }
  }
  // Each triangle's basis into its own slot, in parallel (a cone patch has thousands).
  const auto& triangles = triangulation_.triangles;
  std::vector<std::optional<TriangleBasis>> built(triangles.size());
  parallel_for(triangles.size(), 0, [&](std::size_t k) {
    const Eigen::Vector3i& tri = triangles[k];
    built[k].emplace(clouds_[static_cast<std::size_t>(tri[0])],
                     clouds_[static_cast<std::size_t>(tri[1])],
                     clouds_[static_cast<std::size_t>(tri[2])]);
  });
  bases_.reserve(triangles.size());
  for (auto& basis : built) bases_.push_back(std::move(*basis));
  build_grid();
}

void PlanarDmsSpace::build_grid() {
  if (bases_.empty()) return;
  Eigen::Vector2d lo = bases_[0].box_min(), hi = bases_[0].box_max();
  double total_extent = 0.0;
  for (const TriangleBasis& b : bases_) {
    lo = lo.cwiseMin(b.box_min());
    hi = hi.cwiseMax(b.box_max());
    total_extent += (b.box_max() - b.box_min()).maxCoeff();
  }
  // Cells about the size of a triangle: a handful of candidates per query.
  cell_size_ = std::max(total_extent / static_cast<double>(bases_.size()),
                        1e-12 * std::max(1.0, (hi - lo).maxCoeff()));
  const double max_cells = 4.0 * static_cast<double>(bases_.size()) + 16.0;
  while (((hi - lo).x() / cell_size_ + 1.0) * ((hi - lo).y() / cell_size_ + 1.0) > max_cells) {
    cell_size_ *= 2.0;
  }
  grid_origin_ = lo;
  columns_ = static_cast<int>((hi - lo).x() / cell_size_) + 1;
  rows_ = static_cast<int>((hi - lo).y() / cell_size_) + 1;
  cells_.assign(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_), {});
  for (std::size_t t = 0; t < bases_.size(); ++t) {
    const Eigen::Vector2d a = (bases_[t].box_min() - lo) / cell_size_;
    const Eigen::Vector2d b = (bases_[t].box_max() - lo) / cell_size_;
    const int x0 = std::clamp(static_cast<int>(a.x()), 0, columns_ - 1);
    const int x1 = std::clamp(static_cast<int>(b.x()), 0, columns_ - 1);
    const int y0 = std::clamp(static_cast<int>(a.y()), 0, rows_ - 1);
    const int y1 = std::clamp(static_cast<int>(b.y()), 0, rows_ - 1);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        cells_[static_cast<std::size_t>(y) * static_cast<std::size_t>(columns_) +
               static_cast<std::size_t>(x)]
            .push_back(static_cast<int>(t));
      }
    }
  }
}

std::vector<int> PlanarDmsSpace::grid_triangles(const Eigen::Vector2d& u) const {
  std::vector<int> result;
  if (cells_.empty() || !u.allFinite()) return result;
  const Eigen::Vector2d g = (u - grid_origin_) / cell_size_;
  // A point on a cell border may belong to a box of the neighbouring cell: look at both.
  const int x0 = clamped_cell(g.x() - 1e-9, columns_);
  const int x1 = clamped_cell(g.x() + 1e-9, columns_);
  const int y0 = clamped_cell(g.y() - 1e-9, rows_);
  const int y1 = clamped_cell(g.y() + 1e-9, rows_);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      for (int t : cells_[static_cast<std::size_t>(y) * static_cast<std::size_t>(columns_) +
                          static_cast<std::size_t>(x)]) {
        result.push_back(t);
      }
    }
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

std::vector<int> PlanarDmsSpace::candidate_triangles(const Eigen::Vector2d& u) const {
  std::vector<int> result = grid_triangles(u);
  result.erase(std::remove_if(result.begin(), result.end(),
                              [&](int t) { return !bases_[static_cast<std::size_t>(t)].in_hull(u); }),
               result.end());
  return result;
}

std::vector<BasisFunctionId> PlanarDmsSpace::support(const Eigen::Vector2d& u) const {
  std::vector<BasisFunctionId> result;
  for (int t : candidate_triangles(u)) {
    const TriangleBasis& b = bases_[static_cast<std::size_t>(t)];
    for (int i = 0; i < b.size(); ++i) {
      if (b.in_support(i, u)) result.push_back({t, i});
    }
  }
  return result;
}

std::vector<BasisSample> PlanarDmsSpace::evaluate_basis(const Eigen::Vector2d& u,
                                                        const TieBreak& tie,
                                                        BasisDerivatives derivatives) const {
  std::vector<BasisSample> result;
  evaluate_basis_of(u, grid_triangles(u), tie, derivatives, result);
  return result;
}

void PlanarDmsSpace::evaluate_basis_of(const Eigen::Vector2d& u, const std::vector<int>& triangles,
                                       const TieBreak& tie, BasisDerivatives derivatives,
                                       std::vector<BasisSample>& out) const {
  // Per-thread scratch: evaluation is called per point in hot loops, and the DAG state is a few
  // KB (allocating it per call cost as much as a cheap evaluation).
  thread_local std::vector<Jet> jets;
  thread_local std::vector<double> values;
  thread_local SimplexSplineDag::Scratch dag_scratch;
  for (int t : triangles) {
    const TriangleBasis& basis = bases_[static_cast<std::size_t>(t)];
    if (!basis.in_hull(u)) continue;
    if (derivatives == BasisDerivatives::none) {
      basis.evaluate_values(u, tie, values, dag_scratch);
      for (std::size_t i = 0; i < values.size(); ++i) {
        if (values[i] == 0.0) continue;
        BasisSample sample{t, static_cast<int>(i), Jet{}};
        sample.jet.value = values[i];
        out.push_back(sample);
      }
      continue;
    }
    basis.evaluate(u, tie, jets, dag_scratch, derivatives);
    for (std::size_t i = 0; i < jets.size(); ++i) {
      const Jet& j = jets[i];
      // (BasisDerivatives::first leaves the Hessians zero.)
      if (j.value != 0.0 || !j.gradient.isZero(0.0) || !j.hessian.isZero(0.0)) {
        out.push_back({t, static_cast<int>(i), j});
      }
    }
  }
}

void PlanarDmsSpace::check_rows(const Eigen::Ref<const Eigen::MatrixXd>& control_points) const {
  if (control_points.rows() != function_count()) {
    throw ricci::InvalidInputError("planar DMS space: " + std::to_string(control_points.rows()) +
                                   " control points for " + std::to_string(function_count()) +
                                   " basis functions");
  }
}

SplineJet PlanarDmsSpace::evaluate(const Eigen::Ref<const Eigen::MatrixXd>& control_points,
                                   const Eigen::Vector2d& u, const TieBreak& tie) const {
  check_rows(control_points);
  // Per-thread scratch, as in evaluate_basis_of: patches are evaluated point by point.
  thread_local std::vector<BasisSample> samples;
  samples.clear();
  evaluate_basis_of(u, grid_triangles(u), tie, BasisDerivatives::second, samples);
  const Eigen::Index k = control_points.cols();
  if (k == 3) return sum_jets<3>(control_points, samples);
  return sum_jets<Eigen::Dynamic>(control_points, samples);
}

template <int K>
SplineJet PlanarDmsSpace::sum_jets(const Eigen::Ref<const Eigen::MatrixXd>& control_points,
                                   const std::vector<BasisSample>& samples) const {
  // Fixed-size accumulators for the common K = 3 (a patch in space): no allocation per
  // sample; the same products summed in the same order as the dynamic case.
  const Eigen::Index k = control_points.cols();
  Eigen::Matrix<double, K, 1> value = Eigen::Matrix<double, K, 1>::Zero(k);
  Eigen::Matrix<double, K, 2> gradient = Eigen::Matrix<double, K, 2>::Zero(k, 2);
  Eigen::Matrix<double, K, 3> hessian = Eigen::Matrix<double, K, 3>::Zero(k, 3);
  for (const BasisSample& s : samples) {
    const Eigen::Matrix<double, K, 1> c =
        control_points.row(function_index(s.triangle, s.beta)).transpose();
    value += s.jet.value * c;
    gradient += c * s.jet.gradient.transpose();
    hessian += c * s.jet.hessian.transpose();
  }
  return SplineJet{value, gradient, hessian};
}

Eigen::MatrixXd PlanarDmsSpace::evaluate_directional(
    const Eigen::Ref<const Eigen::MatrixXd>& control_points, const Eigen::Vector2d& u,
    const Eigen::Vector2d& direction, int max_order, const TieBreak& tie) const {
  check_rows(control_points);
  if (max_order < 0) throw ricci::InvalidInputError("planar DMS space: negative derivative order");
  const std::size_t stride = static_cast<std::size_t>(max_order) + 1;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(max_order + 1, control_points.cols());
  std::vector<double> values, scratch;
  for (int t : candidate_triangles(u)) {
    const TriangleBasis& b = bases_[static_cast<std::size_t>(t)];
    b.evaluate_directional(u, direction, max_order, tie, values, scratch);
    for (int i = 0; i < b.size(); ++i) {
      for (std::size_t order = 0; order < stride; ++order) {
        out.row(static_cast<Eigen::Index>(order)) +=
            values[static_cast<std::size_t>(i) * stride + order] *
            control_points.row(function_index(t, i));
      }
    }
  }
  return out;
}

Eigen::MatrixXd PlanarDmsSpace::control_points_of(const BivariatePolynomial& p) const {
  Eigen::MatrixXd result(function_count(), p.coefficients.cols());
  for (std::size_t t = 0; t < triangulation_.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = triangulation_.triangles[t];
    result.middleRows(function_index(static_cast<int>(t), 0), functions_per_triangle()) =
        triangle_control_points(p, clouds_[static_cast<std::size_t>(tri[0])],
                                clouds_[static_cast<std::size_t>(tri[1])],
                                clouds_[static_cast<std::size_t>(tri[2])]);
  }
  return result;
}

}  // namespace spline
