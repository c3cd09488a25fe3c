// The parametric G1 patch of hole_fill.h: D the rim laid out on a circle, P = sum c_f N_f with
// three coordinates, fitted to the surface's position, tangent plane and (softly) a
// cross-boundary derivative along the rim, plus the thin-plate energy.
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <cmath>

#include "ricci/mesh/errors.h"
#include "ricci/util/cancel.h"
#include "spline/basis/multi_index.h"
#include "spline/fill/fill_system.h"

namespace spline::fill_detail {
namespace {

// Rows coupling the three coordinates: weight * n . D_d P (unknown c * F + f for coordinate c
// of function f). Their target is 0 (D_d P in the surface's tangent plane).
struct TangentRows {
  std::vector<Eigen::Triplet<double>> entries;
  int rows = 0;

  void add(const std::vector<BasisSample>& basis, const PlanarDmsSpace& space,
           const Eigen::Vector2d& direction, const Eigen::Vector3d& normal, double weight) {
    const int functions = space.function_count();
    for (const auto& s : basis) {
      const int f = space.function_index(s.triangle, s.beta);
      const double d = weight * s.jet.gradient.dot(direction);
      for (int c = 0; c < 3; ++c) entries.emplace_back(rows, c * functions + f, d * normal[c]);
    }
    ++rows;
  }
};

// The block diagonal matrix with `copies` copies of `block`.
Eigen::SparseMatrix<double> block_diagonal(const Eigen::SparseMatrix<double>& block, int copies) {
  const Eigen::Index n = block.rows();
  Eigen::SparseMatrix<double> result(copies * n, copies * n);
  result.reserve(copies * block.nonZeros());
  for (int c = 0; c < copies; ++c) {
    for (Eigen::Index k = 0; k < n; ++k) {
      result.startVec(c * n + k);
      for (Eigen::SparseMatrix<double>::InnerIterator it(block, k); it; ++it)
        result.insertBack(c * n + it.row(), c * n + k) = it.value();
    }
  }
  result.finalize();
  return result;
}

// Solves min |A_s x_c - b_c|^2 + weight * thin-plate energy of x_c (each coordinate c;
// thin_plate_normal, weight 0: none) + |A_t x|^2 for the control points.
// \throw ricci::Cancelled when `cancel` is set before the factorisation.
Eigen::MatrixX3d solve_coupled(const System& scalar, const TangentRows& tangent,
                               const PlanarDmsSpace& space, double thin_plate,
                               const Eigen::MatrixX3d& anchor_value, const Rim& rim,
                               const std::atomic<bool>* cancel) {
  const int functions = space.function_count();
  const auto [block, block_rhs] = normal_equations(scalar, space, thin_plate);
  ricci::throw_if_cancelled(cancel, "fill_rim");

  Eigen::SparseMatrix<double> t(tangent.rows, 3 * functions);
  t.setFromTriplets(tangent.entries.begin(), tangent.entries.end());
  Eigen::SparseMatrix<double> normal = t.transpose() * t;
  normal += block_diagonal(block, 3);
  Eigen::VectorXd rhs(3 * functions);
  for (int c = 0; c < 3; ++c) rhs.segment(c * functions, functions) = block_rhs.col(c);
  // A small anchor towards the reference (the affine map best fitting the rim) determines the
  // functions that reach nothing and the combinations the thin-plate quadrature does not see.
  // Towards a constant instead, it bends those combinations between the quadrature points
  // whenever the patch is not constant (measured: a planar hole's patch tilted 6 degrees).
  const double anchor = 1e-9 * normal.diagonal().sum() / (3.0 * functions);
  for (int c = 0; c < 3; ++c) {
    for (int f = 0; f < functions; ++f) {
      normal.coeffRef(c * functions + f, c * functions + f) += anchor;
      rhs[c * functions + f] += anchor * anchor_value(f, c);
    }
  }
  const Eigen::VectorXd x =
      solve_normal_equations(normal, rhs, "parametric patch of the " + rim_name(rim));
  Eigen::MatrixX3d points(functions, 3);
  for (int c = 0; c < 3; ++c) points.col(c) = x.segment(c * functions, functions);
  return points;
}

// Control points of the affine map u -> o + M u fitting the rim's samples at D's boundary points
// in the least-squares sense.
Eigen::MatrixX3d affine_reference(const HoleFill& fill,
                                  const std::vector<std::vector<RimSample>>& samples,
                                  const PlanarDmsSpace& space) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rhs = Eigen::Matrix3d::Zero();
  for (std::size_t j = 0; j < samples.size(); ++j) {
    for (std::size_t i = 0; i + 1 < samples[j].size(); ++i) {
      const Eigen::Vector2d u = fill.boundary_points[j][i];
      const Eigen::Vector3d row(1.0, u.x(), u.y());
      normal += row * row.transpose();
      rhs += row * samples[j][i].jet.position.transpose();
    }
  }
  const Eigen::Matrix3d map = normal.ldlt().solve(rhs);  // rows: o, M e_x, M e_y
  const Eigen::MatrixXd plane = identity_control_points(space);
  Eigen::MatrixX3d reference(space.function_count(), 3);
  for (int f = 0; f < space.function_count(); ++f) {
    reference.row(f) = map.row(0) + plane(f, 0) * map.row(1) + plane(f, 1) * map.row(2);
  }
  return reference;
}

}  // namespace

HoleFill fill_parametric(const Rim& rim, const std::vector<std::vector<RimSample>>& samples,
                         const FillOptions& options, const std::vector<int>& refinements) {
  const int m = static_cast<int>(rim.edges.size());
  const int q = static_cast<int>(samples[0].size()) - 1;
  HoleFill fill;
  fill.rim = rim;
  std::vector<Eigen::Vector2d> polygon = layout_by_development(samples, fill);
  if (polygon.empty()) polygon = layout_on_circle(samples, fill);
  const double perimeter = polygon_perimeter(polygon);
  const int boundary_vertices =
      std::max(8, std::min(options.refinement * m, options.max_boundary_vertices));
  const double h = perimeter / boundary_vertices;
  fill.space = patch_space(polygon, h, options.degree, options.knots, fill.corners, refinements,
                           1.0, grid_keep_distance(options, h));
  ricci::throw_if_cancelled(options.cancel, "fill_rim");
  const PlanarDmsSpace& space = *fill.space;
  // An orthonormal frame around the mean normal (informative: P is no height field).
  const Eigen::Vector3d helper =
      std::abs(fill.normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  fill.axes.col(0) = helper.cross(fill.normal).normalized();
  fill.axes.col(1) = fill.normal.cross(fill.axes.col(0));

  // Weights: position rows in units of length; derivative rows (dimensionless: D's lengths are
  // about the surface's) scaled by h to match; R^2 int |H|^2 likewise. So the patch scales with
  // the mesh.
  const double count = static_cast<double>(m) * q;
  const double w_position = std::sqrt(options.position_weight / count);
  // The derivative rows' length scale: the mean rim edge, not h (a finer patch must not weaken
  // them against the thin plate).
  const double scale = perimeter / m;
  const double w_tangent = std::sqrt(options.tangent_weight / count) * scale;
  const double w_cross = std::sqrt(options.cross_weight / count) * scale;
  System scalar;
  TangentRows tangent_rows;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < q; ++i) {  // t = 1 is the next edge's t = 0
      const RimSample& s = samples[j][i];
      const Eigen::Vector3d n = s.jet.normal;
      const Eigen::Vector2d tangent = fill.boundary_tangents[j][i];
      const double speed = tangent.norm();
      const Eigen::Vector2d along = tangent / speed;
      // D runs clockwise in rim order: its inside is on the right of `along`.
      const Eigen::Vector2d inward(along.y(), -along.x());
      const auto basis = space.evaluate_basis(fill.boundary_points[j][i]);
      scalar.add(basis, space, nullptr, s.jet.position, w_position);
      // G1: both derivatives of P in the surface's tangent plane.
      tangent_rows.add(basis, space, along, n, w_tangent);
      tangent_rows.add(basis, space, inward, n, w_tangent);
      // The in-plane Jacobian, softly: along D's boundary the rim's own derivative; across it
      // the tangent-plane vector of the same length pointing into the hole, rate x n (with D's
      // clockwise boundary this makes P_x x P_y point along n: the surface's orientation). It
      // keeps P from folding or collapsing.
      const Eigen::Vector3d rate = s.along_derivative / speed;
      const Eigen::Vector3d across = rate.cross(n);
      scalar.add(basis, space, &along, rate, w_cross);
      scalar.add(basis, space, &inward, across, w_cross);
    }
  }
  const double radius = perimeter / (2.0 * M_PI);
  fill.control_points = solve_coupled(scalar, tangent_rows, space,
                                      options.smoothing * radius * radius,
                                      affine_reference(fill, samples, space), rim,
                                      options.cancel);
  return fill;
}

}  // namespace spline::fill_detail
