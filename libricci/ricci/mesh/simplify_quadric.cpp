#include "ricci/mesh/simplify_quadric.h"

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <queue>
#include <vector>

#include "ricci/util/parallel.h"

namespace ricci {
namespace {

// Boundary planes count this many face planes: a rim moves only along itself.
constexpr double kBoundaryWeight = 100.0;

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
    std::vector<Entry> entries;
    entries.reserve(4 * mesh_.n_edges());
    queue_ = std::priority_queue<Entry>(std::less<Entry>(), std::move(entries));
    for (auto e : mesh_.edges()) enqueue(e);
  }

  int run(int target_faces) {
    int faces = static_cast<int>(mesh_.n_faces());
    while (faces > target_faces && !queue_.empty()) {
      const Entry top = queue_.top();
      queue_.pop();
      const auto e = mesh_.edge_handle(top.edge);
      if (mesh_.status(e).deleted() || top.stamp != stamps_[top.edge]) continue;
      const Eigen::Vector3d x = placements_[top.edge].point;
      HalfedgeHandle h = mesh_.halfedge_handle(e, 0);
      if (!collapse_allowed(h, x)) {
        h = mesh_.halfedge_handle(e, 1);
        if (!collapse_allowed(h, x)) continue;  // until a neighbour's collapse re-queues it
      }
      const int removed = (mesh_.is_boundary(e) ? 1 : 2);
      const auto from = mesh_.from_vertex_handle(h), to = mesh_.to_vertex_handle(h);
      const Quadric q = quadrics_[from.idx()] + quadrics_[to.idx()];
      mesh_.collapse(h);
      mesh_.set_point(to, to_openmesh(x));
      quadrics_[to.idx()] = q;
      faces -= removed;
      for (auto around : mesh_.ve_range(to)) push(around);
    }
    mesh_.garbage_collection();
    return static_cast<int>(mesh_.n_faces());
  }

 private:
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

  // Queues edge e at its current placement's cost, a new stamp making older entries stale.
  void enqueue(EdgeHandle e) {
    queue_.push({placements_[e.idx()].cost, e.idx(), ++stamps_[e.idx()]});
  }

  void push(EdgeHandle e) {
    placements_[e.idx()] = placement(e);
    enqueue(e);
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
  std::priority_queue<Entry> queue_;
};

}  // namespace

int quadric_decimate(Mesh& mesh, int target_faces) {
  Decimator decimator(mesh);
  return decimator.run(target_faces);
}

}  // namespace ricci
