#include "spline/surface/edit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ricci/mesh/errors.h"
#include "spline/tessellate/parallel_for.h"

namespace spline {
namespace {

using ricci::InvalidInputError;

// By vertex: the spline's domain faces around it, ascending.
std::vector<std::vector<int>> domain_stars(const SplineSurface& surface) {
  const ManifoldSplineSpace& space = *surface.spline.space;
  std::vector<std::vector<int>> stars(surface.domain.n_vertices());
  for (int face : space.domain_faces()) {
    for (auto v : surface.domain.fv_range(surface.domain.face_handle(face))) {
      stars[v.idx()].push_back(face);
    }
  }
  return stars;
}

std::vector<int> support_of(const SplineSurface& surface,
                            const std::vector<std::vector<int>>& stars, int face) {
  std::vector<int> faces;
  for (auto v : surface.domain.fv_range(surface.domain.face_handle(face))) {
    faces.insert(faces.end(), stars[v.idx()].begin(), stars[v.idx()].end());
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

void check_surface(const SplineSurface& surface) {
  if (!surface.spline.space ||
      surface.spline.control_points.rows() != surface.spline.space->function_count() ||
      static_cast<int>(surface.domain.n_faces()) != surface.spline.space->face_count()) {
    throw InvalidInputError("edit: the surface's spline, control points and domain disagree");
  }
}

// The report's faces and rims from the mask of affected faces.
void report_affected(const SplineSurface& surface, const std::vector<char>& affected,
                     EditReport& report) {
  for (std::size_t g = 0; g < affected.size(); ++g) {
    if (affected[g]) report.affected_faces.push_back(static_cast<int>(g));
  }
  const auto touches = [&](const Rim& rim) {
    return std::any_of(rim.edges.begin(), rim.edges.end(),
                       [&](const RimEdge& e) { return affected[e.face] != 0; });
  };
  for (std::size_t i = 0; i < surface.fills.size(); ++i) {
    if (touches(surface.fills[i].rim)) report.touched_fills.push_back(static_cast<int>(i));
  }
  for (std::size_t i = 0; i < surface.open_rims.size(); ++i) {
    if (touches(surface.open_rims[i])) report.touched_open_rims.push_back(static_cast<int>(i));
  }
}

// Moves every function of each face by its weight (0: not moved) times the displacement.
EditReport apply_face_weights(SplineSurface& surface, const std::vector<double>& weight_by_face,
                              const Eigen::Vector3d& displacement) {
  const ManifoldSplineSpace& space = *surface.spline.space;
  const auto stars = domain_stars(surface);
  const int m = space.functions_per_face();
  EditReport report;
  std::vector<char> affected(surface.domain.n_faces(), 0);
  for (int face : space.domain_faces()) {
    const double w = weight_by_face[face];
    if (!(w > 0.0)) continue;
    for (int beta = 0; beta < m; ++beta) {
      const int f = space.function_index(face, beta);
      surface.spline.control_points.row(f) += w * displacement.transpose();
      report.moved_functions.push_back(f);
      report.weights.push_back(w);
    }
    report.max_displacement = std::max(report.max_displacement, w * displacement.norm());
    for (int g : support_of(surface, stars, face)) affected[g] = 1;
  }
  report_affected(surface, affected, report);
  return report;
}

// By face: the distance from `centre` to the spline's samples on it; infinity on faces not
// shown (outside the domain or skipped).
std::vector<double> face_distances(const SplineSurface& surface, const Eigen::Vector3d& centre,
                                   const RegionMoveOptions& options) {
  const ManifoldSplineSpace& space = *surface.spline.space;
  const int d = options.samples_per_edge;
  std::vector<Eigen::Vector3d> barycentrics;
  for (int i = 0; i <= d; ++i) {
    for (int j = 0; i + j <= d; ++j) barycentrics.emplace_back(i, j, d - i - j);
  }
  for (Eigen::Vector3d& b : barycentrics) b /= d;
  std::vector<double> distance(surface.domain.n_faces(), std::numeric_limits<double>::infinity());
  const auto& faces = space.domain_faces();
  parallel_for(faces.size(), options.threads, [&](std::size_t i) {
    const int face = faces[i];
    if (!surface.skipped_faces.empty() && surface.skipped_faces[face]) return;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& b : barycentrics) {
      const Eigen::Vector3d p =
          combine(space.evaluate_basis({face, b}, -1, {}, BasisDerivatives::none),
                  surface.spline.control_points, -1)
              .position;
      nearest = std::min(nearest, (p - centre).norm());
    }
    distance[face] = nearest;
  });
  return distance;
}

}  // namespace

std::vector<int> function_support_faces(const SplineSurface& surface, int face) {
  check_surface(surface);
  if (face < 0 || face >= surface.spline.space->face_count() ||
      !surface.spline.space->in_domain(face)) {
    throw InvalidInputError("edit: face " + std::to_string(face) +
                            " is not in the spline's domain");
  }
  return support_of(surface, domain_stars(surface), face);
}

EditReport move_control_points(SplineSurface& surface, const std::vector<int>& functions,
                               const std::vector<Eigen::Vector3d>& displacements) {
  check_surface(surface);
  if (functions.size() != displacements.size()) {
    throw InvalidInputError("edit: " + std::to_string(functions.size()) + " control points but " +
                            std::to_string(displacements.size()) + " displacements");
  }
  const ManifoldSplineSpace& space = *surface.spline.space;
  for (std::size_t i = 0; i < functions.size(); ++i) {
    if (functions[i] < 0 || functions[i] >= space.function_count()) {
      throw InvalidInputError("edit: control point " + std::to_string(functions[i]) +
                              " is outside [0, " + std::to_string(space.function_count()) + ")");
    }
    if (!displacements[i].allFinite()) {
      throw InvalidInputError("edit: the displacement of control point " +
                              std::to_string(functions[i]) + " is not finite");
    }
  }
  const auto stars = domain_stars(surface);
  const int m = space.functions_per_face();
  std::vector<Eigen::Vector3d> total(static_cast<std::size_t>(space.function_count()),
                                     Eigen::Vector3d::Zero());
  std::vector<char> moved(total.size(), 0), affected(surface.domain.n_faces(), 0);
  for (std::size_t i = 0; i < functions.size(); ++i) {
    total[functions[i]] += displacements[i];
    moved[functions[i]] = 1;
  }
  EditReport report;
  for (std::size_t f = 0; f < total.size(); ++f) {
    if (!moved[f]) continue;
    surface.spline.control_points.row(static_cast<Eigen::Index>(f)) += total[f].transpose();
    report.moved_functions.push_back(static_cast<int>(f));
    report.weights.push_back(1.0);
    report.max_displacement = std::max(report.max_displacement, total[f].norm());
    const int face = space.domain_faces()[f / static_cast<std::size_t>(m)];
    for (int g : support_of(surface, stars, face)) affected[g] = 1;
  }
  report_affected(surface, affected, report);
  return report;
}

EditReport move_region(SplineSurface& surface, const Eigen::Vector3d& centre, double radius,
                       const Eigen::Vector3d& displacement, const RegionMoveOptions& options) {
  check_surface(surface);
  if (!(std::isfinite(radius) && radius > 0.0)) {
    throw InvalidInputError("edit: the radius " + std::to_string(radius) +
                            " is not a positive number");
  }
  if (!centre.allFinite() || !displacement.allFinite()) {
    throw InvalidInputError("edit: the centre or the displacement is not finite");
  }
  if (options.samples_per_edge < 1) {
    throw InvalidInputError("edit: samples_per_edge must be at least 1");
  }
  const std::vector<double> distance = face_distances(surface, centre, options);
  const auto stars = domain_stars(surface);
  std::vector<double> weight(surface.domain.n_faces(), 0.0);
  for (int face : surface.spline.space->domain_faces()) {
    double nearest = std::numeric_limits<double>::infinity();
    for (int g : support_of(surface, stars, face)) nearest = std::min(nearest, distance[g]);
    const double s = nearest / radius;
    if (s < 1.0) weight[face] = std::pow(1.0 - s * s, 3);
  }
  return apply_face_weights(surface, weight, displacement);
}

}  // namespace spline
