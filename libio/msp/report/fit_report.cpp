#include "msp/report/fit_report.h"

#include <algorithm>
#include <cmath>

namespace msp {

namespace {

nlohmann::json singularities_json(const spline::FittedSurface& fitted,
                                  const spline::FitSurfaceOptions& options) {
  const auto& atlas = fitted.atlas;
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
  return singularities;
}

nlohmann::json stage_seconds_json(const spline::StageSeconds& stages) {
  nlohmann::json seconds = nlohmann::json::object();
  for (const auto& [name, s] : stages) seconds[name] = s;
  return seconds;
}

nlohmann::json tessellation_json(const spline::FittedSurface& fitted) {
  const auto& t = fitted.topology;
  return {{"density", fitted.tessellation.density},
          {"vertices", t.vertices},
          {"triangles", t.faces},
          {"render_vertices", fitted.tessellation.uvs.rows()},
          {"euler_characteristic", t.euler_characteristic},
          {"boundary_loops", t.boundary_loops},
          {"boundary_edges", t.boundary_edges},
          {"nonmanifold_edges", t.nonmanifold_edges},
          {"misoriented_edges", t.misoriented_edges},
          {"nonmanifold_vertices", t.nonmanifold_vertices},
          {"duplicate_positions", t.duplicate_positions},
          {"float32_degenerate_triangles", fitted.float_topology.degenerate_triangles},
          {"float32_nonmanifold_edges", fitted.float_topology.nonmanifold_edges}};
}

nlohmann::json dihedral_json(const spline::DihedralReport& d) {
  return {{"edges", d.edges},
          {"median_deg", d.median_deg},
          {"p99_deg", d.p99_deg},
          {"max_deg", d.max_deg},
          {"edges_over_60_deg", d.over_60_deg},
          {"edges_over_90_deg", d.over_90_deg}};
}

// Open inputs: the ghost collar and how the domain's boundary was made to follow the scan's.
nlohmann::json boundary_json(const spline::FittedSurface& fitted) {
  const auto& f = fitted.boundary_follow;
  const auto ghosts = std::count(fitted.collar_faces.begin(), fitted.collar_faces.end(), 1);
  return {{"collar_faces", ghosts},
          {"collar_refused", fitted.collar_refused},
          {"follow_splits", f.splits},
          {"follow_distance_before_relative", f.distance_before},
          {"follow_distance_after_relative", f.distance_after}};
}

}  // namespace

nlohmann::json fit_report_json(const std::string& path, const spline::FittedSurface& fitted,
                               const spline::FitSurfaceOptions& options) {
  const auto& atlas = fitted.atlas;
  const auto& space = *fitted.surface.spline.space;
  const double diag = std::max(fitted.bbox_diagonal, 1e-300);
  return {
      {"mesh", path},
      {"input_vertices", fitted.input.vertices},
      {"input_faces", fitted.input.faces},
      {"genus", fitted.input.genus},
      {"boundary_loops", fitted.input.boundary_loops},
      {"singularities", singularities_json(fitted, options)},
      {"domain_faces", space.domain_face_count()},
      {"domain_mesh_faces", atlas.problem.mesh.n_faces()},
      {"cone_refinement",
       {{"levels", atlas.cone_refinement.levels},
        {"rings", options.cone_refinement.rings},
        {"added_faces", atlas.cone_refinement.added_faces}}},
      {"control_points", space.function_count()},
      {"degree", space.degree()},
      {"fairness", options.fairness},
      {"fit_rms", fitted.fit_rms},
      {"fit_max", fitted.fit_max},
      {"fit_rms_relative", fitted.fit_rms / diag},
      {"fit_max_relative", fitted.fit_max / diag},
      {"fit_points", fitted.fit_points},
      {"bbox_diagonal", fitted.bbox_diagonal},
      {"seam_normal_jump_max_deg",
       std::max(fitted.edge_normal_jump_deg, fitted.fill_normal_jump_deg)},
      {"edge_normal_jump_max_deg", fitted.edge_normal_jump_deg},
      {"fill_normal_jump_max_deg", fitted.fill_normal_jump_deg},
      {"fill_position_gap_relative", fitted.fill_position_gap},
      {"filled_rims", fitted.surface.fills.size()},
      {"fill_failures", fitted.fill_failures},
      {"fit_points_on_fills", fitted.fit_points_on_fills},
      {"open_rims", fitted.surface.open_rims.size()},
      {"boundary_rims", fitted.boundary_rims},
      {"fallback_fills", fitted.fallback_fills},
      {"watertight", fitted.watertight},
      {"tessellation", tessellation_json(fitted)},
      {"surface_dihedral", dihedral_json(fitted.surface_dihedral)},
      {"boundary", boundary_json(fitted)},
      {"fit_constraint_residual", fitted.fit_constraint_residual},
      {"seconds", stage_seconds_json(fitted.seconds)},
      {"cpu_seconds", stage_seconds_json(fitted.cpu_seconds)},
  };
}

}  // namespace msp
