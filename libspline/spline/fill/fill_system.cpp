#include "spline/fill/fill_system.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "ricci/mesh/errors.h"
#include "spline/basis/blossom.h"
#include "spline/basis/multi_index.h"
#include "spline/planar/bisect.h"

namespace spline::fill_detail {
namespace {

// Dunavant's 6-point rule, exact for degree 4 (the thin-plate integrand of a cubic piece has
// degree 2): barycentric points and weights summing to one.
std::vector<QuadraturePoint> quadrature_rule() {
  const double a = 0.445948490915965, wa = 0.223381589678011;
  const double b = 0.091576213509771, wb = 0.109951743655322;
  return {{{a, a, 1 - 2 * a}, wa}, {{a, 1 - 2 * a, a}, wa}, {{1 - 2 * a, a, a}, wa},
          {{b, b, 1 - 2 * b}, wb}, {{b, 1 - 2 * b, b}, wb}, {{1 - 2 * b, b, b}, wb}};
}

// The rim's mean point and mean normal; the 3D length of every edge (polyline through samples).
double rim_frame(const std::vector<std::vector<RimSample>>& samples, HoleFill& fill,
                 std::vector<double>& lengths) {
  const int m = static_cast<int>(samples.size());
  const int q = static_cast<int>(samples[0].size()) - 1;
  double total = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  fill.origin.setZero();
  lengths.clear();
  for (const auto& row : samples) {
    double length = 0.0;
    for (int i = 1; i <= q; ++i) length += (row[i].jet.position - row[i - 1].jet.position).norm();
    for (int i = 0; i < q; ++i) {
      normal += row[i].jet.normal;
      fill.origin += row[i].jet.position;
    }
    lengths.push_back(length);
    total += length;
  }
  fill.origin /= static_cast<double>(m) * q;
  if (normal.norm() > 0.0) fill.normal = normal.normalized();
  if (!(total > 0.0)) {
    throw ricci::InvalidInputError("fill_rim: the " + rim_name(fill.rim) + " has zero length");
  }
  return total;
}

// D's boundary data from its corners (chords, clockwise in rim order); returns the polygon
// counter-clockwise.
std::vector<Eigen::Vector2d> set_chords(HoleFill& fill, int q) {
  const int m = static_cast<int>(fill.corners.size());
  fill.boundary_points.clear();
  fill.boundary_tangents.clear();
  for (int j = 0; j < m; ++j) {
    const Eigen::Vector2d a = fill.corners[j], b = fill.corners[(j + 1) % m];
    std::vector<Eigen::Vector2d> points, tangents;
    for (int i = 0; i <= q; ++i) {
      points.push_back(a + (b - a) * (static_cast<double>(i) / q));
      tangents.push_back(b - a);
    }
    fill.boundary_points.push_back(std::move(points));
    fill.boundary_tangents.push_back(std::move(tangents));
  }
  std::vector<Eigen::Vector2d> polygon;  // counter-clockwise
  for (int j = m - 1; j >= 0; --j) polygon.push_back(fill.corners[j]);
  return polygon;
}

// Removes the grid's triangles whose centroid lies outside the closed polygon `boundary` farther
// than `distance` from it, then puts back the triangles around any vertex where the kept ones
// would touch at a point only (two fans), until none does. Vertex indices stay (the knot clouds
// are seeded by them; without_unused_vertices drops the unused ones after).
void trim_grid(PlanarTriangulation& t, const std::vector<Eigen::Vector2d>& boundary,
               double distance) {
  const PolygonRegion region(boundary, distance);
  std::vector<char> kept(t.triangles.size());
  for (std::size_t k = 0; k < t.triangles.size(); ++k) {
    const Eigen::Vector3i& v = t.triangles[k];
    const Eigen::Vector2d c = (t.positions[v[0]] + t.positions[v[1]] + t.positions[v[2]]) / 3.0;
    kept[k] = region.contains(c) || region.distance(c, 2.0 * distance) <= distance;
  }
  std::vector<std::vector<int>> star(t.positions.size());
  for (std::size_t k = 0; k < t.triangles.size(); ++k) {
    for (int c = 0; c < 3; ++c) star[static_cast<std::size_t>(t.triangles[k][c])].push_back(k);
  }
  // Kept triangles (v, a, b) around v are arcs a -> b; more than one arc whose start is no
  // arc's end: more than one fan.
  const auto pinched = [&](std::size_t v) {
    std::vector<std::pair<int, int>> arcs;
    for (int k : star[v]) {
      if (!kept[static_cast<std::size_t>(k)]) continue;
      const Eigen::Vector3i& tri = t.triangles[static_cast<std::size_t>(k)];
      const int at = tri[0] == static_cast<int>(v) ? 0 : tri[1] == static_cast<int>(v) ? 1 : 2;
      arcs.emplace_back(tri[(at + 1) % 3], tri[(at + 2) % 3]);
    }
    int starts = 0;
    for (const auto& arc : arcs) {
      starts += std::none_of(arcs.begin(), arcs.end(),
                             [&](const std::pair<int, int>& o) { return o.second == arc.first; });
    }
    return starts > 1;
  };
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t v = 0; v < star.size(); ++v) {
      if (!pinched(v)) continue;
      for (int k : star[v]) kept[static_cast<std::size_t>(k)] = 1;
      changed = true;
    }
  }
  std::vector<Eigen::Vector3i> triangles;
  for (std::size_t k = 0; k < t.triangles.size(); ++k) {
    if (kept[k]) triangles.push_back(t.triangles[k]);
  }
  t.triangles = std::move(triangles);
}

// The vertices of no triangle and their clouds removed, the others renumbered in order.
void without_unused_vertices(PlanarTriangulation& t, std::vector<KnotCloud>& clouds) {
  std::vector<int> index(t.positions.size(), -1);
  for (const Eigen::Vector3i& tri : t.triangles) {
    for (int c = 0; c < 3; ++c) index[static_cast<std::size_t>(tri[c])] = 0;
  }
  int next = 0;
  for (std::size_t v = 0; v < index.size(); ++v) {
    if (index[v] < 0) continue;
    index[v] = next;
    t.positions[static_cast<std::size_t>(next)] = t.positions[v];
    clouds[static_cast<std::size_t>(next)] = std::move(clouds[v]);
    ++next;
  }
  t.positions.resize(static_cast<std::size_t>(next));
  clouds.resize(static_cast<std::size_t>(next));
  for (Eigen::Vector3i& tri : t.triangles) {
    for (int c = 0; c < 3; ++c) tri[c] = index[static_cast<std::size_t>(tri[c])];
  }
}

}  // namespace

std::vector<QuadraturePoint> thin_plate_rule() {
  const auto base = quadrature_rule();
  std::vector<QuadraturePoint> rule = base;
  for (double ratio : {0.3, 0.1}) {
    for (int corner = 0; corner < 3; ++corner) {
      for (const auto& q : base) {
        QuadraturePoint p;
        p.bary = ratio * q.bary;
        p.bary[corner] += 1.0 - ratio;
        p.weight = ratio * ratio * q.weight;
        rule.push_back(p);
      }
    }
  }
  return rule;
}

std::vector<QuadraturePoint> thin_plate_plain_rule() {
  // thin_plate_rule's corner points add to the plain rule's weight (1.3 in all): scaled to it,
  // both give a polynomial piece the same energy.
  double total = 0.0;
  for (const auto& q : thin_plate_rule()) total += q.weight;
  std::vector<QuadraturePoint> rule = quadrature_rule();
  for (auto& q : rule) q.weight *= total;
  return rule;
}

double grid_keep_distance(const FillOptions& options, double spacing) {
  return options.grid_margin < 0.0 ? INFINITY : options.grid_margin * spacing;
}

std::vector<char> plain_rule_triangles(const PlanarDmsSpace& space,
                                       const std::vector<Eigen::Vector2d>& boundary,
                                       double distance) {
  const PlanarTriangulation& t = space.triangulation();
  std::vector<char> plain(t.triangles.size(), 0);
  if (distance < 0.0) return plain;
  const PolygonRegion region(boundary, std::max(distance, 1e-12));
  for (std::size_t k = 0; k < t.triangles.size(); ++k) {
    const Eigen::Vector3i& v = t.triangles[k];
    const Eigen::Vector2d c = (t.positions[v[0]] + t.positions[v[1]] + t.positions[v[2]]) / 3.0;
    plain[k] = !region.contains(c) && !(region.distance(c, 2.0 * distance) <= distance);
  }
  return plain;
}

std::string rim_name(const Rim& rim) {
  return std::string(rim_kind_description(rim.kind)) + " of " + std::to_string(rim.edges.size()) +
         " edges starting at face " + std::to_string(rim.edges[0].face);
}

std::shared_ptr<const PlanarDmsSpace> patch_space(const std::vector<Eigen::Vector2d>& boundary,
                                                  double spacing, int degree,
                                                  const KnotCloudOptions& knots,
                                                  const std::vector<Eigen::Vector2d>& corners,
                                                  const std::vector<int>& refinements,
                                                  double outside_grading,
                                                  double keep_distance) {
  Eigen::Vector2d lo = boundary[0], hi = boundary[0];
  for (const auto& p : boundary) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(2.0 * spacing);
  PlanarTriangulation t = triangle_grid(lo - margin, hi + margin, spacing);
  const bool trim = std::isfinite(keep_distance) && keep_distance >= 0.0;
  if (trim) trim_grid(t, boundary, keep_distance);
  if (std::any_of(refinements.begin(), refinements.end(), [](int r) { return r > 1; })) {
    std::vector<double> fine(corners.size());
    for (std::size_t c = 0; c < corners.size(); ++c) fine[c] = spacing / refinements[c];
    std::optional<PolygonRegion> region;
    if (outside_grading != 1.0) region.emplace(boundary, spacing);
    refine_to_size(t, [&](const Eigen::Vector2d& x) {
      // fine + distance from the corner, the smallest over the corners (with one refinement
      // for all: fine + the nearest corner's distance, to the bit).
      const double grading = region && !region->contains(x) ? outside_grading : 1.0;
      double size = INFINITY;
      for (std::size_t c = 0; c < corners.size(); ++c)
        size = std::min(size, fine[c] + grading * (x - corners[c]).norm());
      return size < spacing ? size : 1e300;  // the grid's own sides elsewhere
    });
  }
  auto clouds = make_knot_clouds(t, degree, knots);
  if (trim) without_unused_vertices(t, clouds);
  return std::make_shared<const PlanarDmsSpace>(std::move(t), std::move(clouds));
}

std::shared_ptr<const PlanarDmsSpace> patch_space(const std::vector<Eigen::Vector2d>& boundary,
                                                  double spacing, int degree,
                                                  const KnotCloudOptions& knots,
                                                  const std::vector<Eigen::Vector2d>& corners,
                                                  int corner_refinement) {
  return patch_space(boundary, spacing, degree, knots, corners,
                     std::vector<int>(corners.size(), corner_refinement));
}

std::vector<Eigen::Vector2d> layout_on_circle(const std::vector<std::vector<RimSample>>& samples,
                                              HoleFill& fill) {
  const int m = static_cast<int>(samples.size());
  const int q = static_cast<int>(samples[0].size()) - 1;
  std::vector<double> lengths;
  const double total = rim_frame(samples, fill, lengths);
  const double radius = total / (2.0 * M_PI);
  double share = 0.0;
  fill.corners.clear();
  for (int j = 0; j < m; ++j) {
    const double angle = -2.0 * M_PI * share;
    fill.corners.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
    share += 0.8 * lengths[j] / total + 0.2 / m;
  }
  fill.center.setZero();
  return set_chords(fill, q);
}

std::vector<Eigen::Vector2d> layout_by_development(
    const std::vector<std::vector<RimSample>>& samples, HoleFill& fill) {
  const int m = static_cast<int>(samples.size());
  const int q = static_cast<int>(samples[0].size()) - 1;
  std::vector<double> arc;
  const double length = rim_frame(samples, fill, arc);
  // Clockwise turn (seen from the normal: towards the hole) from tangent a to tangent b.
  auto turn = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& n) {
    return -std::atan2(n.dot(a.cross(b)), a.dot(b));
  };
  // The rim's turns: along each edge between samples, and at each corner (edge j's t = 1 to
  // edge j + 1's t = 0).
  std::vector<std::vector<double>> step(m, std::vector<double>(q)), inner(m, std::vector<double>(q));
  std::vector<double> corner(m);
  double total = 0.0;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < q; ++i) {
      const RimSample& a = samples[j][i];
      const RimSample& b = samples[j][i + 1];
      step[j][i] = (b.jet.position - a.jet.position).norm();
      inner[j][i] = turn(a.along_derivative, b.along_derivative, (a.jet.normal + b.jet.normal).normalized());
      total += inner[j][i];
    }
    const RimSample& next = samples[(j + 1) % m][0];
    corner[j] = turn(samples[j][q].along_derivative, next.along_derivative, next.jet.normal);
    total += corner[j];
  }
  // The hole's curvature: spread uniformly by arc length along the edges so that D turns once.
  const double extra = (2.0 * M_PI - total) / length;
  fill.corners.clear();
  fill.boundary_points.assign(m, std::vector<Eigen::Vector2d>(q + 1));
  fill.boundary_tangents.assign(m, std::vector<Eigen::Vector2d>(q + 1));
  std::vector<std::vector<double>> arc_at(m, std::vector<double>(q + 1));
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  double angle = 0.0, s = 0.0;
  auto direction = [](double phi) { return Eigen::Vector2d(std::cos(phi), std::sin(phi)); };
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i <= q; ++i) {
      fill.boundary_points[j][i] = point;
      fill.boundary_tangents[j][i] = samples[j][i].along_derivative.norm() * direction(angle);
      arc_at[j][i] = s;
      if (i == q) break;
      const double next = angle - (inner[j][i] + extra * step[j][i]);
      point += step[j][i] * direction(0.5 * (angle + next));
      s += step[j][i];
      angle = next;
    }
    angle -= corner[j];
  }
  // Close it: subtract the gap linearly in arc length (a constant added to dD/ds).
  const Eigen::Vector2d gap = point;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i <= q; ++i) {
      fill.boundary_points[j][i] -= gap * (arc_at[j][i] / s);
      fill.boundary_tangents[j][i] -= gap * (samples[j][i].along_derivative.norm() / s);
    }
    fill.corners.push_back(fill.boundary_points[j][0]);
  }
  std::vector<Eigen::Vector2d> polygon;  // counter-clockwise
  for (int j = m - 1; j >= 0; --j) {
    for (int i = q; i >= 1; --i) polygon.push_back(fill.boundary_points[j][i]);
  }
  if (!(polygon_area(polygon) > 0.0) || !is_simple(polygon)) return {};
  Eigen::Vector2d center;
  fill.center = star_center(polygon, center) ? center : polygon_mean(polygon);
  return polygon;
}

void System::add(const std::vector<BasisSample>& basis, const PlanarDmsSpace& space,
                 const Eigen::Vector2d* direction, const Eigen::Vector3d& target, double weight) {
  const int row = next_row();
  for (const auto& s : basis) {
    const double d = direction ? s.jet.gradient.dot(*direction) : s.jet.value;
    entries.emplace_back(row, space.function_index(s.triangle, s.beta), weight * d);
  }
  targets.push_back(weight * target);
}

Eigen::MatrixXd identity_control_points(const PlanarDmsSpace& space) {
  BivariatePolynomial identity;
  identity.degree = 1;
  identity.coefficients = Eigen::MatrixXd::Zero(3, 2);
  identity.coefficients(monomial_index(1, 0), 0) = 1.0;
  identity.coefficients(monomial_index(0, 1), 1) = 1.0;
  return space.control_points_of(identity);
}

}  // namespace spline::fill_detail
