#include "msp/fit_report.h"

#include <algorithm>
#include <cmath>

namespace msp {

nlohmann::json fit_report_json(const std::string& path, const spline::FittedSurface& run,
                               const spline::FitSurfaceOptions& options) {
  const auto& atlas = run.atlas;
  const auto& space = *run.surface.spline.space;
  nlohmann::json singularities = nlohmann::json::array();
  if (atlas.problem.cone >= 0) {
    const double K = atlas.flow.curvature[atlas.problem.cone];
    const auto p = atlas.problem.mesh.point(atlas.problem.mesh.vertex_handle(atlas.problem.cone));
    singularities.push_back({{"domain_vertex", atlas.chosen_vertex},
                             {"input_vertex", options.singular_vertex},
                             {"position", {p[0], p[1], p[2]}},
                             {"curvature", K},
                             {"cone_angle", 2 * M_PI - K}});
  } else if (atlas.problem.kind == ricci::OneConeKind::PuncturedSphere) {
    singularities.push_back({{"domain_vertex", atlas.chosen_vertex},
                             {"input_vertex", options.singular_vertex},
                             {"removed_star", true}});
  }
  nlohmann::json seconds = nlohmann::json::object();
  for (const auto& [name, s] : run.seconds) seconds[name] = s;
  nlohmann::json cpu_seconds = nlohmann::json::object();
  for (const auto& [name, s] : run.cpu_seconds) cpu_seconds[name] = s;
  const double diag = std::max(run.bbox_diagonal, 1e-300);
  const auto& t = run.topology;
  return {
      {"mesh", path},
      {"input_vertices", run.input.vertices},
      {"input_faces", run.input.faces},
      {"genus", run.input.genus},
      {"boundary_loops", run.input.boundary_loops},
      {"singularities", singularities},
      {"domain_faces", space.domain_face_count()},
      {"domain_mesh_faces", atlas.problem.mesh.n_faces()},
      {"cone_refinement",
       {{"levels", atlas.cone_refinement.levels},
        {"rings", options.cone_refinement.rings},
        {"added_faces", atlas.cone_refinement.added_faces}}},
      {"control_points", space.function_count()},
      {"degree", space.degree()},
      {"fairness", options.fairness},
      {"fit_rms", run.fit_rms},
      {"fit_max", run.fit_max},
      {"fit_rms_relative", run.fit_rms / diag},
      {"fit_max_relative", run.fit_max / diag},
      {"fit_points", run.fit_points},
      {"bbox_diagonal", run.bbox_diagonal},
      {"seam_normal_jump_max_deg", std::max(run.edge_normal_jump_deg, run.fill_normal_jump_deg)},
      {"edge_normal_jump_max_deg", run.edge_normal_jump_deg},
      {"fill_normal_jump_max_deg", run.fill_normal_jump_deg},
      {"fill_position_gap_relative", run.fill_position_gap},
      {"filled_rims", run.surface.fills.size()},
      {"fill_failures", run.fill_failures},
      {"fit_points_on_fills", run.fit_points_on_fills},
      {"open_rims", run.surface.open_rims.size()},
      {"boundary_rims", run.boundary_rims},
      {"fallback_fills", run.fallback_fills},
      {"watertight", run.watertight},
      {"tessellation",
       {{"density", run.tessellation.density},
        {"vertices", t.vertices},
        {"triangles", t.faces},
        {"render_vertices", run.tessellation.uvs.rows()},
        {"euler_characteristic", t.euler_characteristic},
        {"boundary_loops", t.boundary_loops},
        {"boundary_edges", t.boundary_edges},
        {"nonmanifold_edges", t.nonmanifold_edges},
        {"misoriented_edges", t.misoriented_edges},
        {"nonmanifold_vertices", t.nonmanifold_vertices},
        {"duplicate_positions", t.duplicate_positions},
        {"float32_degenerate_triangles", run.float_topology.degenerate_triangles},
        {"float32_nonmanifold_edges", run.float_topology.nonmanifold_edges}}},
      {"surface_dihedral",
       {{"edges", run.surface_dihedral.edges},
        {"median_deg", run.surface_dihedral.median_deg},
        {"p99_deg", run.surface_dihedral.p99_deg},
        {"max_deg", run.surface_dihedral.max_deg},
        {"edges_over_60_deg", run.surface_dihedral.over_60_deg},
        {"edges_over_90_deg", run.surface_dihedral.over_90_deg}}},
      {"fit_constraint_residual", run.fit_constraint_residual},
      {"seconds", seconds},
      {"cpu_seconds", cpu_seconds},
  };
}

}  // namespace msp
