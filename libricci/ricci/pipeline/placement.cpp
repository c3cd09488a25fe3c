// placement_mesh and place_on_problem_mesh (one_cone_atlas.h): points of the surface carried
// through the intrinsic flow's flips onto the atlas' mesh.
#include <algorithm>
#include <array>
#include <string>

#include "ricci/intrinsic/point_tracking.h"
#include "ricci/mesh/errors.h"
#include "ricci/pipeline/one_cone_atlas.h"

namespace ricci {
namespace {

// The vertices of `face` in fv_range order (SurfacePoint's barycentric order).
std::array<int, 3> face_vertices(const Mesh& mesh, int face) {
  std::array<int, 3> vertices{-1, -1, -1};
  std::size_t k = 0;
  for (auto v : mesh.fv_range(mesh.face_handle(static_cast<unsigned>(face)))) {
    if (k < 3) vertices[k] = v.idx();
    ++k;
  }
  return vertices;
}

// Which of `vertices` is v (-1 when none).
int position_of(const std::array<int, 3>& vertices, int v) {
  for (int k = 0; k < 3; ++k) {
    if (vertices[static_cast<std::size_t>(k)] == v) return k;
  }
  return -1;
}

}  // namespace

const Mesh& placement_mesh(const OneConeAtlasResult& result) {
  return result.flip_record.empty() ? result.problem.mesh : result.flip_record.initial;
}

std::vector<SurfacePoint> place_on_problem_mesh(const OneConeAtlasResult& result,
                                                std::vector<SurfacePoint> points) {
  const IntrinsicFlipRecord& record = result.flip_record;
  if (record.empty()) return points;
  const Mesh& from = record.initial;
  const Mesh& to = result.problem.mesh;
  const IntrinsicCorrespondence map(record.triangulation, record.flip_log);
  const IntrinsicTriangulation& start = map.initial();
  const IntrinsicTriangulation& end = map.final_triangulation();
  if (start.face_count() != static_cast<int>(from.n_faces()) ||
      end.face_count() != static_cast<int>(to.n_faces())) {
    throw TopologyError("placement: the flip record does not match the atlas' mesh");
  }
  std::vector<TriangulationPoint> tracked(points.size());
  for (std::size_t n = 0; n < points.size(); ++n) {
    const int f = points[n].face;
    if (f < 0 || f >= start.face_count()) {
      throw InvalidInputError("placement: point " + std::to_string(n) + " has face " +
                              std::to_string(f) + " of a " +
                              std::to_string(start.face_count()) + "-face mesh");
    }
    const std::array<int, 3> corners = face_vertices(from, f);
    tracked[n].face = f;
    for (int k = 0; k < 3; ++k) {
      const int at = position_of(corners, start.tail[static_cast<std::size_t>(3 * f + k)]);
      if (at < 0) throw TopologyError("placement: the flip record's faces are not its mesh's");
      tracked[n].weights[k] = std::max(points[n].barycentric[at], 0.0);
    }
    if (!(tracked[n].weights.sum() > 0.0)) tracked[n].weights.setConstant(1.0);
  }
  // (Weights at u = 0 keep their precision through the flips: a flip's carry at other scale
  // factors is the same sums, each multiplied by a corner's factor.)
  tracked = map.to_final(std::move(tracked));
  for (std::size_t n = 0; n < points.size(); ++n) {
    const int g = tracked[n].face;
    const Eigen::Vector3d b = barycentric_at(end, tracked[n], record.u);
    const std::array<int, 3> corners = face_vertices(to, g);
    for (int k = 0; k < 3; ++k) {
      const int at = position_of(corners, end.tail[static_cast<std::size_t>(3 * g + k)]);
      if (at < 0) {
        throw TopologyError("placement: the flip record's flips do not give the atlas' mesh");
      }
      points[n].barycentric[at] = b[k];
    }
    points[n].face = g;
  }
  return points;
}

}  // namespace ricci
