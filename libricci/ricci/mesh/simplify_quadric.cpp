#include "ricci/mesh/simplify_quadric.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <vector>

#include "ricci/util/parallel.h"

namespace ricci {
namespace {

// Boundary planes count this many face planes: a rim moves only along itself.
constexpr double kBoundaryWeight = 100.0;

// QuadricDecimateOptions::regions = 0: two regions from this many faces, one below. The domain
// (and a fit's max error and seam) moves with the collapse order as much as it moves between
// fits of a differently sampled scan; at 100k the first stage is ~6% of msp fit's CPU and at 1M
// ~25%, so scans below this size keep the collapses of one queue.
constexpr int kRegionsMinimumFaces = 400000;
// The regions stop at this many times the target; one queue over the whole mesh decides the
// last collapses (and those of the locked cut).
constexpr int kRegionsLeaveFactor = 2;

using Quadric = Eigen::Matrix4d;

Quadric plane_quadric(const Eigen::Vector3d& unit_normal, const Eigen::Vector3d& through,
                      double weight) {
  Eigen::Vector4d p;
  p << unit_normal, -unit_normal.dot(through);
  return weight * p * p.transpose();
}

double error(const Quadric& q, const Eigen::Vector3d& x) {
  const Eigen::Vector4d v(x.x(), x.y(), x.z(), 1.0);
  return v.dot(q * v);
}

struct Placement {
  double cost = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};

// The point minimising the quadric error of q, else (near-singular system, e.g. a flat region
// where every point of the plane is optimal, or an optimum far off the edge) the best of the
// two ends and the midpoint.
Placement place(const Quadric& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Placement best{error(q, a), a};
  for (const Eigen::Vector3d& x : {b, Eigen::Vector3d(0.5 * (a + b))}) {
    const double e = error(q, x);
    if (e < best.cost) best = {e, x};
  }
  const Eigen::Matrix3d m = q.topLeftCorner<3, 3>();
  const double det = m.determinant();
  const double scale = m.cwiseAbs().maxCoeff();
  if (std::abs(det) > 1e-8 * scale * scale * scale) {
    const Eigen::Vector3d x = m.inverse() * (-q.topRightCorner<3, 1>());
    const double length = (b - a).norm();
    if (x.allFinite() && (x - 0.5 * (a + b)).norm() <= 2.0 * length) {
      const double e = error(q, x);
      if (e <= best.cost) best = {e, x};
    }
  }
  best.cost = std::max(best.cost, 0.0);
  return best;
}

struct Entry {
  double cost;
  int edge;
  std::uint32_t stamp;
  bool operator<(const Entry& other) const { return cost > other.cost; }  // min-heap
};

class Decimator {
  using Queue = std::priority_queue<Entry>;

 public:
  explicit Decimator(Mesh& mesh) : mesh_(mesh) {
    mesh_.request_vertex_status();
    mesh_.request_edge_status();
    mesh_.request_halfedge_status();
    mesh_.request_face_status();
    quadrics_.assign(mesh_.n_vertices(), Quadric::Zero());
    for (auto f : mesh_.faces()) {
      const Eigen::Vector3d n = raw_normal(f, VertexHandle(), Eigen::Vector3d::Zero());
      if (!(n.norm() > 0.0)) continue;
      const Eigen::Vector3d p = point(*mesh_.fv_begin(f));
      const Quadric q = plane_quadric(n.normalized(), p, 1.0);
      for (auto v : mesh_.fv_range(f)) quadrics_[v.idx()] += q;
    }
    for (auto h : mesh_.halfedges()) {
      if (!mesh_.is_boundary(h)) continue;
      const auto face = mesh_.face_handle(mesh_.opposite_halfedge_handle(h));
      const Eigen::Vector3d n = raw_normal(face, VertexHandle(), Eigen::Vector3d::Zero());
      const Eigen::Vector3d p = point(mesh_.from_vertex_handle(h));
      const Eigen::Vector3d e = point(mesh_.to_vertex_handle(h)) - p;
      const Eigen::Vector3d m = e.cross(n);
      if (!(m.norm() > 0.0)) continue;
      const Quadric q = plane_quadric(m.normalized(), p, kBoundaryWeight);
      quadrics_[mesh_.from_vertex_handle(h).idx()] += q;
      quadrics_[mesh_.to_vertex_handle(h).idx()] += q;
    }
    stamps_.assign(mesh_.n_edges(), 0);
    placements_.resize(mesh_.n_edges());
    // The first placements in parallel (each edge its own slot), queued in edge order as push
    // would: the same heap, so the same collapses.
    parallel_for(mesh_.n_edges(), 0, [&](std::size_t i) {
      placements_[i] = placement(mesh_.edge_handle(static_cast<int>(i)));
    });
    faces_ = static_cast<int>(mesh_.n_faces());
  }

  // Decimates each region (label[v]: its region, or -1 for a vertex locked at a cut) on its own
  // thread until `left` faces remain in all. A collapse changes only the elements around its two
  // ends, and a region's edges have both ends unlocked in it, so no two threads touch the same
  // element: the result does not depend on the threads or their timing. The regions advance in
  // epochs up to a common cost bound, doubled from one epoch to the next, so that they collapse
  // about the edges one queue would; in each epoch a region removes at most its share (by its
  // faces) of what is left to remove, and the first epoch where one reaches its share is the last.
  void run_regions(const std::vector<int>& label, int regions_count, int left, int threads) {
    const auto regions = static_cast<std::size_t>(regions_count);
    // Faces not yet removed with a vertex in each region.
    std::vector<long long> region_faces(regions, 0);
    for (auto f : mesh_.faces()) {
      for (auto v : mesh_.fv_range(f)) {
        // a face has unlocked vertices of one region at most
        if (label[static_cast<std::size_t>(v.idx())] < 0) continue;
        ++region_faces[static_cast<std::size_t>(label[static_cast<std::size_t>(v.idx())])];
        break;
      }
    }
    std::vector<std::vector<Entry>> entries(regions);
    for (auto e : mesh_.edges()) {
      const int region = label[end_vertex(e, 0).idx()];
      if (region >= 0 && in_region(e, label, region)) {
        entries[static_cast<std::size_t>(region)].push_back(entry(e));
      }
    }
    double bound = first_bound(entries, faces_ - left);
    std::vector<Queue> queues;
    for (auto& list : entries) queues.emplace_back(std::less<Entry>(), std::move(list));
    const int workers = std::min(requested_threads(threads), static_cast<int>(regions));
    for (;;) {
      const long long removable = faces_ - left;
      long long faces = 0;
      for (long long f : region_faces) faces += f;
      if (removable <= 0 || faces == 0) return;
      std::vector<int> budget(regions), removed(regions, 0);
      for (std::size_t r = 0; r < regions; ++r) {
        budget[r] = static_cast<int>(removable * region_faces[r] / faces);
      }
      run_blocks_on_demand(workers, regions, 1, [&](std::size_t r) {
        removed[r] = collapse(queues[r], budget[r], bound, &label, static_cast<int>(r));
      });
      bool full = false, empty = true;
      double lowest = std::numeric_limits<double>::infinity();
      for (std::size_t r = 0; r < regions; ++r) {
        faces_ -= removed[r];
        region_faces[r] -= removed[r];
        full = full || (budget[r] > 0 && removed[r] >= budget[r]);
        if (!queues[r].empty()) {
          empty = false;
          lowest = std::min(lowest, queues[r].top().cost);
        }
      }
      if (full || empty) return;
      bound = std::max(2.0 * bound, lowest);
    }
  }

  // The first epoch's cost bound: the queued edges' cost below which lie a quarter of the
  // collapses wanted (two faces each), so that the epochs start where the collapses do.
  static double first_bound(const std::vector<std::vector<Entry>>& entries, long long removable) {
    std::vector<double> costs;
    for (const auto& list : entries) {
      for (const Entry& entry : list) costs.push_back(entry.cost);
    }
    const auto rank = static_cast<std::size_t>(std::max(0LL, removable / 8));
    if (costs.empty() || rank >= costs.size()) return 0.0;
    const auto nth = costs.begin() + static_cast<std::ptrdiff_t>(rank);
    std::nth_element(costs.begin(), nth, costs.end());
    return *nth;
  }

  // Collapses in cost order over every remaining edge down to target_faces.
  int run(int target_faces) {
    std::vector<Entry> entries;
    entries.reserve(4 * mesh_.n_edges());
    Queue queue(std::less<Entry>(), std::move(entries));
    for (auto e : mesh_.edges()) {
      if (!mesh_.status(e).deleted()) queue.push(entry(e));
    }
    const double any = std::numeric_limits<double>::infinity();
    faces_ -= collapse(queue, static_cast<int>(faces_ - target_faces), any, nullptr, 0);
    mesh_.garbage_collection();
    return static_cast<int>(mesh_.n_faces());
  }

 private:
  // Pops `queue` until `budget` faces are removed, it is empty or its cheapest edge costs more
  // than `bound`. With `label`, only edges with both ends in `region` are queued again (the
  // placements of all are kept current).
  int collapse(Queue& queue, int budget, double bound, const std::vector<int>* label, int region) {
    int removed = 0;
    while (removed < budget && !queue.empty() && !(queue.top().cost > bound)) {
      const Entry top = queue.top();
      queue.pop();
      const auto e = mesh_.edge_handle(top.edge);
      if (mesh_.status(e).deleted() || top.stamp != stamps_[top.edge]) continue;
      const Eigen::Vector3d x = placements_[top.edge].point;
      HalfedgeHandle h = mesh_.halfedge_handle(e, 0);
      if (!collapse_allowed(h, x)) {
        h = mesh_.halfedge_handle(e, 1);
        if (!collapse_allowed(h, x)) continue;  // until a neighbour's collapse re-queues it
      }
      removed += (mesh_.is_boundary(e) ? 1 : 2);
      const auto from = mesh_.from_vertex_handle(h), to = mesh_.to_vertex_handle(h);
      const Quadric q = quadrics_[from.idx()] + quadrics_[to.idx()];
      mesh_.collapse(h);
      mesh_.set_point(to, to_openmesh(x));
      quadrics_[to.idx()] = q;
      for (auto around : mesh_.ve_range(to)) {
        placements_[around.idx()] = placement(around);
        if (label == nullptr || in_region(around, *label, region)) queue.push(entry(around));
      }
    }
    return removed;
  }

  Eigen::Vector3d point(VertexHandle v) const { return to_eigen(mesh_.point(v)); }

  // Unnormalised normal of f, with vertex `moved` (if valid) placed at x.
  Eigen::Vector3d raw_normal(FaceHandle f, VertexHandle moved, const Eigen::Vector3d& x) const {
    Eigen::Vector3d p[3];
    int k = 0;
    for (auto v : mesh_.fv_range(f)) p[k++] = v == moved ? x : point(v);
    return (p[1] - p[0]).cross(p[2] - p[0]);
  }

  Placement placement(EdgeHandle e) const {
    const auto h = mesh_.halfedge_handle(e, 0);
    const auto a = mesh_.from_vertex_handle(h), b = mesh_.to_vertex_handle(h);
    return place(quadrics_[a.idx()] + quadrics_[b.idx()], point(a), point(b));
  }

  // Edge e's queue entry at its current placement's cost, with a new stamp making its older
  // entries stale.
  Entry entry(EdgeHandle e) { return {placements_[e.idx()].cost, e.idx(), ++stamps_[e.idx()]}; }

  VertexHandle end_vertex(EdgeHandle e, int end) const {
    return mesh_.to_vertex_handle(mesh_.halfedge_handle(e, end));
  }

  bool in_region(EdgeHandle e, const std::vector<int>& label, int region) const {
    return label[end_vertex(e, 0).idx()] == region && label[end_vertex(e, 1).idx()] == region;
  }

  // Link condition, and no remaining face around either end turned by 90 degrees or more (or
  // made degenerate) when both ends move to x.
  bool collapse_allowed(HalfedgeHandle h, const Eigen::Vector3d& x) const {
    if (!mesh_.is_collapse_ok(h)) return false;
    const auto from = mesh_.from_vertex_handle(h), to = mesh_.to_vertex_handle(h);
    const auto gone_a = mesh_.face_handle(h);
    const auto gone_b = mesh_.face_handle(mesh_.opposite_halfedge_handle(h));
    for (auto v : {from, to}) {
      for (auto f : mesh_.vf_range(v)) {
        if (f == gone_a || f == gone_b) continue;
        const Eigen::Vector3d before = raw_normal(f, VertexHandle(), x);
        const Eigen::Vector3d after = raw_normal(f, v, x);
        if (!(before.dot(after) > 0.0)) return false;
      }
    }
    return true;
  }

  Mesh& mesh_;
  std::vector<Quadric> quadrics_;
  std::vector<std::uint32_t> stamps_;
  std::vector<Placement> placements_;
  long long faces_ = 0;  // faces not yet removed
};

// Each vertex's region: slabs of equal vertex counts across the bounding box's longest axis,
// then -1 for every vertex with a neighbour in another slab (the cut's vertices are locked).
std::vector<int> slab_regions(const Mesh& mesh, int regions) {
  const std::size_t n = mesh.n_vertices();
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (auto v : mesh.vertices()) {
    low = low.cwiseMin(to_eigen(mesh.point(v)));
    high = high.cwiseMax(to_eigen(mesh.point(v)));
  }
  int axis = 0;
  (high - low).maxCoeff(&axis);
  std::vector<double> coordinate(n);
  for (auto v : mesh.vertices()) {
    coordinate[static_cast<std::size_t>(v.idx())] = mesh.point(v)[axis];
  }
  std::vector<double> sorted = coordinate, cuts;
  for (int r = 1; r < regions; ++r) {
    const std::size_t rank = n * static_cast<std::size_t>(r) / static_cast<std::size_t>(regions);
    const auto nth = sorted.begin() + static_cast<std::ptrdiff_t>(rank);
    std::nth_element(sorted.begin(), nth, sorted.end());
    cuts.push_back(*nth);
  }
  std::vector<int> label(n);
  for (std::size_t i = 0; i < n; ++i) {
    label[i] = static_cast<int>(std::upper_bound(cuts.begin(), cuts.end(), coordinate[i]) -
                                cuts.begin());
  }
  std::vector<char> locked(n, 0);
  for (auto e : mesh.edges()) {
    const int a = mesh.to_vertex_handle(mesh.halfedge_handle(e, 0)).idx();
    const int b = mesh.to_vertex_handle(mesh.halfedge_handle(e, 1)).idx();
    if (label[static_cast<std::size_t>(a)] != label[static_cast<std::size_t>(b)]) {
      locked[static_cast<std::size_t>(a)] = locked[static_cast<std::size_t>(b)] = 1;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (locked[i]) label[i] = -1;
  }
  return label;
}

}  // namespace

int quadric_decimate(Mesh& mesh, int target_faces, const QuadricDecimateOptions& options) {
  const int faces = static_cast<int>(mesh.n_faces());
  const int regions = options.regions > 0 ? options.regions
                      : faces >= kRegionsMinimumFaces ? 2
                                                        : 1;
  const int left = kRegionsLeaveFactor * target_faces;
  Decimator decimator(mesh);
  if (regions > 1 && left < faces) {
    const std::vector<int> label = slab_regions(mesh, regions);
    decimator.run_regions(label, regions, left, options.threads);
  }
  return decimator.run(target_faces);
}

}  // namespace ricci
