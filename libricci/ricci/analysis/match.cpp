// Deformable surface matching (Algorithm 8): the rectangle or the unit disk of a disk, or the
// cone star of a multiply connected domain carried harmonically onto a common convex polygon; the
// map located by a grid over B's parameter domain; the shape error of eq. (13).
#include "ricci/analysis/match.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "ricci/analysis/conformal_module.h"
#include "ricci/analysis/match_internal.h"
#include "ricci/analysis/module_internal.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/singularity/valence.h"
#include "ricci/topology/slice.h"
#include "ricci/util/cross2d.h"
#include "ricci/util/stopwatch.h"

namespace ricci {

std::string to_string(MatchMethod method) {
  return method == MatchMethod::euclidean ? "euclidean" : "hyperbolic";
}

MatchMethod parse_match_method(const std::string& name) {
  if (name == "euclidean") return MatchMethod::euclidean;
  if (name == "hyperbolic") return MatchMethod::hyperbolic;
  throw InvalidInputError("unknown matching method '" + name + "' (euclidean, hyperbolic)");
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::string topology_text(const SurfaceTopology& t) {
  return "genus " + std::to_string(t.genus) + " with " + std::to_string(t.boundary_loops) +
         " boundary loop" + (t.boundary_loops == 1 ? "" : "s");
}

/// \throw TopologyError unless one connected 2-manifold.
SurfaceTopology checked_topology(const Mesh& mesh, const char* name) {
  const SurfaceTopology t = surface_topology(mesh);
  if (!t.manifold) throw TopologyError(std::string(name) + " is not a 2-manifold");
  if (t.components != 1) {
    throw TopologyError(std::string(name) + " has " + std::to_string(t.components) +
                        " components; matching needs one");
  }
  return t;
}

/// \throw InvalidInputError for a vertex out of range or on the boundary.
void check_feature(const MeshTables& tables, int v, const char* name) {
  const int n = tables.num_vertices();
  if (v < 0 || v >= n) {
    throw InvalidInputError(std::string("feature vertex ") + std::to_string(v) + " of " + name +
                            " is out of range [0, " + std::to_string(n) + ")");
  }
  if (tables.is_boundary_vertex[v]) {
    throw InvalidInputError(std::string("feature vertex ") + std::to_string(v) + " of " + name +
                            " is on the boundary; the cone needs an interior vertex");
  }
  const int loops = static_cast<int>(tables.boundary_loops.size());
  if (tables.valence[v] < loops) {
    throw InvalidInputError(std::string("feature vertex ") + std::to_string(v) + " of " + name +
                            " has " + std::to_string(tables.valence[v]) +
                            " neighbours, fewer than the " + std::to_string(loops) +
                            " boundary loops its cuts must reach");
  }
}

using detail::Star;

/// Algorithm 8, steps 1-3: the flat metric with geodesic boundaries and the cone at p.
/// \throw SolverError when the flow does not converge.
EdgeLengths cone_flow(const Mesh& mesh, const MeshTables& tables, int p,
                      const MatchOptions& options, const char* name, ParameterDomain& domain) {
  const int n = tables.num_vertices();
  const int loops = static_cast<int>(tables.boundary_loops.size());
  Targets targets;
  targets.curvature = Eigen::VectorXd::Zero(n);
  // A single vertex of valence ~6 cannot take -2π or less under the inversive-distance
  // metric (the triangle inequality breaks): the cone is spread over p's interior rings.
  std::vector<int> cone = {p};
  for (VertexHandle v : ring_neighbourhood(mesh, mesh.vertex_handle(p), options.cone_rings)) {
    if (!tables.is_boundary_vertex[v.idx()]) cone.push_back(v.idx());
  }
  for (int v : cone) {
    targets.curvature[v] = 2 * M_PI * (2 - loops) / static_cast<double>(cone.size());
  }
  FlowResult flat = flow(mesh, targets, options.flow);
  detail::record_match_flow(flat, options, name, domain);
  return std::move(flat.lengths);
}

/// The star with its walk starting at its j-th ray (loop_order[j]) instead of the ray to c0.
Star rotated(const Star& star, int j) {
  Star out = star;
  if (j == 0) return out;
  const int m = static_cast<int>(star.walk.size());
  const int shift = star.corners[3 * static_cast<size_t>(j)];
  std::rotate(out.walk.begin(), out.walk.begin() + shift, out.walk.end());
  for (int i = 0; i < m; ++i) {
    const int from = (i + shift) % m;
    out.arc[i + 1] = out.arc[i] + star.arc[from + 1] - star.arc[from];
    out.param_arc[i + 1] = out.param_arc[i] + star.param_arc[from + 1] - star.param_arc[from];
  }
  for (int& corner : out.corners) corner = (corner - shift + m) % m;
  std::sort(out.corners.begin(), out.corners.end());
  std::rotate(out.loop_order.begin(), out.loop_order.begin() + j, out.loop_order.end());
  return out;
}

/// By rank (c0 the longest): each boundary loop's 3D length over the whole boundary's.
std::vector<double> relative_loop_lengths(const Mesh& mesh, const MeshTables& tables) {
  std::vector<double> lengths;
  double total = 0;
  for (int loop : detail::loops_by_length(mesh, tables)) {
    const std::vector<int>& vertices = tables.boundary_loops[loop];
    double length = 0;
    for (size_t i = 0; i < vertices.size(); ++i) {
      length += (mesh.point(mesh.vertex_handle(vertices[i])) -
                 mesh.point(mesh.vertex_handle(vertices[(i + 1) % vertices.size()])))
                    .norm();
    }
    lengths.push_back(length);
    total += length;
  }
  for (double& length : lengths) length /= total;
  return lengths;
}

/// Pairings of A's loop ranks with B's (pairing[rank of A] = rank of B) in which every pair's
/// relative 3D lengths agree within `tolerance` (relative), the smallest summed relative
/// difference first, at most `limit` (the search stops after 100000 partial pairings).
std::vector<std::vector<int>> length_pairings(const std::vector<double>& lengths_a,
                                              const std::vector<double>& lengths_b,
                                              double tolerance, size_t limit) {
  const int k = static_cast<int>(lengths_a.size());
  std::vector<std::pair<double, std::vector<int>>> found;
  std::vector<int> pairing;
  std::vector<char> taken(k, 0);
  int budget = 100000;
  const auto difference = [&](int r, int q) {
    return std::abs(lengths_a[r] - lengths_b[q]) / std::max(lengths_a[r], lengths_b[q]);
  };
  const std::function<void(double)> extend = [&](double sum) {
    if (--budget < 0) return;
    const int r = static_cast<int>(pairing.size());
    if (r == k) {
      found.push_back({sum, pairing});
      return;
    }
    for (int q = 0; q < k; ++q) {
      if (taken[q] || !(difference(r, q) <= tolerance)) continue;
      taken[q] = 1;
      pairing.push_back(q);
      extend(sum + difference(r, q));
      pairing.pop_back();
      taken[q] = 0;
    }
  };
  extend(0.0);
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::vector<int>> out;
  for (size_t i = 0; i < found.size() && i < limit; ++i) out.push_back(found[i].second);
  return out;
}

/// When the rays leave the feature towards the loops in another order on A and B: the turns j
/// of B's star (its ray j paired with A's ray 0, and so on round) that pair each loop of A with
/// a loop of B of the same relative 3D length within `tolerance` (relative): where the lengths
/// cannot tell the loops apart, their cyclic order around the feature does.
std::vector<int> pairing_turns(const Star& a, const Star& b, const std::vector<double>& lengths_a,
                               const std::vector<double>& lengths_b, double tolerance) {
  std::vector<int> turns;
  const size_t k = a.loop_order.size();
  for (size_t j = 0; j < k; ++j) {
    bool fits = true;
    for (size_t i = 0; i < k && fits; ++i) {
      const double x = lengths_a[a.loop_order[i]], y = lengths_b[b.loop_order[(i + j) % k]];
      fits = std::abs(x - y) <= tolerance * std::max(x, y);
    }
    if (fits) turns.push_back(static_cast<int>(j));
  }
  return turns;
}

/// One surface's mesh, tables, flat metric and cone star.
struct MeshCut {
  const Mesh* mesh;
  const MeshTables* tables;
  const EdgeLengths* flat;
  const Star* star;
};

/// A pair of cone stars to map, at each turn of B's.
struct Candidate {
  const Star* a;
  const Star* b;
  std::vector<int> turns;
};

/// The loops paired by relative 3D length alone (length_pairings; ranks may swap among loops of
/// about one length), and for each pairing one surface's rays forced to leave p in the other's
/// cyclic order (detail::ordered_star): B in A's, and A in B's; `forced` holds their stars.
void forced_candidates(const MeshCut& a, const MeshCut& b, const MatchOptions& options,
                       const MatchResult& result, std::deque<Star>& forced,
                       std::vector<Candidate>& candidates) {
  const std::vector<int>& loops_a = a.star->loop_order;
  const std::vector<int>& loops_b = b.star->loop_order;
  const int k = static_cast<int>(loops_a.size());
  for (const std::vector<int>& pairing : length_pairings(relative_loop_lengths(*a.mesh, *a.tables),
                                                         relative_loop_lengths(*b.mesh, *b.tables),
                                                         options.loop_length_tolerance, 4)) {
    std::vector<int> inverse(pairing.size());
    for (size_t r = 0; r < pairing.size(); ++r) inverse[pairing[r]] = static_cast<int>(r);
    std::vector<int> order_b, order_a;
    for (int rank : loops_a) order_b.push_back(pairing[rank]);
    for (int rank : loops_b) order_a.push_back(inverse[rank]);
    const auto zero = [](std::vector<int>& order) {  // rotated to start at c0
      const auto at = std::find(order.begin(), order.end(), 0);
      const int i = static_cast<int>(at - order.begin());
      std::rotate(order.begin(), at, order.end());
      return i;
    };
    const int ib = zero(order_b), ia = zero(order_a);
    try {
      forced.push_back(
          detail::ordered_star(*b.mesh, *b.tables, result.b.feature, *b.flat, order_b, "B"));
      candidates.push_back({a.star, &forced.back(), {(k - ib) % k}});
    } catch (const TopologyError&) {
      // B's rays cannot take A's order: A's may take B's
    }
    try {
      forced.push_back(
          detail::ordered_star(*a.mesh, *a.tables, result.a.feature, *a.flat, order_a, "A"));
      candidates.push_back({&forced.back(), b.star, {ia}});
    } catch (const TopologyError&) {
      // neither: the next pairing
    }
  }
}

/// Steps 6-8 with one convex piece per surface: B's disk onto a polygon inscribed in the unit
/// circle by the mean-value harmonic map of its flat metric, A's disk inside it (fill_inside).
/// \throw SolverError when a sparse solve fails.
void one_convex_piece(const Star& star_a, const Star& star_b, MatchResult& trial) {
  const std::vector<double> extents = detail::common_extents(star_a, star_b);
  const std::vector<double> sa = detail::arc_parameters(star_a, extents),
                            sb = detail::arc_parameters(star_b, extents);
  const int n = static_cast<int>(star_b.sliced.mesh.n_vertices());
  Eigen::MatrixX2d x = Eigen::MatrixX2d::Zero(n, 2);
  std::vector<char> fixed(n, 0);
  detail::place_on_circle(star_b, sb, Eigen::Vector2d::Zero(), x, fixed);
  detail::harmonic_fill(star_b.sliced.mesh, star_b.lengths, fixed, x);
  trial.b.positions = std::move(x);
  trial.a.positions = detail::fill_inside(star_a.sliced.mesh, star_a.lengths, star_a.walk, sa,
                                          star_b.walk, sb, trial.b.positions, 1.0);
  detail::fill_cut_domain(star_a.sliced, trial.a);
  detail::fill_cut_domain(star_b.sliced, trial.b);
  trial.pieces = 1;
}

/// Four boundary vertices of a disk where the boundary turns most in 3D (pi minus the sum of the
/// face angles there), each at least 1/20 of the boundary's length from the others, starting
/// from the lowest index.
std::vector<int> turning_corners(const Mesh& mesh, const MeshTables& tables) {
  const std::vector<int>& loop = tables.boundary_loops[0];
  const int m = static_cast<int>(loop.size());
  if (m < 4) throw InvalidInputError("the boundary has fewer than four vertices");
  std::vector<double> turning(m), arc(m + 1, 0.0);
  for (int i = 0; i < m; ++i) {
    const VertexHandle v = mesh.vertex_handle(loop[i]);
    double angle = 0;
    for (HalfedgeHandle h : mesh.voh_range(v)) {
      if (!mesh.is_boundary(h)) angle += mesh.calc_sector_angle(h);
    }
    turning[i] = M_PI - angle;
    arc[i + 1] =
        arc[i] + (mesh.point(v) - mesh.point(mesh.vertex_handle(loop[(i + 1) % m]))).norm();
  }
  std::vector<int> order(m);
  for (int i = 0; i < m; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](int x, int y) { return turning[x] > turning[y]; });
  std::vector<int> chosen;
  for (int i : order) {
    bool apart = true;
    for (int j : chosen) {
      const double d = std::abs(arc[i] - arc[j]);
      apart = apart && std::min(d, arc[m] - d) >= arc[m] / 20;
    }
    if (apart) chosen.push_back(i);
    if (chosen.size() == 4) break;
  }
  if (chosen.size() < 4) throw InvalidInputError("no four corners spread along the boundary");
  std::vector<int> corners;
  for (int i : chosen) corners.push_back(loop[i]);
  std::iter_swap(corners.begin(), std::min_element(corners.begin(), corners.end()));
  return corners;
}

/// The rectangle of a disk, scaled to the unit square.
void rectangle_domain(const Mesh& mesh, const MeshTables& tables, const std::vector<int>& corners,
                      const MatchOptions& options, const char* name, ParameterDomain& domain) {
  ModuleOptions module;
  module.corners = corners.empty() ? turning_corners(mesh, tables) : corners;
  module.flow = options.flow;
  module.accepted_error = options.accepted_error;
  module.force_kind = true;
  module.kind = ModuleKind::Rectangle;
  module.retry = false;                            // the map needs the mesh's own vertices
  module.flow.fall_back_to_other_metrics = false;  // the rectangle must be conformal
  const ModuleResult rectangle = conformal_module(mesh, module);
  if (!rectangle.converged && !(rectangle.flow_error < options.accepted_error)) {
    throw SolverError(std::string("the Ricci flow of ") + name +
                      " to the rectangle did not converge: " + rectangle.message);
  }
  domain.flow_iterations = rectangle.flow_iterations;
  domain.flow_error = rectangle.flow_error;
  domain.metric = to_string(options.flow.scheme);
  domain.corners = rectangle.corners;
  domain.faces = rectangle.domain.faces;
  domain.positions = rectangle.domain.positions;
  domain.positions.col(1) /= rectangle.values[0];
  domain.to_original_vertex.resize(mesh.n_vertices());
  for (int v = 0; v < static_cast<int>(mesh.n_vertices()); ++v) domain.to_original_vertex[v] = v;
}

/// The conformal map of a disk onto the unit disk, `centre` at 0 (ModuleKind::Disk).
void unit_disk_domain(const Mesh& mesh, int centre, const MatchOptions& options, const char* name,
                      ParameterDomain& domain) {
  ModuleOptions module;
  module.force_kind = true;
  module.kind = ModuleKind::Disk;
  module.centre = centre;
  module.flow = options.flow;
  module.accepted_error = options.accepted_error;
  module.retry = false;                            // the map needs the mesh's own vertices
  module.flow.fall_back_to_other_metrics = false;  // the disk map must be conformal
  const ModuleResult disk = conformal_module(mesh, module);
  if (!disk.converged) {
    throw SolverError(std::string("the Ricci flow of ") + name +
                      " to the unit disk did not converge: " + disk.message);
  }
  domain.feature = centre;
  domain.flow_iterations = disk.flow_iterations;
  domain.flow_error = disk.flow_error;
  domain.metric = to_string(options.flow.scheme);
  domain.faces = disk.domain.faces;
  domain.positions = disk.domain.positions;
  domain.to_original_vertex.resize(mesh.n_vertices());
  for (int v = 0; v < static_cast<int>(mesh.n_vertices()); ++v) domain.to_original_vertex[v] = v;
}

double signed_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return 0.5 * cross2d(b - a, c - a);
}

/// Point location in a planar triangulation: a uniform grid of face boxes.
class Locator {
 public:
  struct Hit {
    int face = -1;
    Eigen::Vector3d weights = Eigen::Vector3d::Zero();
    double distance = kInfinity;  ///< 0 inside a face.
  };

  Locator(const Eigen::MatrixX2d& positions, const Eigen::MatrixX3i& faces)
      : p_(positions), f_(faces) {
    lo_ = p_.colwise().minCoeff().transpose();
    const Eigen::Vector2d hi = p_.colwise().maxCoeff().transpose();
    const double side = std::max(hi.x() - lo_.x(), hi.y() - lo_.y());
    cells_ = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(f_.rows()))));
    cell_ = std::max(side, 1e-300) / cells_;
    bins_.resize(static_cast<size_t>(cells_) * cells_);
    for (int f = 0; f < f_.rows(); ++f) {
      Eigen::Vector2d a = p_.row(f_(f, 0)).transpose(), b = a;
      for (int k = 1; k < 3; ++k) {
        a = a.cwiseMin(p_.row(f_(f, k)).transpose());
        b = b.cwiseMax(p_.row(f_(f, k)).transpose());
      }
      for (int i = cell(a.x() - lo_.x()); i <= cell(b.x() - lo_.x()); ++i) {
        for (int j = cell(a.y() - lo_.y()); j <= cell(b.y() - lo_.y()); ++j) {
          bins_[static_cast<size_t>(i) * cells_ + j].push_back(f);
        }
      }
    }
  }

  /// The face containing q, or the closest point of the triangulation to q.
  [[nodiscard]] Hit locate(const Eigen::Vector2d& q) const {
    const int ci = cell(q.x() - lo_.x()), cj = cell(q.y() - lo_.y());
    Hit best;
    for (int r = 0; r <= cells_; ++r) {
      for (int i = ci - r; i <= ci + r; ++i) {
        for (int j = cj - r; j <= cj + r; ++j) {
          if (std::max(std::abs(i - ci), std::abs(j - cj)) != r) continue;
          if (i < 0 || j < 0 || i >= cells_ || j >= cells_) continue;
          for (int f : bins_[static_cast<size_t>(i) * cells_ + j]) {
            const Hit hit = closest(f, q);
            if (hit.distance < best.distance) best = hit;
            if (best.distance == 0) return best;
          }
        }
      }
      if (best.distance <= r * cell_) return best;
    }
    return best;
  }

 private:
  int cell(double offset) const {
    return std::clamp(static_cast<int>(offset / cell_), 0, cells_ - 1);
  }

  Hit closest(int f, const Eigen::Vector2d& q) const {
    const Eigen::Vector2d v[3] = {p_.row(f_(f, 0)).transpose(), p_.row(f_(f, 1)).transpose(),
                                  p_.row(f_(f, 2)).transpose()};
    Hit hit;
    hit.face = f;
    const double area = signed_area(v[0], v[1], v[2]);
    if (area > 0) {
      const Eigen::Vector3d w(signed_area(q, v[1], v[2]) / area, signed_area(v[0], q, v[2]) / area,
                              signed_area(v[0], v[1], q) / area);
      if (w.minCoeff() >= -1e-12) {
        hit.weights = w.cwiseMax(0.0) / w.cwiseMax(0.0).sum();
        hit.distance = 0;
        return hit;
      }
    }
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d a = v[k], b = v[(k + 1) % 3];
      const double length2 = (b - a).squaredNorm();
      const double t = length2 > 0 ? std::clamp((q - a).dot(b - a) / length2, 0.0, 1.0) : 0.0;
      const double d = (q - (a + t * (b - a))).norm();
      if (d < hit.distance) {
        hit.distance = d;
        hit.weights.setZero();
        hit.weights[k] = 1 - t;
        hit.weights[(k + 1) % 3] = t;
      }
    }
    return hit;
  }

  const Eigen::MatrixX2d& p_;
  const Eigen::MatrixX3i& f_;
  Eigen::Vector2d lo_;
  int cells_ = 1;
  double cell_ = 1;
  std::vector<std::vector<int>> bins_;
};

/// How many faces use each side (vertex pair, smaller index first): 1 on the boundary.
std::map<std::pair<int, int>, int> side_uses(const Eigen::MatrixX3i& faces) {
  std::map<std::pair<int, int>, int> sides;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      ++sides[{std::min(a, b), std::max(a, b)}];
    }
  }
  return sides;
}

/// The boundary of a planar triangulation that is star-shaped about `centre` (a convex
/// domain), as a radial function: the boundary vertices by angle about the centre.
class RadialBoundary {
 public:
  RadialBoundary(const Eigen::MatrixX2d& positions, const Eigen::MatrixX3i& faces,
                 const Eigen::Vector2d& centre)
      : centre_(centre) {
    for (const auto& [side, count] : side_uses(faces)) {
      if (count != 1) continue;
      for (int v : {side.first, side.second}) {
        const Eigen::Vector2d d = positions.row(v).transpose() - centre;
        points_.push_back({std::atan2(d.y(), d.x()), d});
      }
    }
    std::sort(points_.begin(), points_.end(),
              [](const Point& x, const Point& y) { return x.angle < y.angle; });
  }

  /// Distance from the centre to the boundary along direction `u` (unit).
  [[nodiscard]] double radius(const Eigen::Vector2d& u) const {
    const double angle = std::atan2(u.y(), u.x());
    const auto after = std::lower_bound(points_.begin(), points_.end(), angle,
                                        [](const Point& x, double a) { return x.angle < a; });
    const Eigen::Vector2d q = after == points_.end() ? points_.front().d : after->d;
    const Eigen::Vector2d p = after == points_.begin() ? points_.back().d : (after - 1)->d;
    const double denominator = cross2d(u, q - p);
    return std::abs(denominator) > 0 ? cross2d(p, q - p) / denominator : p.norm();
  }

  [[nodiscard]] const Eigen::Vector2d& centre() const { return centre_; }

 private:
  struct Point {
    double angle;
    Eigen::Vector2d d;
  };
  Eigen::Vector2d centre_;
  std::vector<Point> points_;
};

/// A's domain carried onto B's (both convex about B's boundary centroid) by the radial map
/// x -> c + (x - c) rho_B / rho_A: one-to-one and orientation-preserving (its Jacobian is
/// rho_B / rho_A times a rotation plus a shear along the rays), where the nearest point of B
/// would fold A's faces between the two boundaries' chords onto B's sides.
Eigen::MatrixX2d radial_onto(const ParameterDomain& a, const ParameterDomain& b) {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  int count = 0;
  for (const auto& [side, uses] : side_uses(b.faces)) {
    if (uses != 1) continue;
    centre += b.positions.row(side.first).transpose() + b.positions.row(side.second).transpose();
    count += 2;
  }
  centre /= std::max(count, 1);
  const RadialBoundary rim_a(a.positions, a.faces, centre), rim_b(b.positions, b.faces, centre);
  Eigen::MatrixX2d moved = a.positions;
  for (Eigen::Index s = 0; s < moved.rows(); ++s) {
    const Eigen::Vector2d d = a.positions.row(s).transpose() - centre;
    const double r = d.norm();
    if (!(r > 0)) continue;
    const Eigen::Vector2d u = d / r;
    const double ra = rim_a.radius(u), rb = rim_b.radius(u);
    // Only near the boundary (weight (r / rho_A)^16): inside, where faces may be tiny and far
    // from the rim, the identity, which no shear can fold.
    if (ra > 0 && rb > 0) {
      const double weight = std::pow(std::min(r / ra, 1.0), 16);
      moved.row(s) = (centre + d * (1 + weight * (rb / ra - 1))).transpose();
    }
  }
  return moved;
}

double diagonal(const Mesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInfinity), hi = -lo;
  for (VertexHandle v : mesh.vertices()) {
    lo = lo.cwiseMin(to_eigen(mesh.point(v)));
    hi = hi.cwiseMax(to_eigen(mesh.point(v)));
  }
  return (hi - lo).norm();
}

/// Area-weighted mean over A's faces of the mean distance at their corners, over `scale`.
double mean_distance(const Mesh& a, const std::vector<double>& distance, double scale) {
  double sum = 0, area = 0;
  for (FaceHandle f : a.faces()) {
    const double face_area = a.calc_face_area(f);
    double d = 0;
    for (VertexHandle v : a.fv_range(f)) d += distance[v.idx()];
    sum += face_area * d / 3;
    area += face_area;
  }
  return sum / (area * scale);
}

}  // namespace

namespace detail {

void record_match_flow(const FlowResult& flow, const MatchOptions& options, const char* name,
                       ParameterDomain& domain) {
  if (!flow.converged() && !(flow.max_error < options.accepted_error)) {
    throw SolverError(std::string("the Ricci flow of ") + name + " did not converge (" +
                      to_string(flow.status) + ", max |K - target| " +
                      std::to_string(flow.max_error) + ")");
  }
  domain.metric = to_string(flow.metric.scheme);
  domain.flow_iterations = flow.iterations;
  domain.flow_error = flow.max_error;
}

void harmonic_fill(const Mesh& cut, const Eigen::VectorXd& lengths, const std::vector<char>& fixed,
                   Eigen::MatrixX2d& x) {
  const int n = static_cast<int>(cut.n_vertices());
  std::vector<int> unknown(n, -1);
  int unknowns = 0;
  for (int v = 0; v < n; ++v) {
    if (!fixed[v]) unknown[v] = unknowns++;
  }
  if (unknowns == 0) return;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(unknowns, 2);
  const auto couple = [&](int i, int j, double w) {
    if (fixed[i]) return;
    entries.emplace_back(unknown[i], unknown[i], w);
    if (fixed[j]) {
      rhs.row(unknown[i]) += w * x.row(j);
    } else {
      entries.emplace_back(unknown[i], unknown[j], -w);
    }
  };
  for (FaceHandle f : cut.faces()) {
    const auto h = face_halfedges(cut, f);
    int v[3];
    double a[3];  // a[k]: the side from corner k - 1 to corner k
    for (int k = 0; k < 3; ++k) {
      v[k] = cut.to_vertex_handle(h[k]).idx();
      a[k] = lengths[cut.edge_handle(h[k]).idx()];
    }
    for (int k = 0; k < 3; ++k) {
      const double s = a[k], t = a[(k + 1) % 3], o = a[(k + 2) % 3];
      const double c = std::clamp((s * s + t * t - o * o) / (2 * s * t), -1.0, 1.0);
      const double half = std::tan(0.5 * std::acos(c));
      couple(v[k], v[(k + 2) % 3], half / s);
      couple(v[k], v[(k + 1) % 3], half / t);
    }
  }
  Eigen::SparseMatrix<double> matrix(unknowns, unknowns);
  matrix.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(matrix);
  if (lu.info() != Eigen::Success) {
    throw SolverError("the harmonic map's sparse LU factorisation failed");
  }
  const Eigen::MatrixX2d solved = lu.solve(rhs);
  for (int v = 0; v < n; ++v) {
    if (!fixed[v]) x.row(v) = solved.row(unknown[v]);
  }
}

void place_on_polygon(const std::vector<int>& walk_a, const std::vector<double>& params_a,
                      const std::vector<int>& walk_b, const std::vector<double>& params_b,
                      const Eigen::MatrixX2d& positions_b, double period, Eigen::MatrixX2d& x,
                      std::vector<char>& fixed) {
  const size_t m = walk_b.size();
  size_t j = 0;  // B's side from walk vertex j to j + 1 (mod m) holds the current parameter
  for (size_t i = 0; i < walk_a.size(); ++i) {
    const double s = params_a[i];
    while (j + 1 < m && params_b[j + 1] <= s) ++j;
    const double from = params_b[j], to = j + 1 < m ? params_b[j + 1] : period;
    const double t = to > from ? std::clamp((s - from) / (to - from), 0.0, 1.0) : 0.0;
    const Eigen::RowVector2d p = positions_b.row(walk_b[j]);
    const Eigen::RowVector2d q = positions_b.row(walk_b[(j + 1) % m]);
    x.row(walk_a[i]) = t == 0 ? p : p + t * (q - p);
    fixed[walk_a[i]] = 1;
  }
}

Eigen::MatrixX2d fill_inside(const Mesh& cut_a, const Eigen::VectorXd& lengths_a,
                             const std::vector<int>& walk_a, const std::vector<double>& params_a,
                             const std::vector<int>& walk_b, const std::vector<double>& params_b,
                             const Eigen::MatrixX2d& positions_b, double period) {
  const int n = static_cast<int>(cut_a.n_vertices());
  Eigen::MatrixX2d x = Eigen::MatrixX2d::Zero(n, 2);
  std::vector<char> fixed(n, 0);
  place_on_polygon(walk_a, params_a, walk_b, params_b, positions_b, period, x, fixed);
  harmonic_fill(cut_a, lengths_a, fixed, x);
  return x;
}

void fill_cut_domain(const SlicedMesh& sliced, ParameterDomain& domain) {
  domain.faces.resize(static_cast<Eigen::Index>(sliced.mesh.n_faces()), 3);
  for (FaceHandle f : sliced.mesh.faces()) {
    int k = 0;
    for (VertexHandle v : sliced.mesh.fv_range(f)) domain.faces(f.idx(), k++) = v.idx();
  }
  domain.to_original_vertex = sliced.to_original_vertex;
}

void evaluate_map(const Mesh& a, const Mesh& b, const MeshTables& tables_a,
                  const MeshTables& tables_b, MatchResult& result, bool carry_radially) {
  // Locate every copy of A's vertices in B's domain (phi is the identity there).
  const Locator locator(result.b.positions, result.b.faces);
  const Eigen::MatrixX2d on_domain_b =
      carry_radially ? radial_onto(result.a, result.b) : result.a.positions;
  const Eigen::Index copies = result.a.positions.rows();
  Eigen::MatrixX2d image(copies, 2);
  std::vector<Locator::Hit> hits(static_cast<size_t>(copies));
  for (Eigen::Index s = 0; s < copies; ++s) {
    const Locator::Hit hit = locator.locate(on_domain_b.row(s).transpose());
    hits[static_cast<size_t>(s)] = hit;
    image.row(s).setZero();
    for (int k = 0; k < 3; ++k) {
      image.row(s) += hit.weights[k] * result.b.positions.row(result.b.faces(hit.face, k));
    }
    if (hit.distance > 0) {
      ++result.snapped_vertices;
      result.snap_distance = std::max(result.snap_distance, hit.distance);
    }
  }
  const int na = static_cast<int>(a.n_vertices());
  result.map.resize(static_cast<size_t>(na));
  std::vector<char> done(static_cast<size_t>(na), 0);
  for (Eigen::Index s = 0; s < copies; ++s) {
    const int v = result.a.to_original_vertex[static_cast<size_t>(s)];
    if (done[v]) continue;
    done[v] = 1;
    const Locator::Hit& hit = hits[static_cast<size_t>(s)];
    MapPoint& point = result.map[v];
    point.face = hit.face;
    point.weights = hit.weights;
    for (int k = 0; k < 3; ++k) {
      point.vertices[k] = result.b.to_original_vertex[result.b.faces(hit.face, k)];
    }
  }
  // A face of A with its three corners on its boundary whose image lies flat (within the
  // rounding of the positions) on one side of B's is flattened, not reversed: no map by
  // vertices avoids it (see MatchResult).
  std::vector<char> on_boundary(static_cast<size_t>(copies), 0);
  for (const auto& [side, uses] : side_uses(result.a.faces)) {
    if (uses == 1) on_boundary[side.first] = on_boundary[side.second] = 1;
  }
  for (Eigen::Index f = 0; f < result.a.faces.rows(); ++f) {
    const auto& F = result.a.faces;
    const Eigen::Vector2d p[3] = {image.row(F(f, 0)), image.row(F(f, 1)), image.row(F(f, 2))};
    const double area = signed_area(p[0], p[1], p[2]);
    if (area > 0) continue;
    int rim = 0;
    double longest = 0, extent = 1;
    for (int k = 0; k < 3; ++k) {
      rim += on_boundary[F(f, k)];
      longest = std::max(longest, (p[(k + 1) % 3] - p[k]).norm());
      extent = std::max(extent, p[k].lpNorm<Eigen::Infinity>());
    }
    if (rim == 3 && std::abs(area) <= 1e-13 * extent * longest) {
      ++result.flattened_ears;
    } else {
      ++result.flipped_faces;
    }
  }
  for (Eigen::Index f = 0; f < result.b.faces.rows(); ++f) {
    const auto& F = result.b.faces;
    const auto& P = result.b.positions;
    if (signed_area(P.row(F(f, 0)), P.row(F(f, 1)), P.row(F(f, 2))) <= 0) ++result.flipped_faces_b;
  }
  map_errors(a, b, tables_a, tables_b, result);
}

void map_errors(const Mesh& a, const Mesh& b, const MeshTables& tables_a,
                const MeshTables& tables_b, MatchResult& result) {
  const int na = static_cast<int>(a.n_vertices());
  // Eq. (13), and against the vertex correspondence when the meshes share their connectivity.
  const auto on_b = [&](const MapPoint& point) {
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      r += point.weights[k] * to_eigen(b.point(b.vertex_handle(point.vertices[k])));
    }
    return r;
  };
  const double diag = diagonal(b);
  std::vector<double> shape(static_cast<size_t>(na)), correspondence(static_cast<size_t>(na));
  const bool same = a.n_vertices() == b.n_vertices() && a.n_faces() == b.n_faces() &&
                    tables_a.face_vertices == tables_b.face_vertices;
  for (int v = 0; v < na; ++v) {
    const Eigen::Vector3d r = on_b(result.map[v]);
    shape[v] = (to_eigen(a.point(a.vertex_handle(v))) - r).norm();
    if (same) correspondence[v] = (to_eigen(b.point(b.vertex_handle(v))) - r).norm();
  }
  result.shape_error = mean_distance(a, shape, diag);
  result.correspondence_error =
      same ? mean_distance(a, correspondence, diag) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace detail

MatchResult match_surfaces(const Mesh& a, const Mesh& b, const MatchOptions& options) {
  const Stopwatch watch;
  const SurfaceTopology ta = checked_topology(a, "A"), tb = checked_topology(b, "B");
  if (ta.genus != tb.genus || ta.boundary_loops != tb.boundary_loops) {
    throw InvalidInputError("A is " + topology_text(ta) + " and B " + topology_text(tb) +
                            "; matching needs the same topology");
  }
  if (ta.boundary_loops == 0 || ta.genus > 0) {
    throw InvalidInputError("matching needs genus-0 surfaces with boundary; the meshes are " +
                            topology_text(ta));
  }
  if ((options.feature_a == -1) != (options.feature_b == -1)) {
    throw InvalidInputError("give feature vertices on both surfaces or on neither");
  }
  const MeshTables tables_a = build_mesh_tables(a), tables_b = build_mesh_tables(b);
  MatchResult result;
  bool evaluated = false;  // the cone star evaluates each pairing of loops it tries
  Stopwatch stage;
  if (options.method == MatchMethod::hyperbolic) {
    if (ta.boundary_loops < 3) {
      throw InvalidInputError("the hyperbolic method needs a negative Euler characteristic " +
                              std::string("(three or more boundary loops); the meshes are ") +
                              topology_text(ta) + ": use the euclidean one");
    }
    if (options.feature_a != -1 || !options.corners_a.empty() || !options.corners_b.empty()) {
      throw InvalidInputError("feature vertices and corners are for the euclidean method");
    }
    detail::klein_polygon_domains(a, tables_a, b, tables_b, options, result);
    evaluated = true;
  } else if (ta.boundary_loops == 1 && options.feature_a != -1) {
    result.domain = "unit disk";
    if (!options.corners_a.empty() || !options.corners_b.empty()) {
      throw InvalidInputError("rectangle corners are for disks without feature vertices");
    }
    check_feature(tables_a, options.feature_a, "A");
    check_feature(tables_b, options.feature_b, "B");
    unit_disk_domain(a, options.feature_a, options, "A", result.a);
    result.a.seconds = stage.lap();
    unit_disk_domain(b, options.feature_b, options, "B", result.b);
    result.b.seconds = stage.lap();
  } else if (ta.boundary_loops == 1) {
    result.domain = "rectangle";
    if (options.corners_a.empty() != options.corners_b.empty()) {
      throw InvalidInputError("give rectangle corners on both surfaces or on neither");
    }
    rectangle_domain(a, tables_a, options.corners_a, options, "A", result.a);
    result.a.seconds = stage.lap();
    rectangle_domain(b, tables_b, options.corners_b, options, "B", result.b);
    result.b.seconds = stage.lap();
  } else {
    result.domain = "cone star";
    if (!options.corners_a.empty() || !options.corners_b.empty()) {
      throw InvalidInputError("rectangle corners are for disks without feature vertices");
    }
    if (options.feature_a != -1) {
      check_feature(tables_a, options.feature_a, "A");
      check_feature(tables_b, options.feature_b, "B");
    }
    result.a.feature = options.feature_a != -1
                           ? options.feature_a
                           : detail::farthest_interior_vertex(
                                 a, tables_a, static_cast<int>(tables_a.boundary_loops.size()));
    result.b.feature = options.feature_b != -1
                           ? options.feature_b
                           : detail::farthest_interior_vertex(
                                 b, tables_b, static_cast<int>(tables_b.boundary_loops.size()));
    const EdgeLengths flat_a = cone_flow(a, tables_a, result.a.feature, options, "A", result.a);
    const Star star_a = detail::cone_star(a, tables_a, result.a.feature, flat_a, "A", false);
    result.a.seconds = stage.lap();
    const EdgeLengths flat_b = cone_flow(b, tables_b, result.b.feature, options, "B", result.b);
    const Star star_b = detail::cone_star(b, tables_b, result.b.feature, flat_b, "B", false);
    result.b.seconds = stage.lap();
    // The pairs of stars tried, each with the turns of B's star that pair the loops: the two
    // stars when their orders agree; else each surface's rays in both orders (rank order, or
    // nearest loop first, which does not depend on the ranks: rays taken in rank order go round
    // other loops when the ranks differ), at every turn that pairs loops of about the same
    // length.
    std::vector<Candidate> candidates;
    std::optional<Star> reach_a, reach_b;
    if (star_a.loop_order == star_b.loop_order) {
      candidates.push_back({&star_a, &star_b, {0}});
    } else if (options.loop_length_tolerance > 0) {
      const std::vector<double> lengths_a = relative_loop_lengths(a, tables_a),
                                lengths_b = relative_loop_lengths(b, tables_b);
      reach_a = detail::cone_star(a, tables_a, result.a.feature, flat_a, "A", true);
      reach_b = detail::cone_star(b, tables_b, result.b.feature, flat_b, "B", true);
      for (const Star* sa : std::array<const Star*, 2>{&star_a, &*reach_a}) {
        for (const Star* sb : std::array<const Star*, 2>{&star_b, &*reach_b}) {
          std::vector<int> turns =
              pairing_turns(*sa, *sb, lengths_a, lengths_b, options.loop_length_tolerance);
          if (!turns.empty()) candidates.push_back({sa, sb, std::move(turns)});
        }
      }
    }
    // Else, loops paired by length alone, one surface's rays forced into the other's order.
    std::deque<Star> forced;
    if (candidates.empty() && options.loop_length_tolerance > 0) {
      const MeshCut cut_a{&a, &tables_a, &flat_a, &star_a}, cut_b{&b, &tables_b, &flat_b, &star_b};
      forced_candidates(cut_a, cut_b, options, result, forced, candidates);
    }
    if (candidates.empty()) {
      const auto text = [](const std::vector<int>& order) {
        std::string t;
        for (int rank : order) t += (t.empty() ? "c" : " c") + std::to_string(rank);
        return t;
      };
      throw InvalidInputError(
          "the cuts leave the feature vertex towards the boundary loops in "
          "a different order on A (" +
          text(star_a.loop_order) + ") and B (" + text(star_b.loop_order) +
          ") and neither a turn nor rays forced into one order pair loops of the same length; " +
          "choose other feature vertices");
    }
    result.a.seconds += stage.lap();
    MatchResult best;
    for (const Candidate& candidate : candidates) {
      const Star& star_a_cut = *candidate.a;
      for (int turn : candidate.turns) {
        const Star star = rotated(*candidate.b, turn);
        MatchResult trial = result;
        trial.a.loop_order = star_a_cut.loop_order;
        trial.b.loop_order = star.loop_order;
        bool pieces = false;
        if (options.decompose) {
          try {
            detail::cone_pieces(a, star_a_cut, flat_a, b, star, flat_b, trial);
            pieces = true;
          } catch (const TopologyError&) {
            // no gamma on both surfaces, or pieces that differ: one convex piece
          }
        }
        if (!pieces) one_convex_piece(star_a_cut, star, trial);
        detail::evaluate_map(a, b, tables_a, tables_b, trial, false);
        if (best.map.empty() || trial.shape_error < best.shape_error) best = std::move(trial);
      }
    }
    result = std::move(best);
    result.b.seconds += stage.lap();
    evaluated = true;
  }
  // The unit disk's two conformal maps sample the circle at different vertices: A's are carried
  // radially into B's polygon. The rectangle's sides are straight: A's boundary is on B's.
  if (!evaluated) {
    detail::evaluate_map(a, b, tables_a, tables_b, result, result.domain == "unit disk");
  }
  result.seconds = watch.seconds();
  return result;
}

double texture_error(const Mesh& a, const Mesh& b, const MatchResult& result,
                     const Eigen::MatrixX3d& colours_a, const Eigen::MatrixX3d& colours_b) {
  if (colours_a.rows() != static_cast<Eigen::Index>(a.n_vertices()) ||
      colours_b.rows() != static_cast<Eigen::Index>(b.n_vertices()) ||
      result.map.size() != a.n_vertices()) {
    throw InvalidInputError("the texture error needs one colour per vertex of A and of B");
  }
  std::vector<double> difference(a.n_vertices()), brightness(b.n_vertices());
  for (size_t v = 0; v < result.map.size(); ++v) {
    const MapPoint& p = result.map[v];
    Eigen::RowVector3d on_b = Eigen::RowVector3d::Zero();
    for (int k = 0; k < 3; ++k) on_b += p.weights[k] * colours_b.row(p.vertices[k]);
    difference[v] = (colours_a.row(static_cast<Eigen::Index>(v)) - on_b).norm();
  }
  for (size_t v = 0; v < brightness.size(); ++v) {
    brightness[v] = colours_b.row(static_cast<Eigen::Index>(v)).norm();
  }
  const double mean_b = mean_distance(b, brightness, 1.0);
  if (!(mean_b > 0)) throw InvalidInputError("B's colours are all black; d_t is undefined");
  return mean_distance(a, difference, 1.0) / mean_b;
}

std::string surface_map_text(const MatchResult& result, int vertices_b, int faces_b) {
  std::ostringstream out;
  out << "msp-map 1 " << result.map.size() << " " << vertices_b << " " << faces_b << "\n";
  char line[160];
  for (const MapPoint& p : result.map) {
    std::snprintf(line, sizeof(line), "%d %d %d %d %.17g %.17g %.17g\n", p.face, p.vertices[0],
                  p.vertices[1], p.vertices[2], p.weights[0], p.weights[1], p.weights[2]);
    out << line;
  }
  return out.str();
}

}  // namespace ricci
