// fill_rim: the least-squares G1 patch of hole_fill.h.
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/util/cancel.h"
#include "spline/basis/blossom.h"
#include "spline/basis/multi_index.h"
#include "spline/fill/hole_fill.h"
#include "spline/fill/fill_system.h"
#include "spline/fill/patch_domain.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

using fill_detail::identity_control_points;
using fill_detail::patch_space;
using fill_detail::polygon_mean;
using fill_detail::System;
using fill_detail::rim_name;
using fill_detail::RimSample;

void check_options(const FillOptions& o) {
  const bool ok = o.degree >= 1 && o.degree <= kMaxDmsDegree && o.refinement >= 1 &&
                  o.corner_refinement >= 1 && o.mild_corner_refinement >= 1 &&
                  o.mild_corner_step_deg >= 0.0 && o.max_refined_rim_step_deg > 0.0 &&
                  o.outside_corner_grading >= 1.0 &&
                  (o.grid_margin < 0.0 || o.grid_margin >= 1.0) &&
                  o.max_boundary_vertices >= 8 && o.samples_per_edge >= 1 &&
                  o.fit_samples_per_edge >= 1 && o.parametric_samples_per_edge >= 1 && o.position_weight > 0.0 &&
                  o.tangent_weight >= 0.0 && o.cross_weight >= 0.0 && o.smoothing >= 0.0 && o.min_normal_cosine > 0.0 &&
                  o.min_normal_cosine < 1.0;
  if (!ok) {
    throw ricci::InvalidInputError(
        "fill_rim: options out of range (degree 1..7, refinements >= 1, mild_corner_step_deg >= 0, "
        "outside_corner_grading >= 1, grid_margin >= 1 or negative, "
        "max_boundary_vertices >= "
        "8, samples >= 1, position_weight > 0, other weights >= 0, min_normal_cosine in (0, 1))");
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

// Solves min |A c - b|^2 + weight * thin-plate energy (the rows of `system` and
// thin_plate_normal, `plain` its plain-rule triangles; weight 0: none) for the columns of b.
// \throw ricci::Cancelled when `cancel` is set before the factorisation.
Eigen::MatrixX3d solve(const System& system, const PlanarDmsSpace& space, double thin_plate,
                       const Eigen::Vector3d& anchor_value, const Rim& rim,
                       const std::atomic<bool>* cancel, const std::vector<char>* plain = nullptr) {
  const int functions = space.function_count();
  auto [normal, rhs] = fill_detail::normal_equations(system, space, thin_plate, plain);
  ricci::throw_if_cancelled(cancel, "fill_rim");
  // A tiny anchor towards the mean value keeps functions that reach nothing determined and
  // moves with the data.
  const double anchor = 1e-12 * normal.diagonal().sum() / functions;
  for (int i = 0; i < functions; ++i) {
    normal.coeffRef(i, i) += anchor;
    rhs.row(i) += anchor * anchor_value.transpose();
  }
  return fill_detail::solve_normal_equations(normal, rhs, rim_name(rim));
}

// Surface samples of every rim edge at t = i / q, i = 0..q (in parallel, each into its slot).
std::vector<std::vector<RimSample>> sample_edges(const ManifoldSpline& spline, const Rim& rim,
                                                 int q) {
  const std::size_t per_edge = static_cast<std::size_t>(q) + 1;
  std::vector<std::vector<RimSample>> samples(rim.edges.size(), std::vector<RimSample>(per_edge));
  parallel_for(rim.edges.size() * per_edge, 0, [&](std::size_t k) {
    const std::size_t e = k / per_edge, i = k % per_edge;
    samples[e][i] =
        fill_detail::sample_rim(spline, rim.edges[e], static_cast<double>(i) / q);
  });
  return samples;
}

double smallest_cosine(const std::vector<std::vector<RimSample>>& samples,
                       const Eigen::Vector3d& n) {
  double worst = 1.0;
  for (const auto& row : samples) {
    for (const auto& s : row) worst = std::min(worst, s.jet.normal.dot(n));
  }
  return worst;
}

// The plane's normal: the mean surface normal along the rim, or the rim's least-squares normal
// (oriented like the mean) when it sees every rim normal at a smaller angle.
Eigen::Vector3d plane_normal(const std::vector<std::vector<RimSample>>& samples) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), mean = Eigen::Vector3d::Zero();
  int count = 0;
  for (const auto& row : samples) {
    for (const auto& s : row) {
      sum += s.jet.normal;
      mean += s.jet.position;
      ++count;
    }
  }
  mean /= count;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& row : samples) {
    for (const auto& s : row) cov += (s.jet.position - mean) * (s.jet.position - mean).transpose();
  }
  const Eigen::Vector3d average = sum.normalized();
  Eigen::Vector3d fitted =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors().col(0);
  if (fitted.dot(average) < 0.0) fitted = -fitted;
  return smallest_cosine(samples, fitted) > smallest_cosine(samples, average) ? fitted : average;
}

// FillOptions::corner_refinement by rim vertex (vertex j starts edge j): the full refinement
// where the surface's normal turns by more than mild_corner_step_deg between consecutive rim
// samples within kCornerSteps samples of the vertex on either edge, mild_corner_refinement (at
// most the full one) elsewhere.
constexpr int kCornerSteps = 4;
std::vector<int> corner_refinements(const std::vector<std::vector<RimSample>>& samples,
                                    const FillOptions& options) {
  const int m = static_cast<int>(samples.size());
  const int q = static_cast<int>(samples[0].size()) - 1;
  const int steps = std::min(kCornerSteps, q);
  const double limit = options.mild_corner_step_deg * M_PI / 180.0;
  const int mild = std::min(options.mild_corner_refinement, options.corner_refinement);
  std::vector<int> refinements(static_cast<std::size_t>(m));
  for (int j = 0; j < m; ++j) {
    const auto& before = samples[static_cast<std::size_t>((j + m - 1) % m)];
    const auto& after = samples[static_cast<std::size_t>(j)];
    double largest = 0.0;
    for (int i = 0; i < steps; ++i) {
      largest = std::max(largest, ricci::angle_between(after[i].jet.normal, after[i + 1].jet.normal));
      largest = std::max(largest, ricci::angle_between(before[q - i].jet.normal,
                                                       before[q - i - 1].jet.normal));
    }
    refinements[static_cast<std::size_t>(j)] = largest > limit ? options.corner_refinement : mild;
  }
  return refinements;
}

Eigen::Vector2d hermite(const Eigen::Vector2d& p0, const Eigen::Vector2d& m0,
                        const Eigen::Vector2d& p1, const Eigen::Vector2d& m1, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 +
         (s3 - s2) * m1;
}

}  // namespace

Eigen::Vector2d HoleFill::parameter(int edge, double t) const {
  const int m = static_cast<int>(boundary_points.size());
  const int j = ((edge % m) + m) % m;
  const auto& points = boundary_points[j];
  const auto& tangents = boundary_tangents[j];
  const int q = static_cast<int>(points.size()) - 1;
  const double x = std::clamp(t, 0.0, 1.0) * q;
  const int i = std::min(static_cast<int>(x), q - 1);
  const double h = 1.0 / q;  // d/dt -> d/ds on [t_i, t_i+1]
  return hermite(points[i], h * tangents[i], points[i + 1], h * tangents[i + 1], x - i);
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

namespace {

// The G1 height-field patch (hole_fill.h). \throw ricci::InvalidInputError when the rim is no
// height field.
HoleFill fill_height_field(const Rim& rim, const std::vector<std::vector<RimSample>>& samples,
                           const FillOptions& options) {
  const int m = static_cast<int>(rim.edges.size());
  const int q = options.fit_samples_per_edge;
  HoleFill fill;
  fill.rim = rim;
  fill.normal = plane_normal(samples);
  const double cosine = smallest_cosine(samples, fill.normal);
  if (cosine < options.min_normal_cosine) {
    throw ricci::InvalidInputError(
        "fill_rim: the " + rim_name(rim) + " is no height field: a surface normal on it makes " +
        std::to_string(std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / M_PI) +
        " degrees with the best plane's normal");
  }
  // Right-handed frame (e1, e2, n), origin at the rim's mean point.
  const Eigen::Vector3d helper =
      std::abs(fill.normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = helper.cross(fill.normal).normalized();
  const Eigen::Vector3d e2 = fill.normal.cross(e1);
  fill.axes.col(0) = e1;
  fill.axes.col(1) = e2;
  fill.origin.setZero();
  for (const auto& row : samples) {
    for (int i = 0; i < q; ++i) fill.origin += row[i].jet.position;
  }
  fill.origin /= static_cast<double>(m) * q;

  // D's boundary: the projected rim, clockwise in rim order.
  std::vector<Eigen::Vector2d> polygon;  // counter-clockwise, q points per edge
  for (const auto& row : samples) {
    std::vector<Eigen::Vector2d> points, tangents;
    for (const auto& s : row) {
      const Eigen::Vector3d d = s.jet.position - fill.origin;
      points.emplace_back(d.dot(e1), d.dot(e2));
      tangents.emplace_back(s.along_derivative.dot(e1), s.along_derivative.dot(e2));
    }
    fill.corners.push_back(points[0]);
    fill.boundary_points.push_back(std::move(points));
    fill.boundary_tangents.push_back(std::move(tangents));
  }
  for (int j = m - 1; j >= 0; --j) {
    for (int i = q; i >= 1; --i) polygon.push_back(fill.boundary_points[j][i]);
  }
  const bool check = rim.kind != Rim::Kind::boundary || options.require_simple_projection;
  if (fill_detail::polygon_area(polygon) <= 0.0) {
    throw ricci::InvalidInputError("fill_rim: the " + rim_name(rim) +
                                   " projects onto its plane with the wrong orientation");
  }
  if (check && !fill_detail::is_simple(polygon)) {
    throw ricci::InvalidInputError("fill_rim: the " + rim_name(rim) +
                                   " is not a simple polygon in its plane; it cannot be filled "
                                   "by a planar patch");
  }
  // A D that is not star-shaped is tessellated by triangulate_region (tessellate_fill).
  if (!fill_detail::star_center(polygon, fill.center)) fill.center = polygon_mean(polygon);

  const double perimeter = fill_detail::polygon_perimeter(polygon);
  const int boundary_vertices =
      std::max(8, std::min(options.refinement * m, options.max_boundary_vertices));
  const double h = perimeter / boundary_vertices;
  fill.space = patch_space(polygon, h, options.degree, options.knots, fill.corners,
                           corner_refinements(samples, options), options.outside_corner_grading,
                           fill_detail::grid_keep_distance(options, h));
  ricci::throw_if_cancelled(options.cancel, "fill_rim");
  const PlanarDmsSpace& space = *fill.space;
  const std::vector<char> plain = fill_detail::plain_rule_triangles(
      space, polygon,
      options.plain_quadrature_distance < 0.0 ? -1.0 : options.plain_quadrature_distance * h);

  // Weights: the height rows have units of length, the slope rows are scaled by h to match,
  // both averaged over the samples; R^2 int |H|^2 (R: D's radius) has the same units. So the
  // solution scales with the mesh.
  const double count = static_cast<double>(m) * q;
  const double w_position = std::sqrt(options.position_weight / count);
  const double w_slope = std::sqrt(options.tangent_weight / count) * h;
  System system;
  double mean_height = 0.0;
  const Eigen::Vector2d ex = Eigen::Vector2d::UnitX(), ey = Eigen::Vector2d::UnitY();
  // The basis at every boundary point (t = 1 is the next edge's t = 0), in parallel.
  std::vector<std::vector<BasisSample>> bases(static_cast<std::size_t>(m) * q);
  parallel_for(bases.size(), 0, [&](std::size_t k) {
    const auto per_edge = static_cast<std::size_t>(q);
    bases[k] = space.evaluate_basis(fill.boundary_points[k / per_edge][k % per_edge]);
  });
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < q; ++i) {
      const RimSample& s = samples[j][i];
      const auto& basis = bases[static_cast<std::size_t>(j * q + i)];
      const double height = (s.jet.position - fill.origin).dot(fill.normal);
      // G1: P_x = e1 + h_x n and P_y = e2 + h_y n orthogonal to the surface's normal.
      const double nn = s.jet.normal.dot(fill.normal);
      system.add(basis, space, nullptr, Eigen::Vector3d(height, 0, 0), w_position);
      system.add(basis, space, &ex, Eigen::Vector3d(-s.jet.normal.dot(e1) / nn, 0, 0), w_slope);
      system.add(basis, space, &ey, Eigen::Vector3d(-s.jet.normal.dot(e2) / nn, 0, 0), w_slope);
      mean_height += height;
    }
  }
  mean_height /= count;
  const double radius = perimeter / (2.0 * M_PI);
  const Eigen::VectorXd heights =
      solve(system, space, options.smoothing * radius * radius,
            Eigen::Vector3d(mean_height, 0, 0), rim, options.cancel, &plain)
          .col(0);

  // The in-plane part: the control points of the identity (exact on D, an affine map).
  const Eigen::MatrixXd plane = identity_control_points(space);
  fill.control_points.resize(space.function_count(), 3);
  for (int f = 0; f < space.function_count(); ++f) {
    fill.control_points.row(f) =
        (fill.origin + plane(f, 0) * e1 + plane(f, 1) * e2 + heights[f] * fill.normal).transpose();
  }

  return fill;
}

// The fallback: D the rim laid out on a circle by 3D arc length (clockwise in rim order, always
// convex), P fitted to the rim's positions only, with the thin-plate energy: watertight and
// consistently oriented, not G1.
HoleFill fill_positions(const Rim& rim, const std::vector<std::vector<RimSample>>& samples,
                        const FillOptions& options) {
  const int m = static_cast<int>(rim.edges.size());
  const int q = options.fit_samples_per_edge;
  HoleFill fill;
  fill.rim = rim;
  fill.g1 = false;
  const std::vector<Eigen::Vector2d> polygon = fill_detail::layout_on_circle(samples, fill);
  const double perimeter = fill_detail::polygon_perimeter(polygon);
  const int boundary_vertices =
      std::max(8, std::min(options.refinement * m, options.max_boundary_vertices));
  const double h = perimeter / boundary_vertices;
  fill.space = patch_space(polygon, h, options.degree, options.knots, fill.corners,
                           options.corner_refinement);
  const PlanarDmsSpace& space = *fill.space;
  const double radius = perimeter / (2.0 * M_PI);
  System system;
  const double w_position = std::sqrt(options.position_weight / (static_cast<double>(m) * q));
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < q; ++i) {
      system.add(space.evaluate_basis(fill.boundary_points[j][i]), space, nullptr,
                 samples[j][i].jet.position, w_position);
    }
  }
  fill.control_points =
      solve(system, space, std::max(options.smoothing, 1e-2) * radius * radius, fill.origin, rim,
            options.cancel);
  return fill;
}

}  // namespace

namespace {

// The largest angle between the surface's normals at consecutive rim samples 1/100 of an edge
// apart.
double largest_rim_normal_step_deg(const ManifoldSpline& spline, const Rim& rim) {
  double largest = 0.0;
  for (const auto& row : sample_edges(spline, rim, 100)) {
    for (std::size_t i = 1; i < row.size(); ++i) {
      largest = std::max(largest, ricci::angle_between(row[i - 1].jet.normal, row[i].jet.normal));
    }
  }
  return largest * 180.0 / M_PI;
}

// fill_rim at one patch space (FillOptions::corner_refinement).
HoleFill fill_rim_once(const ManifoldSpline& spline, const ricci::Mesh& domain_mesh,
                       const Rim& rim, const FillOptions& options) {
  const auto samples = sample_edges(spline, rim, options.fit_samples_per_edge);
  const double diagonal = bounding_diagonal(domain_mesh);
  auto measured = [&](HoleFill fill) {
    fill.diagonal = diagonal;
    const SeamReport report = measure_seam(spline, fill, options.samples_per_edge);
    fill.max_normal_jump_deg = report.max_normal_jump_deg;
    fill.edge_normal_jump_deg = report.edge_normal_jump_deg;
    fill.max_position_gap = report.max_position_gap;
    fill.rms_position_gap = report.rms_position_gap;
    fill.seam_samples = report.samples;
    return fill;
  };
  auto parametric_fill = [&]() {
    ricci::throw_if_cancelled(options.cancel, "fill_rim");
    return measured(fill_detail::fill_parametric(
        rim, sample_edges(spline, rim, options.parametric_samples_per_edge), options,
        corner_refinements(samples, options)));
  };
  if (options.method == FillMethod::parametric) return parametric_fill();
  // Boundary loops: the parametric patch only where the caller asks for a cap whatever the
  // projection (a closed input's puncture: require_simple_projection off) or for fallbacks;
  // an open disk's outer loop, around the surface's outside, has no sensible cap.
  const bool parametric_allowed =
      rim.kind != Rim::Kind::boundary || !options.require_simple_projection ||
      options.fallback_boundary;
  ricci::throw_if_cancelled(options.cancel, "fill_rim");
  HoleFill fill;
  try {
    fill = measured(fill_height_field(rim, samples, options));
  } catch (const ricci::InvalidInputError& e) {
    const bool allowed = (options.method == FillMethod::automatic && parametric_allowed) ||
                         (rim.kind == Rim::Kind::boundary ? options.fallback_boundary
                                                          : options.fallback);
    if (!allowed) throw;
    if (options.method == FillMethod::automatic && parametric_allowed) {
      HoleFill parametric = parametric_fill();
      // A boundary loop around the surface's outside (an open disk's outer loop) has no cap
      // meeting it with the surface's orientation: the patch folds over (~180 degrees).
      if (rim.kind == Rim::Kind::boundary && !options.fallback_boundary &&
          parametric.max_normal_jump_deg > 90.0) {
        throw;
      }
      return parametric;
    }
    fill = measured(fill_positions(rim, samples, options));
    fill.fallback_reason = e.what();
    return fill;
  }
  if (options.method == FillMethod::automatic && parametric_allowed &&
      fill.max_normal_jump_deg > options.target_jump_deg) {
    HoleFill parametric = parametric_fill();
    if (parametric.max_normal_jump_deg < fill.max_normal_jump_deg) return parametric;
  }
  return fill;
}

}  // namespace

HoleFill fill_rim(const ManifoldSpline& spline, const ricci::Mesh& domain_mesh, const Rim& rim,
                  const FillOptions& options) {
  check_options(options);
  const int m = static_cast<int>(rim.edges.size());
  if (m < 3) {
    throw ricci::InvalidInputError("fill_rim: a rim needs at least 3 edges, got " +
                                   std::to_string(m));
  }
  FillOptions first = options;
  if (largest_rim_normal_step_deg(spline, rim) > options.max_refined_rim_step_deg)
    first.corner_refinement = 1;
  HoleFill fill = fill_rim_once(spline, domain_mesh, rim, first);
  if (first.corner_refinement > 1 && fill.max_normal_jump_deg > options.target_jump_deg) {
    FillOptions uniform = options;
    uniform.corner_refinement = 1;
    HoleFill other = fill_rim_once(spline, domain_mesh, rim, uniform);
    if (other.max_normal_jump_deg < fill.max_normal_jump_deg) return other;
  }
  return fill;
}

}  // namespace spline
