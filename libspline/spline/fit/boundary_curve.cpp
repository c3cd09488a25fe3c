#include "spline/fit/boundary_curve.h"

#include <algorithm>
#include <array>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/soup_distance.h"
#include "ricci/topology/slice.h"

namespace spline {
namespace {

// A boundary edge of the surface inside its face: the face and the corners it runs between.
struct RimEdge {
  int face = -1;
  int from = 0, to = 0;  // corner indices of face_halfedges order
};

std::vector<RimEdge> surface_boundary_edges(const ricci::Mesh& mesh,
                                            const std::vector<char>& surface_faces) {
  const auto on_surface = [&](ricci::FaceHandle f) {
    return f.is_valid() &&
           (surface_faces.empty() || surface_faces[static_cast<std::size_t>(f.idx())] != 0);
  };
  std::vector<RimEdge> edges;
  for (auto f : mesh.faces()) {
    if (!on_surface(f)) continue;
    const auto hs = ricci::face_halfedges(mesh, f);
    for (int j = 0; j < 3; ++j) {
      const auto other = mesh.face_handle(mesh.opposite_halfedge_handle(hs[j]));
      if (!on_surface(other)) edges.push_back({f.idx(), (j + 2) % 3, j});
    }
  }
  return edges;
}

Eigen::Vector3d corner(const ricci::Mesh& mesh, int face, int k) {
  const auto hs = ricci::face_halfedges(mesh, mesh.face_handle(face));
  return ricci::to_eigen(mesh.point(mesh.to_vertex_handle(hs[k])));
}

DomainPoint on_edge(const RimEdge& e, double t) {
  DomainPoint p{e.face, Eigen::Vector3d::Zero()};
  p.barycentric[e.from] = 1.0 - t;
  p.barycentric[e.to] = t;
  return p;
}

}  // namespace

BoundaryCurvePoints boundary_curve_points(const ricci::Mesh& domain,
                                          const std::vector<char>& surface_faces,
                                          const ricci::Mesh& dense,
                                          const BoundaryCurveOptions& options) {
  if (options.samples_per_edge < 1 || options.weight < 0) {
    throw ricci::InvalidInputError("boundary curve: samples_per_edge must be >= 1, weight >= 0");
  }
  if (!surface_faces.empty() && surface_faces.size() != domain.n_faces()) {
    throw ricci::InvalidInputError("boundary curve: " + std::to_string(surface_faces.size()) +
                                   " surface flags for " + std::to_string(domain.n_faces()) +
                                   " faces");
  }
  BoundaryCurvePoints out;
  out.points.resize(0, 3);
  const std::vector<RimEdge> rim = surface_boundary_edges(domain, surface_faces);
  Eigen::MatrixX3d dense_points(static_cast<Eigen::Index>(dense.n_vertices()), 3);
  for (auto v : dense.vertices()) dense_points.row(v.idx()) = ricci::to_eigen(dense.point(v));
  std::vector<std::array<int, 2>> dense_edges;
  for (auto e : dense.edges()) {
    if (!dense.is_boundary(e)) continue;
    const auto h = dense.halfedge_handle(e, 0);
    dense_edges.push_back({dense.from_vertex_handle(h).idx(), dense.to_vertex_handle(h).idx()});
  }
  if (options.weight == 0 || rim.empty() || dense_edges.empty()) return out;

  // The domain's boundary as segments (rows 2i, 2i + 1: edge i's ends).
  Eigen::MatrixX3d rim_points(static_cast<Eigen::Index>(2 * rim.size()), 3);
  std::vector<std::array<int, 2>> rim_segments(rim.size());
  for (std::size_t i = 0; i < rim.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(2 * i);
    rim_points.row(r) = corner(domain, rim[i].face, rim[i].from).transpose();
    rim_points.row(r + 1) = corner(domain, rim[i].face, rim[i].to).transpose();
    rim_segments[i] = {static_cast<int>(r), static_cast<int>(r + 1)};
  }
  const ricci::SegmentSoupDistance scan_curve(dense_points, dense_edges);
  const double max_gap =
      options.max_gap *
      (dense_points.colwise().maxCoeff() - dense_points.colwise().minCoeff()).norm();
  const ricci::SegmentSoupDistance domain_curve(rim_points, rim_segments);

  std::vector<DomainPoint> parameters;
  std::vector<Eigen::Vector3d> targets;
  const int s = options.samples_per_edge;
  for (std::size_t i = 0; i < rim.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(2 * i);
    for (int k = 0; k < s; ++k) {
      const double t = static_cast<double>(k) / s;
      const Eigen::Vector3d x =
          ((1.0 - t) * rim_points.row(r) + t * rim_points.row(r + 1)).transpose();
      const ricci::SoupHit hit = scan_curve.closest(x);
      if (hit.distance > max_gap) continue;
      parameters.push_back(on_edge(rim[i], t));
      targets.push_back(hit.point);
    }
  }
  for (auto v : dense.vertices()) {
    if (!dense.is_boundary(v)) continue;
    const Eigen::Vector3d x = dense_points.row(v.idx()).transpose();
    const ricci::SoupHit hit = domain_curve.closest(x);
    if (hit.distance > max_gap) continue;
    const auto r = static_cast<Eigen::Index>(2 * hit.primitive);
    const Eigen::Vector3d a = rim_points.row(r).transpose(), b = rim_points.row(r + 1).transpose();
    const double length2 = (b - a).squaredNorm();
    const double t =
        length2 > 0.0 ? std::clamp((hit.point - a).dot(b - a) / length2, 0.0, 1.0) : 0.0;
    const DomainPoint p = on_edge(rim[static_cast<std::size_t>(hit.primitive)], t);
    out.scan_vertices.push_back(v.idx());
    out.scan_vertex_parameters.push_back(p);
    parameters.push_back(p);
    targets.push_back(x);
  }
  out.samples = static_cast<int>(parameters.size());
  const auto copies = static_cast<std::size_t>(options.weight);
  out.parameters.reserve(copies * parameters.size());
  out.points.resize(static_cast<Eigen::Index>(copies * parameters.size()), 3);
  Eigen::Index row = 0;
  for (std::size_t c = 0; c < copies; ++c) {
    for (std::size_t i = 0; i < parameters.size(); ++i) {
      out.parameters.push_back(parameters[i]);
      out.points.row(row++) = targets[i].transpose();
    }
  }
  return out;
}

BoundaryCurvePoints missed_boundary_points(const ManifoldSpline& spline,
                                           const BoundaryCurvePoints& boundary, double distance,
                                           int copies) {
  BoundaryCurvePoints out;
  std::vector<Eigen::Index> missed;
  for (Eigen::Index i = 0; i < boundary.samples; ++i) {
    const auto& p = boundary.parameters[static_cast<std::size_t>(i)];
    if ((spline.evaluate(p).position - boundary.points.row(i).transpose()).norm() > distance)
      missed.push_back(i);
  }
  out.samples = static_cast<int>(missed.size());
  out.points.resize(static_cast<Eigen::Index>(missed.size()) * std::max(copies, 0), 3);
  Eigen::Index row = 0;
  for (int c = 0; c < copies; ++c) {
    for (Eigen::Index i : missed) {
      out.parameters.push_back(boundary.parameters[static_cast<std::size_t>(i)]);
      out.points.row(row++) = boundary.points.row(i);
    }
  }
  return out;
}

}  // namespace spline
