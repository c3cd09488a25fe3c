#include "spline/surface/fold_smoothing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "ricci/mesh/arrays.h"
#include "ricci/mesh/errors.h"
#include "spline/tessellate/dihedral.h"

namespace spline {
namespace {

void check_flags(const ricci::Mesh& domain, const std::vector<char>& faces, const char* what) {
  if (faces.size() != domain.n_faces()) {
    throw ricci::InvalidInputError(std::string(what) + ": " + std::to_string(faces.size()) +
                                   " face flags for a domain of " +
                                   std::to_string(domain.n_faces()) + " faces");
  }
}

}  // namespace

std::vector<int> rings_from_faces(const ricci::Mesh& domain, const std::vector<char>& faces,
                                  int max_rings) {
  check_flags(domain, faces, "rings_from_faces");
  if (max_rings < 0) throw ricci::InvalidInputError("rings_from_faces: max_rings < 0");
  std::vector<int> ring(faces.size(), -1);
  std::vector<int> front;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (!faces[f]) continue;
    ring[f] = 0;
    front.push_back(static_cast<int>(f));
  }
  for (int r = 1; r <= max_rings && !front.empty(); ++r) {
    std::vector<int> next;
    for (int f : front) {
      for (auto g : domain.ff_range(domain.face_handle(f))) {
        int& at = ring[static_cast<std::size_t>(g.idx())];
        if (at >= 0) continue;
        at = r;
        next.push_back(g.idx());
      }
    }
    front = std::move(next);
  }
  return ring;
}

std::vector<double> fold_smoothing_floor(const ricci::Mesh& domain, const std::vector<char>& folded,
                                         const FoldSmoothingOptions& options) {
  check_flags(domain, folded, "fold_smoothing_floor");
  if (!(options.level > 0.0) || !(options.taper > 0.0 && options.taper <= 1.0) ||
      options.rings < 0 || options.taper_rings < 0) {
    throw ricci::InvalidInputError(
        "fold_smoothing_floor: level must be > 0, taper in (0, 1], rings >= 0");
  }
  const std::vector<int> ring =
      rings_from_faces(domain, folded, options.rings + options.taper_rings);
  std::vector<double> floor(ring.size(), 0.0);
  for (std::size_t f = 0; f < ring.size(); ++f) {
    if (ring[f] < 0) continue;
    floor[f] = options.level * std::pow(options.taper, std::max(0, ring[f] - options.rings));
  }
  return floor;
}

std::vector<Eigen::Vector3d> mesh_fold_points(const ricci::Mesh& mesh) {
  const ricci::VertexFaceArrays arrays = ricci::to_arrays(mesh);
  std::vector<std::array<int, 3>> triangles(static_cast<std::size_t>(arrays.F.rows()));
  for (Eigen::Index f = 0; f < arrays.F.rows(); ++f)
    triangles[static_cast<std::size_t>(f)] = {arrays.F(f, 0), arrays.F(f, 1), arrays.F(f, 2)};
  const DihedralReport report = dihedral_angles(triangles, arrays.V);
  std::vector<Eigen::Vector3d> points;
  points.reserve(report.fold_edges.size());
  for (const auto& e : report.fold_edges)
    points.push_back(0.5 * (arrays.V.row(e[0]) + arrays.V.row(e[1])).transpose());
  return points;
}

bool all_within(const std::vector<Eigen::Vector3d>& points,
                const std::vector<Eigen::Vector3d>& near, double radius) {
  const double r2 = radius * radius;
  for (const auto& p : points) {
    bool found = false;
    for (const auto& q : near) {
      if ((p - q).squaredNorm() <= r2) {
        found = true;
        break;
      }
    }
    if (!found) return false;
  }
  return true;
}

}  // namespace spline
