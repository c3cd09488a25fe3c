// Ear clipping, O(k^3) in the polygon size k; mesh polygons have a handful of corners.
#include "ricci/mesh/triangulate_polygon.h"
#include "ricci/util/cross2d.h"

#include <Eigen/Geometry>

namespace ricci {
namespace {

/// True when q lies inside or on triangle (a, b, c) given counter-clockwise.
bool inside(const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
            const Eigen::Vector2d& c) {
  return cross2d(b - a, q - a) >= 0 && cross2d(c - b, q - b) >= 0 && cross2d(a - c, q - c) >= 0;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon(
    const std::vector<Eigen::Vector3d>& corners,
    const std::function<bool(int, int)>& diagonal_allowed) {
  const int k = static_cast<int>(corners.size());
  std::vector<std::array<int, 3>> triangles;
  if (k < 3) return triangles;
  if (k == 3) return {{0, 1, 2}};
  // Newell's normal: the polygon's vector area, robust to non-planar and concave polygons.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int i = 0; i < k; ++i) normal += corners[i].cross(corners[(i + 1) % k]);
  Eigen::Vector3d u = normal.unitOrthogonal();
  if (normal.squaredNorm() == 0 || !normal.allFinite()) u = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d v = normal.normalized().cross(u);
  std::vector<Eigen::Vector2d> flat(k);
  for (int i = 0; i < k; ++i) flat[i] = {corners[i].dot(u), corners[i].dot(v)};  // CCW about normal

  std::vector<int> ring(k);
  for (int i = 0; i < k; ++i) ring[i] = i;
  while (ring.size() > 3) {
    const int m = static_cast<int>(ring.size());
    int best = -1, fallback = -1;
    double fallback_turn = -INFINITY;
    for (int i = 0; i < m && best < 0; ++i) {
      const int a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
      const double turn = cross2d(flat[b] - flat[a], flat[c] - flat[b]);
      if (turn > fallback_turn) {
        fallback_turn = turn;
        fallback = i;
      }
      if (turn <= 0) continue;  // reflex or flat corner: not an ear
      bool empty = true;
      for (int j = 0; j < m && empty; ++j) {
        const int q = ring[j];
        if (q != a && q != b && q != c && inside(flat[q], flat[a], flat[b], flat[c])) empty = false;
      }
      if (empty && (!diagonal_allowed || diagonal_allowed(a, c))) best = i;
    }
    const int i = best >= 0 ? best : fallback;
    triangles.push_back({ring[(i + m - 1) % m], ring[i], ring[(i + 1) % m]});
    ring.erase(ring.begin() + i);
  }
  triangles.push_back({ring[0], ring[1], ring[2]});
  return triangles;
}

}  // namespace ricci
