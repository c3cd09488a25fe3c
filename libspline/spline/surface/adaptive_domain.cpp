#include "spline/surface/adaptive_domain.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/ray_cast.h"
#include "ricci/mesh/simplify.h"
#include "ricci/metric/subdivide.h"

namespace spline {
namespace {

// Faces a split flag costs on average: three of its own and about one closing a neighbour.
constexpr int kFacesPerSplit = 4;
// A base mesh whose splits leave the total below this share of the target is rebuilt larger.
constexpr double kRebuildBelow = 0.9;

void check(const AdaptiveDomainOptions& o) {
  if (o.target_faces < 4 || !(o.base_share > 0.0 && o.base_share <= 1.0) ||
      !(o.max_turn_deg > 0.0) || !(o.min_thickness_edges >= 0.0) || o.max_levels < 0 ||
      o.relax_iterations < 0) {
    throw ricci::InvalidInputError(
        "adaptive domain: need target_faces >= 4, base_share in (0, 1], max_turn_deg > 0, "
        "min_thickness_edges >= 0, max_levels >= 0 and relax_iterations >= 0");
  }
}

Eigen::Vector3d unit_normal(const ricci::Mesh& mesh, ricci::FaceHandle f) {
  std::array<Eigen::Vector3d, 3> c;
  int k = 0;
  for (auto v : mesh.fv_range(f)) c[k++] = ricci::to_eigen(mesh.point(v));
  const Eigen::Vector3d n = (c[1] - c[0]).cross(c[2] - c[0]);
  const double length = n.norm();
  return length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

// Unit face normals by face index (zero for a degenerate face).
std::vector<Eigen::Vector3d> face_normals(const ricci::Mesh& mesh) {
  std::vector<Eigen::Vector3d> normals(mesh.n_faces());
  for (auto f : mesh.faces()) normals[static_cast<std::size_t>(f.idx())] = unit_normal(mesh, f);
  return normals;
}

// Squared distances of the scan's vertices to `mesh`, summed by closest face, over their mean.
std::vector<double> deviation_scores(const ricci::Mesh& mesh, const ricci::Mesh& dense) {
  const Eigen::MatrixX3d points = ricci::to_arrays(dense).V;
  std::vector<double> score(mesh.n_faces(), 0.0);
  double total = 0.0;
  for (const ricci::SurfacePoint& hit : ricci::closest_points(mesh, points)) {
    if (hit.face < 0) continue;
    const double d2 = hit.distance * hit.distance;
    score[static_cast<std::size_t>(hit.face)] += d2;
    total += d2;
  }
  const double mean = total / std::max<std::size_t>(1, score.size());
  if (mean > 0.0)
    for (double& s : score) s /= mean;
  return score;
}

// Fewest scan vertices for a quadric height field over a face's neighbourhood (6 unknowns).
constexpr int kMinQuadricPoints = 12;

// The sum of squared misses of the points `own` against the quadric height field
// h(x, y) = a + b x + c y + d x^2 + e x y + f y^2 fitted (least squares) to the points `near`, in
// the frame of a face: origin `centre`, unit normal n, x and y in units of `edge`.
double quadric_misses(const Eigen::MatrixX3d& points, const std::vector<Eigen::Index>& near,
                      const std::vector<Eigen::Index>& own, const Eigen::Vector3d& centre,
                      const Eigen::Vector3d& n, double edge) {
  const Eigen::Vector3d u = n.unitOrthogonal(), w = n.cross(u);
  const auto row = [&](Eigen::Index k, double& height) {
    const Eigen::Vector3d d = points.row(k).transpose() - centre;
    const double x = d.dot(u) / edge, y = d.dot(w) / edge;
    height = d.dot(n);
    Eigen::Matrix<double, 6, 1> r;
    r << 1.0, x, y, x * x, x * y, y * y;
    return r;
  };
  Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
  for (Eigen::Index k : near) {
    double height = 0.0;
    const Eigen::Matrix<double, 6, 1> r = row(k, height);
    normal += r * r.transpose();
    rhs += height * r;
  }
  const Eigen::Matrix<double, 6, 1> q = normal.ldlt().solve(rhs);
  double sum = 0.0;
  for (Eigen::Index k : own) {
    double height = 0.0;
    const double fitted = row(k, height).dot(q);
    const double miss = height - fitted;
    sum += std::isfinite(miss) ? miss * miss : 0.0;
  }
  return sum;
}

// Squared residuals of the scan's vertices against a quadric height field fitted to those whose
// closest face is f or a face sharing a vertex with it, in f's normal frame, summed by closest
// face, over their mean. A cubic spline follows a smooth bend across a few faces; what a
// quadric over the neighbourhood misses is detail the faces must resolve. Faces with too few
// points take their squared distances to the domain instead.
std::vector<double> quadric_residual_scores(const ricci::Mesh& mesh, const ricci::Mesh& dense) {
  const Eigen::MatrixX3d points = ricci::to_arrays(dense).V;
  const std::vector<ricci::SurfacePoint> hits = ricci::closest_points(mesh, points);
  std::vector<std::vector<Eigen::Index>> by_face(mesh.n_faces());
  for (std::size_t k = 0; k < hits.size(); ++k)
    if (hits[k].face >= 0)
      by_face[static_cast<std::size_t>(hits[k].face)].push_back(static_cast<Eigen::Index>(k));
  std::vector<double> score(mesh.n_faces(), 0.0);
  double total = 0.0;
  for (auto f : mesh.faces()) {
    const auto fi = static_cast<std::size_t>(f.idx());
    if (by_face[fi].empty()) continue;
    std::vector<int> ring;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double edge = 0.0;
    for (auto h : mesh.fh_range(f)) {
      const auto v = mesh.to_vertex_handle(h);
      centre += ricci::to_eigen(mesh.point(v)) / 3.0;
      edge += mesh.calc_edge_length(h) / 3.0;
      for (auto g : mesh.vf_range(v)) ring.push_back(g.idx());
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    std::vector<Eigen::Index> near;
    for (int g : ring)
      for (Eigen::Index k : by_face[static_cast<std::size_t>(g)]) near.push_back(k);
    const Eigen::Vector3d n = unit_normal(mesh, f);
    double sum = 0.0;
    if (static_cast<int>(near.size()) < kMinQuadricPoints || n.isZero() || !(edge > 0.0)) {
      for (Eigen::Index k : by_face[fi]) {
        const double d = hits[static_cast<std::size_t>(k)].distance;
        sum += d * d;
      }
    } else {
      sum = quadric_misses(points, near, by_face[fi], centre, n, edge);
    }
    score[fi] = sum;
    total += sum;
  }
  const double mean = total / static_cast<double>(std::max<std::size_t>(1, score.size()));
  if (mean > 0.0)
    for (double& s : score) s /= mean;
  return score;
}

// Sizing score of every face: above 1 where the face is too large for what the spline must
// resolve there (the larger of the split score, AdaptiveDomainOptions::split_by, and the
// thickness criterion).
std::vector<double> sizing_scores(const ricci::Mesh& mesh, const ricci::Mesh& dense,
                                  const AdaptiveDomainOptions& o) {
  using SplitBy = AdaptiveDomainOptions::SplitBy;
  const std::vector<double> deviation =
      o.split_by == SplitBy::deviation          ? deviation_scores(mesh, dense)
      : o.split_by == SplitBy::quadric_residual ? quadric_residual_scores(mesh, dense)
                                                : std::vector<double>();
  const std::vector<Eigen::Vector3d> normal = face_normals(mesh);
  const Eigen::VectorXd thickness =
      o.min_thickness_edges > 0.0 ? ricci::face_thickness(mesh) : Eigen::VectorXd();
  std::vector<double> score(mesh.n_faces(), 0.0);
  for (auto f : mesh.faces()) {
    const Eigen::Vector3d& n = normal[static_cast<std::size_t>(f.idx())];
    double turn = 0.0, edge = 0.0;
    int edges = 0;
    for (auto h : mesh.fh_range(f)) {
      edge += mesh.calc_edge_length(h);
      ++edges;
      const auto g = mesh.opposite_face_handle(h);
      if (!g.is_valid()) continue;
      const double c = std::clamp(n.dot(normal[static_cast<std::size_t>(g.idx())]), -1.0, 1.0);
      turn = std::max(turn, std::acos(c) * 180.0 / M_PI);
    }
    double s =
        deviation.empty() ? turn / o.max_turn_deg : deviation[static_cast<std::size_t>(f.idx())];
    if (thickness.size() > 0 && edges > 0) {
      const double t = thickness[f.idx()];
      if (t > 0.0 && std::isfinite(t)) s = std::max(s, o.min_thickness_edges * edge / edges / t);
    }
    score[static_cast<std::size_t>(f.idx())] = s;
  }
  return score;
}

// One level: the faces scoring above 1, highest first, as many as the face budget allows.
// Returns the number flagged.
int flag_faces(const std::vector<double>& score, int budget, std::vector<char>& refine) {
  std::vector<int> order;
  for (std::size_t f = 0; f < score.size(); ++f)
    if (score[f] > 1.0) order.push_back(static_cast<int>(f));
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return score[static_cast<std::size_t>(a)] > score[static_cast<std::size_t>(b)];
  });
  const int allowed = std::max(0, budget / kFacesPerSplit);
  const int flagged = std::min(allowed, static_cast<int>(order.size()));
  refine.assign(score.size(), 0);
  for (int k = 0; k < flagged; ++k) refine[static_cast<std::size_t>(order[k])] = 1;
  return flagged;
}

double mean_edge_length(const ricci::Mesh& mesh) {
  double sum = 0.0;
  for (auto e : mesh.edges()) sum += mesh.calc_edge_length(e);
  return mesh.n_edges() > 0 ? sum / static_cast<double>(mesh.n_edges()) : 0.0;
}

// Vertex moves that turn a face from `before` (its unit normals) to a cosine below `min_cos`, or
// flatten it to a segment, are undone: the corners of such faces go back to `old`; with
// `repeat`, until no face turns (at worst every move is undone).
void undo_turning_moves(ricci::Mesh& mesh, const std::vector<Eigen::Vector3d>& before,
                        const std::vector<ricci::Mesh::Point>& old, double min_cos, bool repeat) {
  for (bool undone = true; undone;) {
    undone = false;
    for (auto f : mesh.faces()) {
      if (unit_normal(mesh, f).dot(before[static_cast<std::size_t>(f.idx())]) >= min_cos) continue;
      for (auto v : mesh.fv_range(f)) {
        const auto& p = old[static_cast<std::size_t>(v.idx())];
        if (mesh.point(v) == p) continue;
        mesh.set_point(v, p);
        undone = repeat;
      }
    }
  }
}

// Tangential relaxation after the splits: each interior vertex moved half-way to its
// neighbours' mean within its tangent plane, then onto the scan (oriented closest point); a
// vertex whose move turns a face by more than 60 degrees stays. Evens out the red-green
// closures' obtuse halves and the 4:1 size steps while the grading stays.
void relax(ricci::Mesh& mesh, const ricci::Mesh& dense, int iterations,
           const std::vector<char>& pinned) {
  const double search = 2.0 * mean_edge_length(mesh);
  for (int it = 0; it < iterations; ++it) {
    mesh.request_vertex_normals();
    mesh.request_face_normals();
    mesh.update_normals();
    const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
    Eigen::MatrixX3d moved(n, 3), normals(n, 3);
    for (auto v : mesh.vertices()) {
      const Eigen::Vector3d p = ricci::to_eigen(mesh.point(v));
      const Eigen::Vector3d nv = ricci::to_eigen(mesh.normal(v));
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      int count = 0;
      for (auto w : mesh.vv_range(v)) {
        mean += ricci::to_eigen(mesh.point(w));
        ++count;
      }
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      if (!mesh.is_boundary(v) && !pinned[static_cast<std::size_t>(v.idx())] && count > 0) {
        d = 0.5 * (mean / count - p);
        d -= d.dot(nv) * nv;
      }
      moved.row(v.idx()) = (p + d).transpose();
      normals.row(v.idx()) = nv.transpose();
    }
    const auto hits = ricci::closest_points(dense, moved, normals, search);
    const std::vector<Eigen::Vector3d> before = face_normals(mesh);
    const std::vector<ricci::Mesh::Point> old(mesh.points(), mesh.points() + mesh.n_vertices());
    for (auto v : mesh.vertices()) {
      if (mesh.is_boundary(v) || pinned[static_cast<std::size_t>(v.idx())]) continue;
      const Eigen::Vector3d& q = hits[static_cast<std::size_t>(v.idx())].point;
      mesh.set_point(v, ricci::Mesh::Point(q.x(), q.y(), q.z()));
    }
    undo_turning_moves(mesh, before, old, 0.5, false);  // 60 degrees
    mesh.release_vertex_normals();
    mesh.release_face_normals();
  }
}

// A new vertex's move onto the scan is undone only where it turns a face over (90 degrees or
// more) or flattens it: smaller turns are what the splits are for on curved parts.
constexpr double kMinSplitMoveCos = 1e-3;

// For each face flagged in `refine`, the scan vertex farthest from it among those whose closest
// face of `domain` it is (face -1 where none is).
struct FarthestPoint {
  int vertex = -1;           // index into the scan's vertices
  double distance = -1.0;    // to the face
  Eigen::Vector3d foot;      // its closest point on the face
};

std::vector<FarthestPoint> farthest_scan_vertices(const ricci::Mesh& domain,
                                                  const Eigen::MatrixX3d& points,
                                                  const std::vector<char>& refine) {
  std::vector<FarthestPoint> out(domain.n_faces());
  const std::vector<ricci::SurfacePoint> hits = ricci::closest_points(domain, points);
  for (std::size_t k = 0; k < hits.size(); ++k) {
    const int f = hits[k].face;
    if (f < 0 || !refine[static_cast<std::size_t>(f)]) continue;
    FarthestPoint& far = out[static_cast<std::size_t>(f)];
    if (hits[k].distance <= far.distance) continue;
    far = {static_cast<int>(k), hits[k].distance, hits[k].point};
  }
  return out;
}

// The midpoint vertex of `refined` (index >= first_new) on the edge between old vertices a and
// b: the new vertex adjacent to both (invalid when the edge was not split).
ricci::VertexHandle edge_midpoint(const ricci::Mesh& refined, ricci::VertexHandle a,
                                  ricci::VertexHandle b, int first_new) {
  for (auto w : refined.vv_range(a)) {
    if (w.idx() < first_new) continue;
    for (auto x : refined.vv_range(w))
      if (x == b) return w;
  }
  return ricci::VertexHandle();
}

// The interior vertex of `refined` among flagged face f's corners and edge midpoints nearest
// to `foot` (invalid when all are on the boundary).
ricci::VertexHandle nearest_split_vertex(const ricci::Mesh& domain, const ricci::Mesh& refined,
                                         ricci::FaceHandle f, const Eigen::Vector3d& foot,
                                         int first_new) {
  ricci::VertexHandle best;
  double best_d = 0.0;
  const auto consider = [&](ricci::VertexHandle v) {
    if (!v.is_valid() || refined.is_boundary(v)) return;
    const double d = (ricci::to_eigen(refined.point(v)) - foot).norm();
    if (!best.is_valid() || d < best_d) best = v, best_d = d;
  };
  for (auto h : domain.fh_range(f)) {
    const auto a = domain.from_vertex_handle(h), b = domain.to_vertex_handle(h);
    consider(refined.vertex_handle(a.idx()));
    consider(edge_midpoint(refined, a, b, first_new));
  }
  return best;
}

// `targets` (by vertex of `refined`) with, for each flagged face of `domain`, the vertex among
// its corners and midpoints nearest to the foot of its farthest scan vertex set to that scan
// vertex (and flagged in `placed`); where two faces pick one vertex, the farther scan vertex
// wins.
void place_at_farthest(const ricci::Mesh& domain, const ricci::Mesh& refined,
                       const Eigen::MatrixX3d& points, const std::vector<char>& refine,
                       int first_new, std::vector<Eigen::Vector3d>& targets,
                       std::vector<char>& placed) {
  const std::vector<FarthestPoint> farthest = farthest_scan_vertices(domain, points, refine);
  std::vector<double> claimed(targets.size(), -1.0);
  for (auto f : domain.faces()) {
    const FarthestPoint& far = farthest[static_cast<std::size_t>(f.idx())];
    if (far.vertex < 0) continue;
    const auto v = nearest_split_vertex(domain, refined, f, far.foot, first_new);
    if (!v.is_valid()) continue;
    const auto i = static_cast<std::size_t>(v.idx());
    if (far.distance <= claimed[i]) continue;
    claimed[i] = far.distance;
    targets[i] = points.row(far.vertex).transpose();
    placed[i] = 1;
  }
}

// The reference normals the split moves are checked against: for each face of `mesh`, the
// normal of the scan's face closest to its centroid where the face agrees with it (within 90
// degrees), else the face's own. A farthest-point move may swing a face across a part thinner
// than the face; checked against its own normal alone, it could end facing against the scan.
std::vector<Eigen::Vector3d> scan_facing_normals(const ricci::Mesh& mesh,
                                                 const ricci::Mesh& dense) {
  std::vector<Eigen::Vector3d> normals = face_normals(mesh);
  Eigen::MatrixX3d centroids(static_cast<Eigen::Index>(mesh.n_faces()), 3);
  for (auto f : mesh.faces())
    centroids.row(f.idx()) = ricci::to_eigen(mesh.calc_face_centroid(f)).transpose();
  const std::vector<ricci::SurfacePoint> hits = ricci::closest_points(dense, centroids);
  for (std::size_t f = 0; f < normals.size(); ++f) {
    if (hits[f].face < 0) continue;
    const Eigen::Vector3d n = unit_normal(dense, dense.face_handle(hits[f].face));
    if (n.dot(normals[f]) > 0.0) normals[f] = n;
  }
  return normals;
}

// The interior vertices of `mesh` moved to `targets` (by vertex); the moves that turn a face
// from `reference` (unit normals by face) by 90 degrees or more, or flatten it, are undone.
// Next to a boundary the closest scan point of a midpoint over a notch of the scan's boundary
// lies on that boundary, in line with the domain's boundary edge: such a face would be flat.
void move_to(ricci::Mesh& mesh, const std::vector<Eigen::Vector3d>& targets,
             const std::vector<Eigen::Vector3d>& reference) {
  const std::vector<ricci::Mesh::Point> old(mesh.points(), mesh.points() + mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    if (mesh.is_boundary(v)) continue;  // the boundary stays on the followed curve
    const Eigen::Vector3d& p = targets[static_cast<std::size_t>(v.idx())];
    mesh.set_point(v, ricci::Mesh::Point(p.x(), p.y(), p.z()));
  }
  undo_turning_moves(mesh, reference, old, kMinSplitMoveCos, true);
}

// split_domain_faces; with `pinned`, also flags (by vertex of the result, appended to) the
// vertices that went onto a farthest scan vertex and stayed there.
ricci::Mesh split_faces(const ricci::Mesh& domain, const ricci::Mesh& dense,
                        const std::vector<char>& refine, SplitPlacement placement,
                        std::vector<char>* pinned) {
  ricci::Mesh refined = ricci::subdivide_midpoint_locally(domain, refine);
  const auto first_new = static_cast<Eigen::Index>(domain.n_vertices());
  const auto added = static_cast<Eigen::Index>(refined.n_vertices()) - first_new;
  if (added <= 0) {
    if (pinned != nullptr) pinned->resize(refined.n_vertices(), 0);
    return refined;
  }
  refined.request_vertex_normals();
  refined.request_face_normals();
  refined.update_normals();
  Eigen::MatrixX3d moved(added, 3), normals(added, 3);
  for (Eigen::Index i = 0; i < added; ++i) {
    const auto v = refined.vertex_handle(static_cast<int>(first_new + i));
    moved.row(i) = ricci::to_eigen(refined.point(v)).transpose();
    normals.row(i) = ricci::to_eigen(refined.normal(v)).transpose();
  }
  const auto hits = ricci::closest_points(dense, moved, normals, 2.0 * mean_edge_length(refined));
  // Targets by vertex: the old vertices stay, the new ones go to their closest scan points;
  // with farthest_point, the vertices nearest to the flagged faces' farthest scan vertices go
  // there instead, checked against the scan's normals.
  std::vector<Eigen::Vector3d> closest;
  for (auto v : refined.vertices()) closest.push_back(ricci::to_eigen(refined.point(v)));
  for (Eigen::Index i = 0; i < added; ++i)
    closest[static_cast<std::size_t>(first_new + i)] = hits[static_cast<std::size_t>(i)].point;
  std::vector<Eigen::Vector3d> farthest = closest;
  std::vector<char> at_farthest(closest.size(), 0);
  if (placement == SplitPlacement::closest_point) {
    move_to(refined, closest, face_normals(refined));
  } else {
    place_at_farthest(domain, refined, ricci::to_arrays(dense).V, refine,
                      static_cast<int>(first_new), farthest, at_farthest);
    const std::vector<Eigen::Vector3d> reference = scan_facing_normals(refined, dense);
    const std::vector<ricci::Mesh::Point> before(refined.points(),
                                                 refined.points() + refined.n_vertices());
    move_to(refined, farthest, reference);
    // The new vertices an undone move left on their edge: their closest scan point instead.
    std::vector<Eigen::Vector3d> retry;
    for (auto v : refined.vertices()) {
      const auto i = static_cast<std::size_t>(v.idx());
      const bool left = v.idx() >= first_new && refined.point(v) == before[i];
      retry.push_back(left ? closest[i] : ricci::to_eigen(refined.point(v)));
    }
    move_to(refined, retry, reference);
  }
  refined.release_vertex_normals();
  refined.release_face_normals();
  if (pinned != nullptr) {
    pinned->resize(refined.n_vertices(), 0);
    for (auto v : refined.vertices()) {
      const auto i = static_cast<std::size_t>(v.idx());
      if (at_farthest[i] && ricci::to_eigen(refined.point(v)) == farthest[i]) (*pinned)[i] = 1;
    }
  }
  return refined;
}

ricci::Mesh uniform_base(const ricci::Mesh& dense, int faces) {
  ricci::SimplifyOptions simplify;
  simplify.target_faces = std::max(4, faces);
  return ricci::simplify_mesh(dense, simplify).mesh;
}

// `base` split level by level up to `target` faces.
AdaptiveDomain split_to(const ricci::Mesh& dense, ricci::Mesh base, int target,
                        const AdaptiveDomainOptions& o) {
  AdaptiveDomain out;
  out.mesh = std::move(base);
  out.base_faces = static_cast<int>(out.mesh.n_faces());
  std::vector<char> pinned;  // vertices on a farthest scan vertex: the relaxation keeps them
  for (int level = 0; level < o.max_levels; ++level) {
    const int budget = target - static_cast<int>(out.mesh.n_faces());
    std::vector<char> refine;
    const int flagged = flag_faces(sizing_scores(out.mesh, dense, o), budget, refine);
    out.split_faces.push_back(flagged);
    if (flagged == 0) break;
    out.mesh = split_faces(out.mesh, dense, refine, o.placement, &pinned);
  }
  pinned.resize(out.mesh.n_vertices(), 0);
  relax(out.mesh, dense, o.relax_iterations, pinned);
  return out;
}

}  // namespace

AdaptiveDomain adaptive_domain(const ricci::Mesh& dense, const AdaptiveDomainOptions& options) {
  check(options);
  // The remeshing lands above its target where parts are thin (camel: 1.4 times, less for a
  // coarser base): the total is aimed at what the uniform domain of target_faces has.
  const int target = static_cast<int>(uniform_base(dense, options.target_faces).n_faces());
  const int base = static_cast<int>(std::lround(options.base_share * options.target_faces));
  ricci::Mesh base_mesh = uniform_base(dense, base);
  const double ratio = static_cast<double>(base_mesh.n_faces()) / std::max(base, 4);
  AdaptiveDomain out = split_to(dense, std::move(base_mesh), target, options);
  const int faces = static_cast<int>(out.mesh.n_faces());
  if (faces < kRebuildBelow * target && base < options.target_faces) {
    // Few faces needed splitting: a larger base takes the rest of the budget.
    const int added = faces - out.base_faces;
    const int larger = static_cast<int>(std::lround((target - added) / ratio));
    out = split_to(dense, uniform_base(dense, std::min(options.target_faces, larger)), target,
                   options);
  }
  return out;
}

ricci::Mesh split_domain_faces(const ricci::Mesh& domain, const ricci::Mesh& dense,
                               const std::vector<char>& refine, SplitPlacement placement) {
  return split_faces(domain, dense, refine, placement, nullptr);
}

}  // namespace spline
