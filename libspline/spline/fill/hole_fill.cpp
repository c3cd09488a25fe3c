// fill_rim: the least-squares G1 patch of hole_fill.h.
#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/errors.h"
#include "spline/fill/hole_fill.h"
#include "spline/fill/patch_domain.h"

namespace spline {
namespace {

using fill_detail::RimSample;

// Dunavant's 6-point rule, exact for degree 4 (the thin-plate integrand of a cubic piece has
// degree 2): barycentric points and weights summing to one.
struct QuadraturePoint {
  Eigen::Vector3d bary;
  double weight;
};
std::vector<QuadraturePoint> quadrature_rule() {
  const double a = 0.445948490915965, wa = 0.223381589678011;
  const double b = 0.091576213509771, wb = 0.109951743655322;
  return {{{a, a, 1 - 2 * a}, wa}, {{a, 1 - 2 * a, a}, wa}, {{1 - 2 * a, a, a}, wa},
          {{b, b, 1 - 2 * b}, wb}, {{b, 1 - 2 * b, b}, wb}, {{1 - 2 * b, b, b}, wb}};
}

void check_options(const FillOptions& o) {
  const bool ok = o.degree >= 1 && o.degree <= kMaxDmsDegree && o.refinement >= 1 &&
                  o.max_boundary_vertices >= 8 && o.samples_per_edge >= 1 &&
                  o.fit_samples_per_edge >= 1 && o.position_weight > 0.0 &&
                  o.tangent_weight >= 0.0 && o.cross_weight >= 0.0 && o.smoothing >= 0.0;
  if (!ok) {
    throw ricci::InvalidInputError(
        "fill_rim: options out of range (degree 1..7, refinement >= 1, max_boundary_vertices >= "
        "8, samples >= 1, position_weight > 0, other weights >= 0)");
  }
}

double bounding_diagonal(const ricci::Mesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = ricci::to_eigen(mesh.point(v));
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

const char* kind_name(Rim::Kind kind) {
  switch (kind) {
    case Rim::Kind::cone_hole: return "cone hole";
    case Rim::Kind::boundary: return "boundary loop";
    case Rim::Kind::excluded: return "excluded-face hole";
  }
  return "rim";
}

bool segments_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d) {
  auto side = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    const double v = (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
    return (v > 0) - (v < 0);
  };
  return side(a, b, c) * side(a, b, d) <= 0 && side(c, d, a) * side(c, d, b) <= 0;
}

// Boundary loops: the rim's corner points projected onto their least-squares plane must form a
// simple polygon, else the patch (a disk spanning the loop) would fold.
void check_simple_projection(const std::vector<Eigen::Vector3d>& points, const Rim& rim) {
  const int m = static_cast<int>(points.size());
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= m;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(cov);
  const Eigen::Vector3d x = eigen.eigenvectors().col(2), y = eigen.eigenvectors().col(1);
  std::vector<Eigen::Vector2d> q;
  for (const auto& p : points) q.emplace_back((p - mean).dot(x), (p - mean).dot(y));
  for (int i = 0; i < m; ++i) {
    for (int j = i + 2; j < m; ++j) {
      if (i == 0 && j == m - 1) continue;  // adjacent through the wrap
      if (segments_cross(q[i], q[(i + 1) % m], q[j], q[(j + 1) % m])) {
        throw ricci::InvalidInputError(
            std::string("fill_rim: the ") + kind_name(rim.kind) + " of " + std::to_string(m) +
            " edges starting at face " + std::to_string(rim.edges[0].face) +
            " is not a simple polygon in its least-squares plane (edges " + std::to_string(i) +
            " and " + std::to_string(j) + " cross); it cannot be filled by a planar patch");
      }
    }
  }
}

// Rows of the least-squares system over unknowns (coordinate c, function f) -> c * F + f.
struct System {
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> rhs;
  int rows = 0;
  int functions = 0;

  // One scalar row: sum over samples of weight * coefficient[c] * value.
  void add_coupled(const std::vector<BasisSample>& basis, const PlanarDmsSpace& space,
                   const Eigen::Vector2d& direction, const Eigen::Vector3d& coefficient,
                   double weight, double target) {
    for (const auto& s : basis) {
      const int f = space.function_index(s.triangle, s.beta);
      const double d = s.jet.gradient.dot(direction);
      for (int c = 0; c < 3; ++c) {
        if (coefficient[c] != 0.0)
          triplets.emplace_back(rows, c * functions + f, weight * coefficient[c] * d);
      }
    }
    rhs.push_back(weight * target);
    ++rows;
  }
};

// Jet of a basis sample in the direction d (d = 0: the value).
double directional(const BasisSample& s, const Eigen::Vector2d* d) {
  return d ? s.jet.gradient.dot(*d) : s.jet.value;
}

// Three rows (one per coordinate) of weight * (D_d P - target).
void add_vector_rows(System& system, const std::vector<BasisSample>& basis,
                     const PlanarDmsSpace& space, const Eigen::Vector2d* direction,
                     const Eigen::Vector3d& target, double weight) {
  for (int c = 0; c < 3; ++c) {
    for (const auto& s : basis) {
      system.triplets.emplace_back(system.rows,
                                   c * system.functions + space.function_index(s.triangle, s.beta),
                                   weight * directional(s, direction));
    }
    system.rhs.push_back(weight * target[c]);
    ++system.rows;
  }
}

struct Layout {
  std::vector<Eigen::Vector2d> corners;        // D, clockwise in rim order
  std::vector<std::vector<RimSample>> samples;  // by edge, fit samples t = i / q, i = 0..q
};

Layout lay_out(const ManifoldSpline& spline, const Rim& rim, int q) {
  Layout layout;
  std::vector<double> lengths;
  for (const RimEdge& e : rim.edges) {
    std::vector<RimSample> row;
    double length = 0.0;
    for (int i = 0; i <= q; ++i) {
      row.push_back(fill_detail::sample_rim(spline, e, static_cast<double>(i) / q));
      if (i > 0) length += (row[i].jet.position - row[i - 1].jet.position).norm();
    }
    lengths.push_back(length);
    layout.samples.push_back(std::move(row));
  }
  layout.corners = fill_detail::circle_layout(lengths);
  return layout;
}

// The patch's space: nested rings over D and one ring of collar outside it.
std::shared_ptr<const PlanarDmsSpace> patch_space(const std::vector<Eigen::Vector2d>& corners,
                                                  int boundary_vertices, int degree,
                                                  const KnotCloudOptions& knots) {
  const std::vector<Eigen::Vector2d> shape(corners.rbegin(), corners.rend());  // CCW
  const double perimeter = fill_detail::polygon_perimeter(shape);
  const double spacing = perimeter / boundary_vertices;
  const double apothem = 2.0 * fill_detail::polygon_area(shape) / perimeter;
  const double step = 0.5 * std::sqrt(3.0) * spacing / apothem;
  const double collar = 1.0 + step;
  const int outer_count = static_cast<int>(std::lround(perimeter * collar / spacing));
  const auto outer =
      fill_detail::sample_scaled_polygon(shape, Eigen::Vector2d::Zero(), collar, outer_count);
  PlanarTriangulation t = fill_detail::nested_rings(
      outer, shape, Eigen::Vector2d::Zero(), fill_detail::ring_scales(1.0, step), spacing);
  auto clouds = make_knot_clouds(t, degree, knots);
  return std::make_shared<const PlanarDmsSpace>(std::move(t), std::move(clouds));
}

Eigen::MatrixX3d solve(const System& system, int functions, const Eigen::Vector3d& anchor_point,
                       const Rim& rim) {
  const int n = 3 * functions;
  Eigen::SparseMatrix<double> a(system.rows, n);
  a.setFromTriplets(system.triplets.begin(), system.triplets.end());
  const Eigen::Map<const Eigen::VectorXd> b(system.rhs.data(), system.rows);
  Eigen::SparseMatrix<double> normal = (a.transpose() * a).pruned();
  Eigen::VectorXd rhs = a.transpose() * b;
  // A tiny anchor towards the rim's centroid: functions reaching nothing stay determined, and
  // the anchor moves with the data (translation equivariance).
  const double anchor = 1e-12 * normal.diagonal().sum() / n;
  for (int i = 0; i < n; ++i) {
    normal.coeffRef(i, i) += anchor;
    rhs[i] += anchor * anchor_point[i / functions];
  }
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success) {
    throw ricci::SolverError("fill_rim: the normal equations of the " +
                             std::string(kind_name(rim.kind)) + " at face " +
                             std::to_string(rim.edges[0].face) + " are not positive definite");
  }
  Eigen::VectorXd x = solver.solve(rhs);
  // One step of iterative refinement: the seam weights make the matrix ill-conditioned.
  x += solver.solve(rhs - normal * x);
  if (!x.allFinite())
    throw ricci::SolverError("fill_rim: the patch solve produced non-finite control points");
  Eigen::MatrixX3d points(functions, 3);
  for (int c = 0; c < 3; ++c) points.col(c) = x.segment(c * functions, functions);
  return points;
}

}  // namespace

Eigen::Vector2d HoleFill::parameter(int edge, double t) const {
  const int m = static_cast<int>(corners.size());
  const int j = ((edge % m) + m) % m;
  return (1.0 - t) * corners[j] + t * corners[(j + 1) % m];
}

SplineJet HoleFill::jet(const Eigen::Vector2d& u) const {
  return space->evaluate(control_points, u);
}

PatchPoint HoleFill::evaluate(const Eigen::Vector2d& u) const {
  const SplineJet j = jet(u);
  PatchPoint p;
  p.position = j.value;
  p.du = j.gradient.col(0);
  p.dv = j.gradient.col(1);
  const Eigen::Vector3d n = p.du.cross(p.dv);
  const double length = n.norm();
  if (length > 0.0) p.normal = n / length;
  return p;
}

HoleFill fill_rim(const ManifoldSpline& spline, const ricci::Mesh& domain_mesh, const Rim& rim,
                  const FillOptions& options) {
  check_options(options);
  const int m = static_cast<int>(rim.edges.size());
  if (m < 3) {
    throw ricci::InvalidInputError("fill_rim: a rim needs at least 3 edges, got " +
                                   std::to_string(m));
  }
  const int q = options.fit_samples_per_edge;
  const Layout layout = lay_out(spline, rim, q);
  if (rim.kind == Rim::Kind::boundary && options.require_simple_projection) {
    std::vector<Eigen::Vector3d> points;
    for (const auto& row : layout.samples) points.push_back(row[0].jet.position);
    check_simple_projection(points, rim);
  }

  HoleFill fill;
  fill.rim = rim;
  fill.corners = layout.corners;
  fill.diagonal = bounding_diagonal(domain_mesh);
  const int boundary_vertices = std::min(options.refinement * m, options.max_boundary_vertices);
  fill.space = patch_space(fill.corners, std::max(boundary_vertices, 8), options.degree,
                           options.knots);
  const PlanarDmsSpace& space = *fill.space;

  // Weights (hole_fill.h): every term has units of length^2, so the solution scales with the
  // mesh; h is the patch's boundary spacing.
  const double perimeter = fill_detail::polygon_perimeter(fill.corners);
  const double h = perimeter / std::max(boundary_vertices, 8);
  const double samples = static_cast<double>(m) * q;
  const double w_position = std::sqrt(options.position_weight / samples);
  const double w_tangent = std::sqrt(options.tangent_weight / samples) * h;
  const double w_cross = std::sqrt(options.cross_weight / samples) * h;

  System system;
  system.functions = space.function_count();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int j = 0; j < m; ++j) {
    const Eigen::Vector2d p0 = fill.corners[j], p1 = fill.corners[(j + 1) % m];
    const Eigen::Vector2d along = (p1 - p0).normalized();
    const Eigen::Vector2d inward(along.y(), -along.x());  // D lies right of the rim direction
    const double scale = layout.samples[j][0].chart_length / (p1 - p0).norm();
    for (int i = 0; i < q; ++i) {  // t = 1 is the next edge's t = 0
      const RimSample& s = layout.samples[j][i];
      const auto basis = space.evaluate_basis(fill.parameter(j, static_cast<double>(i) / q));
      add_vector_rows(system, basis, space, nullptr, s.jet.position, w_position);
      system.add_coupled(basis, space, along, s.jet.normal, w_tangent, 0.0);
      system.add_coupled(basis, space, inward, s.jet.normal, w_tangent, 0.0);
      add_vector_rows(system, basis, space, &inward, scale * s.outward_derivative, w_cross);
      centroid += s.jet.position;
    }
  }
  centroid /= samples;

  if (options.smoothing > 0.0) {
    const double area = std::abs(fill_detail::polygon_area(fill.corners));
    const double w = options.smoothing * std::pow(h, 4) / area;
    const auto rule = quadrature_rule();
    const auto& t = space.triangulation();
    for (int k = 0; k < space.triangle_count(); ++k) {
      const Eigen::Vector3i v = t.triangles[k];
      const Eigen::Vector2d a = t.positions[v[0]], b = t.positions[v[1]], c = t.positions[v[2]];
      const double triangle_area = 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
      for (const auto& qp : rule) {
        const double root = std::sqrt(w * triangle_area * qp.weight);
        const auto basis = space.evaluate_basis(qp.bary[0] * a + qp.bary[1] * b + qp.bary[2] * c);
        for (int c3 = 0; c3 < 3; ++c3) {
          const double factors[3] = {1.0, std::sqrt(2.0), 1.0};
          for (int r = 0; r < 3; ++r) {
            for (const auto& s : basis) {
              system.triplets.emplace_back(
                  system.rows, c3 * system.functions + space.function_index(s.triangle, s.beta),
                  root * factors[r] * s.jet.hessian[r]);
            }
            system.rhs.push_back(0.0);
            ++system.rows;
          }
        }
      }
    }
  }
  fill.control_points = solve(system, space.function_count(), centroid, rim);

  const SeamReport report = measure_seam(spline, fill, options.samples_per_edge);
  fill.max_normal_jump_deg = report.max_normal_jump_deg;
  fill.max_position_gap = report.max_position_gap;
  fill.rms_position_gap = report.rms_position_gap;
  fill.seam_samples = report.samples;
  return fill;
}

}  // namespace spline
