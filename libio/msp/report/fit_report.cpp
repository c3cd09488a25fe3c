#include "msp/report/fit_report.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <spline/fill/puncture.h>
#include <spline/surface/cap_holes.h>

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
    nlohmann::json puncture = {{"domain_vertex", atlas.chosen_vertex},
                               {"input_vertex", options.singular_vertex},
                               {"removed_star", true}};
    const spline::PunctureChoice& choice = fitted.puncture;
    if (choice.vertex >= 0) {  // chosen for flatness among near-least-distortion vertices
      puncture["flatness_choice"] = {
          {"normal_spread_deg", choice.normal_spread_deg},
          {"least_distortion_vertex", choice.distortion_vertex},
          {"least_distortion_normal_spread_deg", choice.distortion_spread_deg},
          {"candidates", choice.candidates},
          {"moved", choice.vertex != choice.distortion_vertex}};
    }
    singularities.push_back(std::move(puncture));
  }
  return singularities;
}

// Twice the area vector of a face of `mesh` (its normal, of length twice its area).
Eigen::Vector3d area_vector(const ricci::Mesh& mesh, int face) {
  Eigen::Vector3d p[3];
  int k = 0;
  for (auto v : mesh.fv_range(mesh.face_handle(face))) p[k++] = ricci::to_eigen(mesh.point(v));
  return (p[1] - p[0]).cross(p[2] - p[0]);
}

// A hole's faces in 3D: their area, bounding box and how far their normals turn from the
// area-weighted mean (degrees; 0 for a flat hole, tens over a pocket or around a corner).
struct HoleShape {
  double area = 0.0;
  Eigen::AlignedBox3d box;
  double normal_spread_deg = 0.0;
};

HoleShape hole_shape(const ricci::Mesh& mesh, const std::vector<int>& faces) {
  HoleShape shape;
  for (int f : faces) {
    const Eigen::Vector3d a = area_vector(mesh, f);
    shape.area += a.norm() / 2;
    for (auto v : mesh.fv_range(mesh.face_handle(f)))
      shape.box.extend(ricci::to_eigen(mesh.point(v)));
  }
  // A boundary loop's patch covers no face: no spread.
  if (!faces.empty()) shape.normal_spread_deg = spline::faces_normal_spread_deg(mesh, faces);
  return shape;
}

// Each patch's hole as the domain mesh sees it (covered faces, their share of the domain's
// area, extent over the input's diagonal, normal spread) and the patch's seam: largest, the rim
// edges where it exceeds 90 degrees (the patch folds back there), the domain vertex starting
// the worst rim edge.
nlohmann::json fill_patches_json(const spline::FittedSurface& fitted, double diag) {
  const ricci::Mesh& mesh = fitted.surface.domain;
  double total_area = 0.0;
  for (auto f : mesh.faces()) total_area += area_vector(mesh, f.idx()).norm() / 2;
  nlohmann::json patches = nlohmann::json::array();
  for (const auto& fill : fitted.surface.fills) {
    const auto& faces = fill.rim.covered_faces;
    const HoleShape shape = hole_shape(mesh, faces);
    const auto& jumps = fill.edge_normal_jump_deg;
    const auto flipped =
        std::count_if(jumps.begin(), jumps.end(), [](double d) { return d > 90.0; });
    nlohmann::json worst = nullptr;
    if (!jumps.empty() && jumps.size() == fill.rim.edges.size()) {
      const auto j = std::max_element(jumps.begin(), jumps.end()) - jumps.begin();
      const int v = spline::rim_vertices(fill.rim, mesh)[static_cast<std::size_t>(j)];
      const Eigen::Vector3d p = ricci::to_eigen(mesh.point(mesh.vertex_handle(v)));
      worst = {p.x(), p.y(), p.z()};
    }
    patches.push_back(
        {{"kind", spline::rim_kind_id(fill.rim.kind)},
         {"covered_faces", faces.size()},
         {"rim_edges", fill.rim.edges.size()},
         {"area_fraction", total_area > 0.0 ? shape.area / total_area : 0.0},
         {"extent_relative", faces.empty() ? 0.0 : shape.box.diagonal().norm() / diag},
         {"normal_spread_deg", shape.normal_spread_deg},
         {"g1", fill.g1},
         {"max_normal_jump_deg", fill.max_normal_jump_deg},
         {"rim_edges_over_90_deg", flipped},
         {"worst_rim_point", worst}});
  }
  return patches;
}

nlohmann::json stage_seconds_json(const spline::StageSeconds& stages) {
  nlohmann::json seconds = nlohmann::json::object();
  for (const auto& [name, s] : stages) seconds[name] = s;
  return seconds;
}

nlohmann::json tessellation_json(const spline::FittedSurface& fitted) {
  const auto& t = fitted.topology;
  return {{"density", fitted.tessellation.density},
          {"turn_splits", fitted.tessellation.turn_splits},
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

nlohmann::json point_json(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// Relative to the input's diagonal; a negative figure (nothing to measure) stays -1.
double relative(double x, double diag) { return x < 0.0 ? -1.0 : x / diag; }

// The boundary of the output against the input's (Hausdorff both ways; the small holes capped
// before the fit left out and counted), the ghost collar and how the domain's boundary was made
// to follow the scan's.
nlohmann::json boundary_json(const spline::FittedSurface& fitted, double diag) {
  const auto& f = fitted.boundary_follow;
  const auto& d = fitted.delivered;
  const auto ghosts = std::count(fitted.collar_faces.begin(), fitted.collar_faces.end(), 1);
  return {{"input_boundary_edges", d.scan_boundary_edges},
          {"input_boundary_edges_left_out", d.scan_boundary_edges_left_out},
          {"capped_holes", fitted.capped_holes},
          {"capped_hole_diameter_relative", fitted.capped_hole_diameter},
          {"surface_boundary_edges", d.surface_boundary_edges},
          {"hausdorff_relative", relative(d.boundary_hausdorff, diag)},
          {"surface_to_input_relative", relative(d.surface_boundary_to_scan_boundary, diag)},
          {"input_to_surface_relative", relative(d.scan_boundary_to_surface_boundary, diag)},
          {"hausdorff_point", point_json(d.boundary_hausdorff_point)},
          {"collar_faces", ghosts},
          {"collar_refused", fitted.collar_refused},
          {"boundary_curve_dropped", fitted.boundary_curve_dropped},
          {"follow_splits", f.splits},
          {"follow_loops_rebuilt", f.loops_rebuilt},
          {"follow_distance_before_relative", f.distance_before},
          {"follow_distance_after_relative", f.distance_after}};
}

// Points of the delivered surface back to the input, and the share of the input it reaches.
nlohmann::json surface_to_scan_json(const spline::ScanDistanceReport& d, double diag) {
  nlohmann::json out = {{"points", d.surface_points},
                        {"points_left_out", d.surface_points_left_out},
                        {"p99_relative", d.surface_to_scan_p99 / diag},
                        {"max_relative", d.surface_to_scan_max / diag},
                        {"max_point", point_json(d.surface_to_scan_max_point)}};
  if (d.surface_points_left_out > 0)
    out["left_out_because"] = "on patches capping the input's boundary loops (--fill-boundaries)";
  return out;
}

// Where the surface folds: the midpoints of the first fold edges (all of them are counted in
// surface_dihedral.edges_over_90_deg).
nlohmann::json folds_json(const spline::FittedSurface& fitted, double diag) {
  constexpr std::size_t kListed = 50;
  const auto& edges = fitted.surface_dihedral.fold_edges;
  const auto& x = fitted.tessellation.positions;
  nlohmann::json points = nlohmann::json::array();
  for (std::size_t i = 0; i < std::min(edges.size(), kListed); ++i) {
    const Eigen::Vector3d mid = 0.5 * (x.row(edges[i][0]) + x.row(edges[i][1])).transpose();
    points.push_back(point_json(mid));
  }
  // Folds on the fill patches (both ends on a patch's triangles), on the spline next to the
  // cone and elsewhere on it (spline::surface_fold_places).
  const spline::SurfaceFoldPlaces where = spline::surface_fold_places(fitted);
  return {{"count", edges.size()},
          {"on_patches", where.places.on_patches},
          {"on_spline_near_cone", where.places.near_cone},
          {"on_spline_elsewhere", where.places.elsewhere},
          {"near_cone_radius_relative", where.near_cone_radius / diag},
          {"spline_cone_distance_median_relative", where.places.median_cone_distance / diag},
          {"listed", points.size()},
          {"points", points}};
}

// Every fit round: the first, then each refinement of the domain (the best one delivered).
nlohmann::json refinement_json(const spline::FittedSurface& fitted,
                               const spline::FitSurfaceOptions& options) {
  nlohmann::json rounds = nlohmann::json::array();
  for (const auto& r : fitted.refinement) {
    rounds.push_back({{"domain_faces", r.domain_faces},
                      {"control_points", r.control_points},
                      {"folds", r.folds},
                      {"projection_rms_relative", r.projection_rms / fitted.bbox_diagonal},
                      {"projection_max_relative", r.projection_max / fitted.bbox_diagonal},
                      {"vertices_over_tolerance", r.vertices_over_tolerance}});
    if (!r.error.empty()) rounds.back()["error"] = r.error;
  }
  return {{"max_rounds", options.refinement_rounds},
          {"fold_rounds", options.fold_rounds},
          {"tolerance_relative", options.tolerance},
          {"rms_goal_relative", options.rms_goal},
          {"fold_free_rms_relative", options.fold_free_rms},
          {"adaptive_domain",
           {{"on", fitted.domain_base_faces > 0},
            {"base_faces", fitted.domain_base_faces},
            {"split_faces", fitted.domain_split_faces}}},
          {"rounds", rounds}};
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
        {"added_faces", atlas.cone_refinement.added_faces},
        {"radial_splits", atlas.cone_refinement.radial_splits}}},
      {"metric", {{"route", atlas.flow.metric_name}, {"refused", atlas.flow.failed_attempts}}},
      {"tracked_parameters", !atlas.flip_record.empty()},
      {"control_points", space.function_count()},
      {"degree", space.degree()},
      {"fairness", options.fairness_order()},
      {"fairness_free_faces", fitted.fit_unconstrained_faces},
      {"cone_hole_reach_layers",
       spline::cone_hole_limits(fitted.input.genus, fitted.fit_unconstrained_faces > 0)
           .reach_layers},
      {"fit_rms", fitted.fit_rms},
      {"fit_max", fitted.fit_max},
      {"fit_rms_relative", fitted.fit_rms / diag},
      {"fit_max_relative", fitted.fit_max / diag},
      {"fit_points", fitted.fit_points},
      {"fit_max_point", point_json(fitted.delivered.fit_max_point)},
      {"surface_to_scan", surface_to_scan_json(fitted.delivered, diag)},
      {"coverage",
       {{"fraction", fitted.delivered.coverage},
        {"tolerance_relative", fitted.delivered.coverage_tolerance / diag}}},
      {"folds", folds_json(fitted, diag)},
      {"refinement", refinement_json(fitted, options)},
      {"projection",
       {{"rms_relative", fitted.projection_rms / diag},
        {"max_relative", fitted.projection_max / diag},
        {"points", fitted.projection_points},
        {"points_on_fills", fitted.fit_points_on_fills}}},
      {"bbox_diagonal", fitted.bbox_diagonal},
      {"seam_normal_jump_max_deg",
       std::max(fitted.edge_normal_jump_deg, fitted.fill_normal_jump_deg)},
      {"edge_normal_jump_max_deg", fitted.edge_normal_jump_deg},
      {"fill_normal_jump_max_deg", fitted.fill_normal_jump_deg},
      {"fill_position_gap_relative", fitted.fill_position_gap},
      {"filled_rims", fitted.surface.fills.size()},
      {"fill_patches", fill_patches_json(fitted, diag)},
      {"fill_failures", fitted.fill_failures},
      {"fit_points_on_fills", fitted.fit_points_on_fills},
      {"open_rims", fitted.surface.open_rims.size()},
      {"boundary_rims", fitted.boundary_rims},
      {"fallback_fills", fitted.fallback_fills},
      {"watertight", fitted.watertight},
      {"topology_mismatch", spline::topology_mismatch(fitted)},
      {"tessellation", tessellation_json(fitted)},
      {"surface_dihedral", dihedral_json(fitted.surface_dihedral)},
      {"boundary", boundary_json(fitted, diag)},
      {"fit_constraint_residual", fitted.fit_constraint_residual},
      {"seconds", stage_seconds_json(fitted.seconds)},
      {"cpu_seconds", stage_seconds_json(fitted.cpu_seconds)},
  };
}

}  // namespace msp
