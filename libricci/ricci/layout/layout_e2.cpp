#include "ricci/layout/layout_e2.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <utility>
#include <string>
#include <vector>

#include "ricci/mesh/errors.h"
#include "ricci/util/cross2d.h"

namespace ricci {
namespace {

constexpr long double kPiL = 3.141592653589793238462643383279502884L;

// Angle opposite `opposite` in the triangle (opposite, b, c), half-angle formula in long double
// (as corner_angle_from_lengths); clamped to [0, pi] when the triangle inequality fails.
long double corner_angle_l(long double opposite, long double b, long double c) {
  const long double s_a = 0.5L * (b + c - opposite), s_b = 0.5L * (opposite + c - b),
                    s_c = 0.5L * (opposite + b - c), s = 0.5L * (opposite + b + c);
  return 2.0L * std::atan2(std::sqrt(std::max(0.0L, s_b * s_c)), std::sqrt(std::max(0.0L, s * s_a)));
}

double length_of(const Mesh& mesh, const Eigen::VectorXd& lengths, HalfedgeHandle h) {
  return lengths[mesh.edge_handle(h).idx()];
}

void check_lengths(const Mesh& mesh, const Eigen::VectorXd& lengths) {
  if (lengths.size() != static_cast<Eigen::Index>(mesh.n_edges())) {
    throw InvalidInputError("layout: " + std::to_string(lengths.size()) + " lengths for " +
                            std::to_string(mesh.n_edges()) + " edges");
  }
  for (auto f : mesh.faces()) {
    double l[3];
    int k = 0;
    for (auto h : mesh.fh_range(f)) l[k++] = length_of(mesh, lengths, h);
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(l[i]) || l[i] <= 0.0 || l[i] > l[(i + 1) % 3] + l[(i + 2) % 3]) {
        throw InvalidInputError("layout: face " + std::to_string(f.idx()) +
                                " violates the triangle inequality or has a bad length");
      }
    }
  }
}


// Longest edge of each face.
std::vector<double> face_sizes(const Mesh& mesh, const Eigen::VectorXd& lengths) {
  std::vector<double> size(mesh.n_faces(), 0.0);
  for (auto f : mesh.faces()) {
    for (auto h : mesh.fh_range(f)) size[f.idx()] = std::max(size[f.idx()], length_of(mesh, lengths, h));
  }
  return size;
}

// Growth scale of a face: 0 for faces at least half the median size (breadth-first among
// them: a short, balanced growth tree keeps the closure error of ordinary faces lowest), else
// floor(log16(size / median)) < 0, so smaller faces, down to the tiny ones at a large cone,
// grow first, outwards from the smallest, scale by scale. (Measured: a 1/256 threshold leaves
// 9e-9 relative errors on genus3_100k's mid-size faces at the cone; ordering every scale costs
// rocker-arm's varied faces 4e-9; this split gives ~1e-10 on both.)
int size_bucket(double size, double median) {
  if (size >= 0.5 * median) return 0;
  const int octave = std::ilogb(size / median);
  return -((3 - octave) / 4);  // floor(octave / 4), octave < 0
}

double median_size(std::vector<double> size) {
  std::nth_element(size.begin(), size.begin() + static_cast<long>(size.size() / 2), size.end());
  return size[size.size() / 2];
}

// The seed: the smallest face when sizes span more than 2^8 (tiny faces at a large cone, where
// the growth must start), else the central face.
int default_seed(const Mesh& mesh, const std::vector<double>& size) {
  const auto [lo, hi] = std::minmax_element(size.begin(), size.end());
  if (*hi > 256.0 * *lo) return static_cast<int>(lo - size.begin());
  return central_face_of(mesh);
}

// Double-double coordinates (Dekker/Knuth error-free sums): a position is hi + lo with |lo| at
// most half an ulp of hi. Only sums and differences need the extra word: a new vertex is its
// neighbour plus an offset the size of an edge, computed in double from the (exact to 1e-16
// relative) edge vector, so placement keeps ~32 digits relative to the chart and ~16 relative
// to each edge, however tiny.
struct TwoSum {
  double sum, error;
};

TwoSum two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}

// (hi_b + lo_b) - (hi_a + lo_a) rounded to double.
double dd_difference(double hi_b, double lo_b, double hi_a, double lo_a) {
  const TwoSum d = two_sum(hi_b, -hi_a);
  return d.sum + (d.error + (lo_b - lo_a));
}

// (hi + lo) + x, renormalised.
void dd_add(double& hi, double& lo, double x) {
  const TwoSum s = two_sum(hi, x);
  const TwoSum r = two_sum(s.sum, s.error + lo);
  hi = r.sum;
  lo = r.error;
}

// Offset of the third vertex from a given the vector ab (counter-clockwise), as
// place_third_vertex but relative to a.
Eigen::Vector2d third_vertex_offset(const Eigen::Vector2d& ab, double l_ac, double l_bc) {
  const double d = ab.norm();
  const Eigen::Vector2d e = ab / d;
  const Eigen::Vector2d n(-e.y(), e.x());
  // Foot of the altitude from the two circle equations; height from the stable area. Across
  // a short edge of a sliver l_ac ~ l_bc >> d: l_ac^2 - l_bc^2 as a product keeps the digits
  // (l_ac - l_bc is exact there) that the difference of squares would lose, times l/d.
  const double x = (d * d + (l_ac - l_bc) * (l_ac + l_bc)) / (2.0 * d);
  const double y = 2.0 * triangle_area_from_lengths(d, l_ac, l_bc) / d;
  return x * e + y * n;
}

}  // namespace

int central_face_of(const Mesh& mesh) {
  std::vector<int> depth(mesh.n_faces(), -1);
  std::deque<FaceHandle> queue;
  for (auto f : mesh.faces()) {
    for (auto h : mesh.fh_range(f)) {
      if (mesh.is_boundary(mesh.opposite_halfedge_handle(h)) && depth[f.idx()] < 0) {
        depth[f.idx()] = 0;
        queue.push_back(f);
      }
    }
  }
  if (queue.empty()) return 0;
  FaceHandle last = queue.front();
  while (!queue.empty()) {
    last = queue.front();
    queue.pop_front();
    for (auto g : mesh.ff_range(last)) {
      if (depth[g.idx()] < 0) {
        depth[g.idx()] = depth[last.idx()] + 1;
        queue.push_back(g);
      }
    }
  }
  return last.idx();
}

double corner_angle_from_lengths(double opposite, double b, double c) {
  // Half-angle form tan(theta/2) = sqrt((s-b)(s-c) / (s(s-a))): accurate for needles, where
  // acos of the cosine law or the circle intersection's sqrt(l^2 - x^2) lose half the digits.
  const double s_a = 0.5 * (b + c - opposite), s_b = 0.5 * (opposite + c - b),
               s_c = 0.5 * (opposite + b - c), s = 0.5 * (opposite + b + c);
  return 2.0 * std::atan2(std::sqrt(std::max(0.0, s_b * s_c)), std::sqrt(std::max(0.0, s * s_a)));
}

double triangle_area_from_lengths(double a, double b, double c) {
  // Kahan's ordering of Heron's formula: accurate to a few ulps even for needles, where
  // sqrt(l^2 - x^2) in a naive circle intersection loses half the digits.
  if (a < b) std::swap(a, b);
  if (b < c) std::swap(b, c);
  if (a < b) std::swap(a, b);
  const double p = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
  return 0.25 * std::sqrt(std::max(0.0, p));
}

Eigen::Vector2d place_third_vertex(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double l_ac,
                                   double l_bc) {
  return a + third_vertex_offset(b - a, l_ac, l_bc);
}

Eigen::Vector2d LayoutE2Result::edge_vector(int from, int to) const {
  if (positions_low.rows() != positions.rows()) return (positions.row(to) - positions.row(from)).transpose();
  return {dd_difference(positions(to, 0), positions_low(to, 0), positions(from, 0), positions_low(from, 0)),
          dd_difference(positions(to, 1), positions_low(to, 1), positions(from, 1), positions_low(from, 1))};
}

void measure_layout(const Mesh& mesh, const Eigen::VectorXd& lengths, LayoutE2Result& result) {
  result.min_signed_area = std::numeric_limits<double>::infinity();
  result.flipped_faces = 0;
  std::vector<double> angle(mesh.n_vertices(), 0.0);
  for (auto f : mesh.faces()) {
    const auto h0 = mesh.halfedge_handle(f);
    const auto h1 = mesh.next_halfedge_handle(h0);
    const int corner[3] = {mesh.from_vertex_handle(h0).idx(), mesh.to_vertex_handle(h0).idx(),
                           mesh.to_vertex_handle(h1).idx()};
    // Edge vectors from each corner: the orientation test of a face 1e-17 of the chart wide is
    // only meaningful on the double-double differences.
    const Eigen::Vector2d ab = result.edge_vector(corner[0], corner[1]),
                          ac = result.edge_vector(corner[0], corner[2]),
                          bc = result.edge_vector(corner[1], corner[2]);
    const double area = 0.5 * cross2d(ab, ac);
    result.min_signed_area = std::min(result.min_signed_area, area);
    if (!(area > 0.0)) ++result.flipped_faces;
    const Eigen::Vector2d u[3] = {ab, bc, -ac}, v[3] = {ac, -ab, -bc};
    for (int m = 0; m < 3; ++m) angle[corner[m]] += std::atan2(cross2d(u[m], v[m]), u[m].dot(v[m]));
  }
  result.max_relative_length_error = 0.0;
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const double d =
        result.edge_vector(mesh.from_vertex_handle(h).idx(), mesh.to_vertex_handle(h).idx()).norm();
    const double l = lengths[e.idx()];
    result.max_relative_length_error =
        std::max(result.max_relative_length_error, std::abs(d - l) / l);
  }
  result.max_vertex_angle = angle.empty() ? 0.0 : *std::max_element(angle.begin(), angle.end());
}

namespace {

// Faces waiting to be developed, as (face, halfedge it is entered by), popped in the order of
// (scale bucket, magnification bucket, arrival).
class FaceQueue {
 public:
  void push(int bucket, int magnification, int face, int entry) {
    queues_[{bucket, magnification}].emplace_back(face, entry);
    ++size_;
  }
  [[nodiscard]] bool empty() const { return size_ == 0; }
  // \pre !empty().
  std::pair<int, int> pop() {
    auto it = queues_.begin();
    while (it->second.empty()) it = queues_.erase(it);
    const std::pair<int, int> front = it->second.front();
    it->second.pop_front();
    --size_;
    return front;
  }

 private:
  std::map<std::pair<int, int>, std::deque<std::pair<int, int>>> queues_;
  size_t size_ = 0;
};

// Above this relative edge error the growth is run again with needles last (grow_layout).
constexpr double kNeedleRetryError = 1e-8;

// Places every vertex of `mesh` from result.seed_face outwards into result.positions(_low).
// Faces come off a queue by (scale bucket, magnification bucket, arrival order): breadth-first
// among faces of one scale, except that faces below half the median size come first, smallest
// scale first (layout_e2's comment). Without `needles_last` a face's free vertex is placed as
// soon as the face is reached and the magnification bucket is 0. With it, a face's free vertex is
// placed when the face comes off the queue, from the edge it was entered by, and the entries whose
// base edge d is much shorter than the sides l placing the vertex (l/d >= 2, a needle entered by
// its short edge) wait: such a placement multiplies the rounding of the corner angle at the short
// edge by l/d (when directions were taken from positions, it multiplied the base's whole error
// and compounded along runs of needles: the inversive-distance metric of marching-cubes
// genus2_100k missed by 0.46 of an edge, 2.2e-8 with needles last). A face is entered again by
// each placed edge; the first entry off the queue wins. Each face's halfedges get their
// directions when its free vertex is placed (develop_directions). Returns the number of faces
// reached.
size_t grow_layout(const Mesh& mesh, const LongLengths& lengths, const std::vector<double>& size,
                   bool needles_last, LayoutE2Result& result) {
  const int n = static_cast<int>(mesh.n_vertices());
  Eigen::MatrixX2d& hi = result.positions;
  Eigen::MatrixX2d& lo = result.positions_low;
  hi = Eigen::MatrixX2d::Zero(n, 2);
  lo = Eigen::MatrixX2d::Zero(n, 2);
  std::vector<char> placed(mesh.n_vertices(), 0);
  // By halfedge: its direction in the chart, set when its face is developed.
  std::vector<long double> direction(mesh.n_halfedges(), 0.0L);
  auto place = [&](int w, int from, long double l, long double angle) {
    const long double offset[2] = {l * std::cos(angle), l * std::sin(angle)};
    for (int k = 0; k < 2; ++k) {
      hi(w, k) = hi(from, k);
      lo(w, k) = lo(from, k);
      const double head = static_cast<double>(offset[k]);
      dd_add(hi(w, k), lo(w, k), head);
      dd_add(hi(w, k), lo(w, k), static_cast<double>(offset[k] - head));
    }
    placed[w] = 1;
  };
  auto length = [&](HalfedgeHandle h) { return lengths[mesh.edge_handle(h).idx()]; };
  // Develops face(o) from the placed edge o (its direction: the opposite's, turned by pi): sets
  // its halfedges' directions and places its free vertex.
  auto place_across = [&](HalfedgeHandle o) {
    const auto next = mesh.next_halfedge_handle(o), prev = mesh.prev_halfedge_handle(o);
    const long double a_to_b =
        std::remainder(direction[mesh.opposite_halfedge_handle(o).idx()] + kPiL, 2.0L * kPiL);
    const DevelopedDirections d = develop_directions(a_to_b, length(o), length(prev), length(next));
    direction[o.idx()] = a_to_b;
    direction[next.idx()] = d.b_to_w;
    direction[prev.idx()] = std::remainder(d.a_to_w + kPiL, 2.0L * kPiL);
    const int w = mesh.to_vertex_handle(next).idx();
    if (!placed[w]) place(w, mesh.from_vertex_handle(o).idx(), length(prev), d.a_to_w);
  };

  const FaceHandle seed(result.seed_face);
  const auto h0 = mesh.halfedge_handle(seed);
  const int a = mesh.from_vertex_handle(h0).idx(), b = mesh.to_vertex_handle(h0).idx();
  placed[a] = 1;
  place(b, a, length(h0), 0.0L);
  direction[mesh.opposite_halfedge_handle(h0).idx()] = kPiL;  // h0 along +x
  place_across(h0);

  // Entries in (scale bucket, magnification bucket, arrival) order: a first-in first-out queue
  // per bucket pair (a handful of them), the lowest non-empty one first; the same order as a
  // priority queue on the triple, without its O(log n) per face.
  FaceQueue queue;
  const double median = median_size(size);
  std::vector<char> entered(mesh.n_faces(), 0), done(mesh.n_faces(), 0);
  auto enter = [&](HalfedgeHandle o) {  // o: the halfedge of face(o) along an edge already placed
    const FaceHandle g = mesh.face_handle(o);
    if (!g.is_valid() || done[g.idx()] || (!needles_last && entered[g.idx()])) return;
    entered[g.idx()] = 1;
    int magnification = 0;
    if (needles_last) {
      const long double side = std::max(length(mesh.prev_halfedge_handle(o)), length(mesh.next_halfedge_handle(o)));
      magnification = std::max(0, std::ilogb(static_cast<double>(side / length(o))));
    } else {
      place_across(o);
    }
    queue.push(size_bucket(size[g.idx()], median), magnification, g.idx(), o.idx());
  };
  enter(h0);
  size_t reached = 0;
  while (!queue.empty()) {
    const auto [face, entry] = queue.pop();
    if (done[face]) continue;
    done[face] = 1;
    ++reached;
    if (needles_last) place_across(HalfedgeHandle(entry));  // else developed when entered
    for (auto h : mesh.fh_range(FaceHandle(face))) enter(mesh.opposite_halfedge_handle(h));
  }
  result.halfedge_directions.resize(static_cast<Eigen::Index>(direction.size()));
  for (size_t h = 0; h < direction.size(); ++h) {
    result.halfedge_directions[static_cast<Eigen::Index>(h)] = static_cast<double>(direction[h]);
  }
  return reached;
}

}  // namespace

LongLengths long_lengths(const Eigen::VectorXd& lengths, const Eigen::VectorXd& low) {
  if (low.size() == 0) return lengths.cast<long double>();
  if (low.size() != lengths.size()) {
    throw InvalidInputError("layout: " + std::to_string(low.size()) + " low parts for " +
                            std::to_string(lengths.size()) + " lengths");
  }
  return lengths.cast<long double>() + low.cast<long double>();
}

DevelopedDirections develop_directions(long double a_to_b, long double l_ab, long double l_aw,
                                       long double l_bw) {
  return {a_to_b + corner_angle_l(l_bw, l_ab, l_aw), a_to_b + kPiL - corner_angle_l(l_aw, l_ab, l_bw)};
}

LayoutE2Result layout_e2(const Mesh& mesh, const Eigen::VectorXd& lengths,
                         const LayoutE2Options& options) {
  return layout_e2(mesh, lengths, Eigen::VectorXd(), options);
}

LayoutE2Result layout_e2(const Mesh& mesh, const Eigen::VectorXd& lengths,
                         const Eigen::VectorXd& lengths_low, const LayoutE2Options& options) {
  if (mesh.n_faces() == 0) throw InvalidInputError("layout: mesh has no faces");
  check_lengths(mesh, lengths);
  const LongLengths metric = long_lengths(lengths, lengths_low);
  LayoutE2Result result;
  const std::vector<double> size = face_sizes(mesh, lengths);
  result.seed_face = options.seed_face >= 0 ? options.seed_face : default_seed(mesh, size);
  if (result.seed_face >= static_cast<int>(mesh.n_faces())) {
    throw InvalidInputError("layout: seed face " + std::to_string(result.seed_face) +
                            " is out of range");
  }
  const size_t reached = grow_layout(mesh, metric, size, false, result);
  if (reached != mesh.n_faces()) {
    throw TopologyError("layout: " + std::to_string(mesh.n_faces() - reached) +
                        " faces cannot be reached from seed face " +
                        std::to_string(result.seed_face) + " (mesh not connected)");
  }
  measure_layout(mesh, lengths, result);
  if (result.max_relative_length_error > kNeedleRetryError) {
    LayoutE2Result retry = result;
    grow_layout(mesh, metric, size, true, retry);
    measure_layout(mesh, lengths, retry);
    if (retry.max_relative_length_error < result.max_relative_length_error) result = std::move(retry);
  }
  return result;
}

}  // namespace ricci
