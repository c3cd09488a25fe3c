#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ricci/mesh/cgal_convert.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/mesh/simplify.h"
#include "ricci/mesh/simplify_quadric.h"

namespace ricci {
namespace {

namespace SMS = CGAL::Surface_mesh_simplification;
namespace PMP = CGAL::Polygon_mesh_processing;
using cgal::SurfaceMesh;

// Collapse::staged: the own quadric collapse down to this many times the target and at least
// kStageMinimumFaces, CGAL's from there (see SimplifyOptions). Inputs below that size keep the
// domains CGAL gives (those the tests' thresholds were set on).
constexpr int kStageFactor = 4;
constexpr int kStageMinimumFaces = 16000;

void collapse_to(SurfaceMesh& mesh, int target_faces) {
  using Policies = SMS::GarlandHeckbert_plane_policies<SurfaceMesh, cgal::Kernel>;
  Policies policies(mesh);
  SMS::Bounded_normal_change_placement<Policies::Get_placement> placement(policies.get_placement());
  // For a triangle mesh, faces ~ 2/3 of edges.
  SMS::Count_stop_predicate<SurfaceMesh> stop(static_cast<SurfaceMesh::size_type>(target_faces * 3 / 2));
  SMS::edge_collapse(mesh, stop, CGAL::parameters::get_cost(policies.get_cost()).get_placement(placement));
  mesh.collect_garbage();
}

// Edge length of `faces` equilateral triangles covering the mesh's area.
double edge_length_for(const SurfaceMesh& mesh, int faces) {
  double area = PMP::area(mesh);
  return std::sqrt(4.0 * area / (std::sqrt(3.0) * faces));
}

void remesh(SurfaceMesh& mesh, int target_faces, int iterations) {
  PMP::isotropic_remeshing(faces(mesh), edge_length_for(mesh, target_faces), mesh,
                           CGAL::parameters::number_of_iterations(static_cast<unsigned>(iterations))
                               .protect_constraints(false)
                               .relax_constraints(false));
  mesh.collect_garbage();
}

double min_corner_angle_deg(const Mesh& mesh) {
  double smallest = 180.0;
  for (auto h : mesh.halfedges()) {
    if (mesh.is_boundary(h)) continue;
    smallest = std::min(smallest, mesh.calc_sector_angle(h) * 180.0 / M_PI);
  }
  return smallest;
}

}  // namespace

SimplifyResult simplify_mesh(const Mesh& dense, const SimplifyOptions& options) {
  if (options.target_faces < 4) {
    throw InvalidInputError("simplify: target of " + std::to_string(options.target_faces) +
                            " faces is too small (need at least 4)");
  }
  SimplifyResult result;
  result.faces_before = static_cast<int>(dense.n_faces());
  SurfaceMesh mesh;
  const int target = options.target_faces;
  using Collapse = SimplifyOptions::Collapse;
  const int first_stage = options.collapse == Collapse::quadric
                              ? target
                              : std::max(kStageFactor * target, kStageMinimumFaces);
  if (options.collapse != Collapse::cgal && first_stage < result.faces_before) {
    Mesh decimated = dense;
    quadric_decimate(decimated, first_stage);
    mesh = cgal::to_surface_mesh(decimated);
  } else {
    mesh = cgal::to_surface_mesh(dense);
  }
  if (target < static_cast<int>(mesh.number_of_faces())) collapse_to(mesh, target);
  if (options.remesh_iterations > 0) remesh(mesh, options.target_faces, options.remesh_iterations);
  result.mesh = cgal::from_surface_mesh(mesh);
  result.faces_after = static_cast<int>(result.mesh.n_faces());
  const SurfaceTopology before = surface_topology(dense), after = surface_topology(result.mesh);
  if (after.euler_characteristic != before.euler_characteristic ||
      (after.boundary_loops == 0) != (before.boundary_loops == 0)) {
    throw TopologyError("simplify: the topology changed (Euler characteristic " +
                        std::to_string(before.euler_characteristic) + " -> " +
                        std::to_string(after.euler_characteristic) + "); ask for more faces");
  }
  result.min_angle_deg = min_corner_angle_deg(result.mesh);
  return result;
}

}  // namespace ricci
