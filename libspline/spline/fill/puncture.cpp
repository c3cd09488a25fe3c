#include "spline/fill/puncture.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ricci/mesh/errors.h"

namespace spline {

namespace {

// Twice the area vector of a face (its normal, of length twice its area).
Eigen::Vector3d area_vector(const ricci::Mesh& mesh, int face) {
  Eigen::Vector3d p[3];
  int k = 0;
  for (auto v : mesh.fv_range(mesh.face_handle(face))) p[k++] = ricci::to_eigen(mesh.point(v));
  return (p[1] - p[0]).cross(p[2] - p[0]);
}

// The faces with a corner within rings - 1 vertex rings of `vertex` (rings = 1: its star).
std::vector<int> faces_within(const ricci::Mesh& mesh, ricci::VertexHandle vertex, int rings) {
  std::vector<int> depth(mesh.n_vertices(), -1);
  std::vector<ricci::VertexHandle> front{vertex};
  depth[static_cast<std::size_t>(vertex.idx())] = 0;
  std::vector<char> taken(mesh.n_faces(), 0);
  std::vector<int> faces;
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<ricci::VertexHandle> next;
    for (auto v : front) {
      for (auto f : mesh.vf_range(v)) {
        char& t = taken[static_cast<std::size_t>(f.idx())];
        if (t) continue;
        t = 1;
        faces.push_back(f.idx());
      }
      for (auto w : mesh.vv_range(v)) {
        int& d = depth[static_cast<std::size_t>(w.idx())];
        if (d >= 0) continue;
        d = ring + 1;
        next.push_back(w);
      }
    }
    front = std::move(next);
  }
  return faces;
}

}  // namespace

double star_normal_spread_deg(const ricci::Mesh& mesh, int vertex, int rings) {
  if (vertex < 0 || vertex >= static_cast<int>(mesh.n_vertices())) {
    throw ricci::InvalidInputError("vertex " + std::to_string(vertex) + " is out of range (" +
                                   std::to_string(mesh.n_vertices()) + " vertices)");
  }
  if (rings < 1) throw ricci::InvalidInputError("rings must be at least 1");
  return faces_normal_spread_deg(mesh, faces_within(mesh, mesh.vertex_handle(vertex), rings));
}

double faces_normal_spread_deg(const ricci::Mesh& mesh, const std::vector<int>& faces) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (auto f : faces) mean += area_vector(mesh, f);
  if (!(mean.norm() > 0.0)) return 180.0;
  mean.normalize();
  double spread = 0.0;
  for (auto f : faces) {
    const Eigen::Vector3d n = area_vector(mesh, f);
    if (!(n.norm() > 0.0)) continue;
    const double c = std::clamp(n.dot(mean) / n.norm(), -1.0, 1.0);
    spread = std::max(spread, std::acos(c) * 180.0 / M_PI);
  }
  return spread;
}

PunctureChoice choose_puncture(const ricci::Mesh& mesh,
                               const ricci::SingularityOptions& singularity,
                               const PunctureChoiceOptions& options) {
  if (options.rings < 1) throw ricci::InvalidInputError("puncture rings must be at least 1");
  if (!(options.distortion_tolerance >= 0.0)) {
    throw ricci::InvalidInputError("the puncture's distortion tolerance must be >= 0");
  }
  if (!(options.min_spread_gain >= 0.0 && options.min_spread_gain <= 1.0)) {
    throw ricci::InvalidInputError("the puncture's spread gain must lie in [0, 1]");
  }
  PunctureChoice out;
  out.choice = ricci::choose_singularity(mesh, singularity);
  out.vertex = out.distortion_vertex = out.choice.vertex;
  out.area_distortion = out.choice.area_distortion;
  if (out.vertex < 0) return out;
  out.normal_spread_deg = out.distortion_spread_deg =
      star_normal_spread_deg(mesh, out.vertex, options.rings);
  double best = std::numeric_limits<double>::infinity();
  for (const auto& s : out.choice.verified) best = std::min(best, s.area_distortion);
  if (!std::isfinite(best)) return out;
  out.candidates = 0;
  int flattest = -1;
  double chosen_distortion = std::numeric_limits<double>::infinity();
  double chosen_spread = std::numeric_limits<double>::infinity();
  for (const auto& s : out.choice.verified) {
    if (!(s.area_distortion <= (1.0 + options.distortion_tolerance) * best)) continue;
    ++out.candidates;
    const double spread = star_normal_spread_deg(mesh, s.vertex, options.rings);
    if (spread < chosen_spread ||
        (spread == chosen_spread && s.area_distortion < chosen_distortion)) {
      flattest = s.vertex;
      chosen_spread = spread;
      chosen_distortion = s.area_distortion;
    }
  }
  if (flattest < 0 || !(chosen_spread <= (1.0 - options.min_spread_gain) *
                                           out.distortion_spread_deg)) {
    return out;
  }
  out.vertex = flattest;
  out.normal_spread_deg = chosen_spread;
  out.area_distortion = chosen_distortion;
  return out;
}

}  // namespace spline
