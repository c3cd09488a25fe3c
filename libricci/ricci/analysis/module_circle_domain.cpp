// The circle domain of a multiply connected domain (ricci-flow-3d-shape-analysis §5.1.3): the
// flat metric conformal to the mesh whose boundary loops have constant geodesic curvature (total
// 2π on c0, -2π on each hole) is found by a fixed-point iteration on the Ricci flow's boundary
// targets (each loop's total spread by the current metric's lengths, the flow restarted from
// the last metric, whose discrete conformal structure never changes); laid out, it is a disk
// with circular holes, then normalised by a Möbius map. Koebe's fill-and-map iteration
// (Algorithm 7), which re-derives the discrete structure from each step's planar layout, was
// tried first and drifted away from the answer over the sweeps.
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <numeric>
#include <queue>

#include <Eigen/Dense>

#include "ricci/analysis/module_internal.h"
#include "ricci/layout/layout_e2.h"
#include "ricci/mesh/errors.h"
#include "ricci/topology/cut_graph.h"

namespace ricci::detail {

namespace {

struct Circle {
  Complex centre;
  double radius = 0;
};

/// The point p inside the unit disk that the automorphism z -> (z - p) / (1 - conj(p) z) sends
/// to the common centre of the unit circle and `circle`'s image: the one of the two points
/// symmetric with respect to both circles (x and 1/x on the ray through the centre a, with
/// (x - |a|)(1/x - |a|) = r²) that lies inside the disk.
Complex concentric_point(const Circle& circle) {
  const double a = std::abs(circle.centre), r = circle.radius;
  if (a < 1e-15) return 0;
  const double b = 1 + a * a - r * r;
  const double x = (b - std::sqrt(std::max(0.0, b * b - 4 * a * a))) / (2 * a);
  return x * circle.centre / a;
}

/// Least-squares (Kåsa) circle through planar points, fitted about their centroid.
Circle fit_circle(const std::vector<Complex>& points) {
  Complex mean = 0;
  for (Complex p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::MatrixX3d a(static_cast<Eigen::Index>(points.size()), 3);
  Eigen::VectorXd b(a.rows());
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const Complex q = points[static_cast<size_t>(i)] - mean;
    a.row(i) << q.real(), q.imag(), 1.0;
    b[i] = -std::norm(q);
  }
  const Eigen::Vector3d x = a.colPivHouseholderQr().solve(b);
  const Complex centre(-0.5 * x[0], -0.5 * x[1]);
  return {centre + mean, std::sqrt(std::max(0.0, std::norm(centre) - x[2]))};
}

/// Lays the current flat metric out and normalises it: z by mesh vertex, and the circles (or
/// points, radius 0) whose standing ends the iteration; the first order.size() are the loops'.
using Normalise = std::function<std::vector<Circle>(std::vector<Complex>&)>;

/// The fixed point of the boundary targets: each loop's geodesic curvature `total[k]` spread by
/// the current metric's boundary lengths, half a step at a time, until the targets or the
/// normalised domain stand. Fills the flow figures and the roundness of `result`; returns the
/// last domain's circles (z its positions). `result.converged` false: stopped early.
std::vector<Circle> round_boundaries(const MeshTables& tables, const std::vector<int>& order,
                                     const std::vector<double>& total, const ModuleOptions& options,
                                     FlatMetric& metric, const Normalise& normalised,
                                     std::vector<Complex>& z, ModuleResult& result) {
  const int vertices = tables.num_vertices();
  // Constant geodesic curvature on each loop: its total (2π on c0, -2π on each hole) spread by
  // the current metric's boundary lengths; repeated until the spread stops changing.
  const auto targets_for = [&]() {
    Targets targets;
    targets.curvature = Eigen::VectorXd::Zero(vertices);
    for (size_t k = 0; k < tables.boundary_loops.size(); ++k) {
      const std::vector<int>& loop = tables.boundary_loops[k];
      const std::vector<double> edge = metric.loop_lengths(loop);
      double length = 0;
      for (double l : edge) length += l;
      for (size_t i = 0; i < loop.size(); ++i) {
        const double dual = 0.5 * (edge[i] + edge[(i + loop.size() - 1) % loop.size()]);
        targets.curvature[loop[i]] = total[k] * dual / length;
      }
    }
    return targets;
  };
  Targets targets = targets_for();
  FlowResult current = metric.solve(targets);
  int iterations = current.iterations;
  double last_change = INFINITY;
  double damping = 0.5;
  std::vector<Circle> previous;  // the domain of the flow before
  bool standing = false;         // the loop ended on a standing module: previous is current's
  for (int sweep = 1; sweep <= options.max_circle_iterations; ++sweep) {
    record_flow(current, options, result);
    result.flow_iterations = iterations;
    result.circle_iterations = sweep;
    if (!result.converged) return {};
    const Targets next = targets_for();
    const double change = (next.curvature - targets.curvature).cwiseAbs().maxCoeff();
    // The circle domains form a family (Möbius maps of the disk) along which the targets may
    // keep sliding at a constant rate once the shape is round: stop when a small change stalls.
    const bool sliding = sweep > 3 && change > 0.9 * last_change && change < 1e-5;
    if (change < options.circle_tolerance || sliding) break;
    // The module is Möbius-normalised, so the sliding does not move it: stop when it stands.
    if (change < 1e-3) {
      std::vector<Circle> now = normalised(z);
      double moved = previous.empty() ? INFINITY : 0.0;
      for (size_t k = 0; k < now.size() && !previous.empty(); ++k) {
        moved = std::max({moved, std::abs(now[k].centre - previous[k].centre),
                          std::abs(now[k].radius - previous[k].radius)});
      }
      previous = std::move(now);
      if (moved < options.circle_module_tolerance) {
        standing = true;
        break;
      }
    }
    // Half steps: the full update overshoots and grows. Where a loop's targets still swing
    // back and forth (a change that does not shrink while above 1e-3: a period-2 oscillation,
    // beetle.off's small holes), the step is halved again, down to 1/16.
    if (change > 1e-3 && change > 0.9 * last_change) damping = std::max(damping / 2, 1.0 / 16);
    last_change = change;
    targets.curvature += damping * (next.curvature - targets.curvature);
    current = metric.solve(targets);
    iterations += current.iterations;
  }
  // The last flow's domain, unless the loop just laid it out.
  const std::vector<Circle> circles = standing ? previous : normalised(z);
  result.roundness = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    for (int v : tables.boundary_loops[order[k]]) {
      result.roundness = std::max(
          result.roundness,
          std::abs(std::abs(z[v] - circles[k].centre) - circles[k].radius) / circles[k].radius);
    }
  }
  return circles;
}

}  // namespace

std::vector<int> loops_by_length(const Mesh& mesh, const MeshTables& tables) {
  std::vector<double> length(tables.boundary_loops.size(), 0.0);
  for (size_t k = 0; k < length.size(); ++k) {
    const std::vector<int>& loop = tables.boundary_loops[k];
    for (size_t i = 0; i < loop.size(); ++i) {
      length[k] += (mesh.point(mesh.vertex_handle(loop[i])) -
                    mesh.point(mesh.vertex_handle(loop[(i + 1) % loop.size()])))
                       .norm();
    }
  }
  std::vector<int> order(length.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return length[a] > length[b]; });
  return order;
}

namespace {

class FixedFlatMetric : public FlatMetric {
 public:
  FixedFlatMetric(const Mesh& mesh, const MeshTables& tables, const FlowOptions& options,
                  int cut_root)
      : mesh_(mesh), tables_(tables), options_(options), cut_root_(cut_root) {}

  FlowResult solve(const Targets& targets) override {
    current_ = started_ ? flow(tables_, current_.metric, targets, options_)
                        : flow(mesh_, targets, options_);
    started_ = true;
    return current_;
  }

  std::vector<double> loop_lengths(const std::vector<int>& loop) const override {
    const EdgeLengths& lengths = started_ ? current_.lengths : mesh_lengths();
    std::vector<double> edge(loop.size());
    for (size_t i = 0; i < loop.size(); ++i) {
      const VertexHandle next = mesh_.vertex_handle(loop[(i + 1) % loop.size()]);
      const HalfedgeHandle h = mesh_.find_halfedge(mesh_.vertex_handle(loop[i]), next);
      edge[i] = lengths[mesh_.edge_handle(h).idx()];
    }
    return edge;
  }

  // Cut along tree paths from the root's loop to the others: the holonomy around each round
  // hole is trivial, so the copies of a cut vertex coincide.
  void layout(std::vector<Complex>& z) const override {
    const EdgeLengths& lengths = current_.lengths;
    z.assign(tables_.num_vertices(), 0);
    if (cut_root_ < 0) {
      const LayoutE2Result layout = layout_e2(mesh_, lengths);
      for (int v = 0; v < tables_.num_vertices(); ++v) {
        z[v] = Complex(layout.positions(v, 0), layout.positions(v, 1));
      }
      return;
    }
    const CutGraph cut = compute_cut_graph(mesh_, mesh_.vertex_handle(cut_root_), lengths);
    const SlicedMesh sliced = slice_along(mesh_, cut.is_cut_edge);
    check_disk(sliced, "circle-domain slice");
    const LayoutE2Result layout = layout_e2(sliced.mesh, sliced_edge_lengths(sliced, lengths));
    for (int s = 0; s < static_cast<int>(sliced.mesh.n_vertices()); ++s) {
      z[sliced.to_original_vertex[s]] = Complex(layout.positions(s, 0), layout.positions(s, 1));
    }
  }

  Eigen::MatrixX3i faces() const override {
    CanonicalDomain domain;
    copy_faces(mesh_, domain);
    return domain.faces;
  }

 private:
  const EdgeLengths& mesh_lengths() const {
    if (initial_.size() == 0) initial_ = mesh_edge_lengths(mesh_);
    return initial_;
  }

  const Mesh& mesh_;
  const MeshTables& tables_;
  FlowOptions options_;
  int cut_root_;
  bool started_ = false;
  FlowResult current_;
  mutable EdgeLengths initial_;
};

}  // namespace

std::unique_ptr<FlatMetric> fixed_flat_metric(const Mesh& mesh, const MeshTables& tables,
                                              const FlowOptions& options, int cut_root) {
  return std::make_unique<FixedFlatMetric>(mesh, tables, options, cut_root);
}

void circle_domain_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                          ModuleResult& result, FlatMetric* metric) {
  const std::vector<int> order = loops_by_length(mesh, tables);
  const int holes = static_cast<int>(order.size()) - 1;
  // Lay the flat surface out, then c0 onto the unit circle, the disk automorphism that makes c1
  // concentric with it, c2's centre onto the positive real axis.
  const int root = tables.boundary_loops[order[0]][0];
  std::unique_ptr<FlatMetric> fixed;
  if (metric == nullptr) {
    fixed = fixed_flat_metric(mesh, tables, options.flow, root);
    metric = fixed.get();
  }
  const Normalise normalised = [&](std::vector<Complex>& z) {
    metric->layout(z);
    const auto circle_of = [&](int k) {
      std::vector<Complex> points;
      for (int v : tables.boundary_loops[k]) points.push_back(z[v]);
      return fit_circle(points);
    };
    const Circle outer = circle_of(order[0]);
    for (Complex& q : z) q = (q - outer.centre) / outer.radius;
    const Complex p = concentric_point(circle_of(order[1]));
    for (Complex& q : z) q = (q - p) / (1.0 - std::conj(p) * q);
    std::vector<Circle> circles;
    for (int k : order) circles.push_back(circle_of(k));
    const Complex turn = std::abs(circles[2].centre) > 0
                             ? std::conj(circles[2].centre) / std::abs(circles[2].centre)
                             : Complex(1);
    for (Complex& q : z) q *= turn;
    for (Circle& c : circles) c.centre *= turn;
    return circles;
  };
  std::vector<double> total(order.size(), -2 * M_PI);
  total[order[0]] = 2 * M_PI;
  std::vector<Complex> z;
  const std::vector<Circle> circles =
      round_boundaries(tables, order, total, options, *metric, normalised, z, result);
  if (!result.converged) return;
  if (result.roundness > options.max_roundness) {
    result.converged = false;
    result.message = "the circle-domain iteration did not converge: a boundary vertex is " +
                     std::to_string(result.roundness) +
                     " of its loop's radius off its circle after " +
                     std::to_string(result.circle_iterations) + " flows";
  }
  for (int k = 1; k <= holes; ++k) {
    const std::string index = std::to_string(k);
    if (k >= 3) {
      result.values.push_back(circles[k].centre.real());
      result.names.push_back("x" + index);
    }
    if (k >= 2) {
      result.values.push_back(k == 2 ? circles[k].centre.real() : circles[k].centre.imag());
      result.names.push_back((k == 2 ? "x" : "y") + index);
    }
    result.values.push_back(circles[k].radius);
    result.names.push_back("r" + index);
  }
  CanonicalDomain& domain = result.domain;
  domain.positions.resize(static_cast<Eigen::Index>(z.size()), 2);
  for (size_t v = 0; v < z.size(); ++v) {
    domain.positions.row(static_cast<Eigen::Index>(v)) << z[v].real(), z[v].imag();
  }
  domain.faces = metric->faces();
  for (int k = 0; k <= holes; ++k) {
    domain.boundaries.push_back(tables.boundary_loops[order[k]]);
    domain.boundary_loop.push_back(k);
  }
}

int farthest_interior_vertex(const Mesh& mesh, const MeshTables& tables, int min_valence) {
  const EdgeLengths lengths = mesh_edge_lengths(mesh);
  std::vector<double> dist(tables.num_vertices(), INFINITY);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (const auto& loop : tables.boundary_loops) {
    for (int v : loop) {
      dist[v] = 0;
      queue.push({0.0, v});
    }
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    for (HalfedgeHandle h : mesh.voh_range(mesh.vertex_handle(v))) {
      const int w = mesh.to_vertex_handle(h).idx();
      const double nd = d + lengths[mesh.edge_handle(h).idx()];
      if (nd < dist[w]) {
        dist[w] = nd;
        queue.push({nd, w});
      }
    }
  }
  int best = -1;
  bool best_enough = false;
  for (int v = 0; v < tables.num_vertices(); ++v) {
    if (tables.is_boundary_vertex[v]) continue;
    const bool enough = tables.valence[v] >= min_valence;
    if (best < 0 || (enough && !best_enough) || (enough == best_enough && dist[v] > dist[best])) {
      best = v;
      best_enough = enough;
    }
  }
  if (best < 0) throw InvalidInputError("the mesh has no interior vertex");
  return best;
}

void disk_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                 ModuleResult& result) {
  const int vertices = tables.num_vertices();
  int centre = options.centre;
  if (centre == -1) centre = farthest_interior_vertex(mesh, tables, 0);
  if (centre < 0 || centre >= vertices || tables.is_boundary_vertex[centre]) {
    throw InvalidInputError("the disk's centre vertex " + std::to_string(centre) +
                            " is out of range or on the boundary");
  }
  // The boundary vertex nearest the centre along edge paths goes to 1.
  const EdgeLengths lengths3d = mesh_edge_lengths(mesh);
  std::vector<double> dist(vertices, INFINITY);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  dist[centre] = 0;
  queue.push({0.0, centre});
  int one = -1;
  while (!queue.empty() && one < 0) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    if (tables.is_boundary_vertex[v]) one = v;
    for (HalfedgeHandle h : mesh.voh_range(mesh.vertex_handle(v))) {
      const int w = mesh.to_vertex_handle(h).idx();
      const double nd = d + lengths3d[mesh.edge_handle(h).idx()];
      if (nd < dist[w]) {
        dist[w] = nd;
        queue.push({nd, w});
      }
    }
  }
  const std::vector<int>& loop = tables.boundary_loops[0];
  // Laid out (a disk needs no cut), the boundary's circle onto the unit circle, the disk
  // automorphism that sends the centre to 0, the rotation that sends `one` to 1. The boundary
  // vertices' positions are what must stand.
  const std::unique_ptr<FlatMetric> metric = fixed_flat_metric(mesh, tables, options.flow, -1);
  const Normalise normalised = [&](std::vector<Complex>& z) {
    metric->layout(z);
    std::vector<Complex> points;
    for (int v : loop) points.push_back(z[v]);
    const Circle outer = fit_circle(points);
    for (Complex& q : z) q = (q - outer.centre) / outer.radius;
    const Complex p = z[centre];
    for (Complex& q : z) q = (q - p) / (1.0 - std::conj(p) * q);
    const Complex turn = std::abs(z[one]) > 0 ? std::conj(z[one]) / std::abs(z[one]) : Complex(1);
    for (Complex& q : z) q *= turn;
    std::vector<Circle> circles = {{Complex(0), 1.0}};
    for (int v : loop) circles.push_back({z[v], 0.0});
    return circles;
  };
  std::vector<Complex> z;
  (void)round_boundaries(tables, {0}, {2 * M_PI}, options, *metric, normalised, z, result);
  if (!result.converged) return;
  if (result.roundness > options.max_roundness) {
    result.converged = false;
    result.message = "the disk iteration did not converge: a boundary vertex is " +
                     std::to_string(result.roundness) + " off the unit circle after " +
                     std::to_string(result.circle_iterations) + " flows";
  }
  result.corners = {centre, one};
  CanonicalDomain& domain = result.domain;
  domain.positions.resize(vertices, 2);
  for (int v = 0; v < vertices; ++v) domain.positions.row(v) << z[v].real(), z[v].imag();
  copy_faces(mesh, domain);
  domain.boundaries.push_back(loop);
  domain.boundary_loop.push_back(0);
  domain.corners = {centre, one};
}

}  // namespace ricci::detail
