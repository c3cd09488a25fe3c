#include "spline/knots/knot_cloud.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ricci/mesh/errors.h"
#include "spline/basis/multi_index.h"

namespace spline {
namespace {

constexpr double kPi = 3.14159265358979323846;

// splitmix64: a portable, fully specified generator (std distributions are not).
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  std::uint64_t state_;
};

void check_options(int degree, const KnotCloudOptions& options) {
  if (degree < 1 || degree > kMaxDmsDegree) {
    throw ricci::InvalidInputError("knot cloud: degree " + std::to_string(degree) +
                                   " outside 1.." + std::to_string(kMaxDmsDegree));
  }
  if (!(options.radius_fraction > 0.0 && options.radius_fraction < 0.5) ||
      !(options.radius_jitter >= 0.0 && options.radius_jitter < 1.0) ||
      !(options.angle_jitter >= 0.0 && options.angle_jitter <= 0.4)) {
    throw ricci::InvalidInputError(
        "knot cloud: options out of range (radius_fraction in (0,0.5), radius_jitter in [0,1), "
        "angle_jitter in [0,0.4])");
  }
}

}  // namespace

KnotCloud make_knot_cloud(int degree, std::uint64_t vertex_id, const Eigen::Vector2d& center,
                          const std::vector<Eigen::Vector2d>& ring, bool ring_closed,
                          const KnotCloudOptions& options) {
  check_options(degree, options);
  if (ring.size() < 2) {
    throw ricci::InvalidInputError("knot cloud: vertex " + std::to_string(vertex_id) +
                                   " has fewer than two ring neighbours");
  }
  const std::size_t fan = ring_closed ? ring.size() : ring.size() - 1;
  double smallest_inradius = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < fan; ++i) {
    smallest_inradius =
        std::min(smallest_inradius, inradius(center, ring[i], ring[(i + 1) % ring.size()]));
  }
  if (!(smallest_inradius > 0.0) || !std::isfinite(smallest_inradius)) {
    throw ricci::InvalidInputError("knot cloud: vertex " + std::to_string(vertex_id) +
                                   " has a degenerate incident triangle");
  }
  const double radius = options.radius_fraction * smallest_inradius;

  // Pattern relative to the first neighbour's direction (rigid-motion equivariance).
  const Eigen::Vector2d first = ring[0] - center;
  const double reference = std::atan2(first.y(), first.x());
  std::vector<double> edge_angles;
  for (const Eigen::Vector2d& w : ring) {
    const Eigen::Vector2d e = w - center;
    edge_angles.push_back(std::atan2(e.y(), e.x()) - reference);
  }
  Random random(options.seed * 0x2545F4914F6CDD1Dull ^ (vertex_id + 0x632BE59BD9B4E019ull));
  const double spacing = 2.0 * kPi / (degree + 0.5);
  std::vector<double> angles(static_cast<std::size_t>(degree));
  std::vector<double> scales(static_cast<std::size_t>(degree));
  for (int j = 0; j < degree; ++j) {
    angles[j] = j * spacing + (2.0 * random.uniform() - 1.0) * options.angle_jitter * spacing;
    scales[j] = 1.0 - options.radius_jitter * random.uniform();
  }
  // Rotation of the whole pattern maximising the smallest angle (modulo pi) between a knot
  // direction and an edge line: the middle of the widest gap between the forbidden rotations
  // e - a (mod pi).
  std::vector<double> forbidden;
  for (double a : angles) {
    for (double e : edge_angles) {
      double d = std::fmod(e - a, kPi);
      if (d < 0.0) d += kPi;
      forbidden.push_back(d);
    }
  }
  std::sort(forbidden.begin(), forbidden.end());
  double best_rotation = 0.0, widest_gap = -1.0;
  for (std::size_t i = 0; i < forbidden.size(); ++i) {
    const double next = i + 1 < forbidden.size() ? forbidden[i + 1] : forbidden[0] + kPi;
    if (next - forbidden[i] > widest_gap) {
      widest_gap = next - forbidden[i];
      best_rotation = 0.5 * (forbidden[i] + next);
    }
  }
  KnotCloud cloud;
  cloud.knots.push_back(center);
  for (int j = 0; j < degree; ++j) {
    const double angle = reference + best_rotation + angles[j];
    cloud.knots.push_back(center +
                          radius * scales[j] * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  return cloud;
}

std::vector<KnotCloud> make_knot_clouds(const PlanarTriangulation& triangulation, int degree,
                                        const KnotCloudOptions& options) {
  check_options(degree, options);
  validate(triangulation);
  const std::vector<VertexRing> rings = vertex_rings(triangulation);
  std::vector<KnotCloud> clouds(triangulation.positions.size());
  for (std::size_t v = 0; v < rings.size(); ++v) {
    const Eigen::Vector2d& center = triangulation.positions[v];
    if (rings[v].neighbours.empty()) {
      clouds[v].knots.assign(static_cast<std::size_t>(degree) + 1, center);
      continue;
    }
    std::vector<Eigen::Vector2d> ring;
    for (int w : rings[v].neighbours) ring.push_back(triangulation.positions[w]);
    clouds[v] = make_knot_cloud(degree, v, center, ring, rings[v].closed, options);
  }
  return clouds;
}

KnotCloud transformed(const KnotCloud& cloud, const Eigen::Matrix2d& rotation,
                      const Eigen::Vector2d& translation) {
  KnotCloud result;
  result.knots.reserve(cloud.knots.size());
  for (const Eigen::Vector2d& t : cloud.knots) result.knots.push_back(rotation * t + translation);
  return result;
}

}  // namespace spline
