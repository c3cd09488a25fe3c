#include "msp/report/ricci_reports.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include <ricci/hyperbolic/klein.h>

namespace msp {
namespace {

/// Genus as an integer when it is one (every 2-manifold), else the half-integer.
nlohmann::ordered_json genus_json(double genus) {
  if (genus == std::floor(genus)) return static_cast<long long>(genus);
  return genus;
}

nlohmann::json singularities_json(const ricci::OneConeAtlasResult& r) {
  nlohmann::json list = nlohmann::json::array();
  if (r.problem.cone >= 0) {
    double K = r.flow.curvature[r.problem.cone];
    list.push_back({{"vertex", r.chosen_vertex}, {"curvature", K}, {"cone_angle", 2 * M_PI - K}});
  } else if (r.problem.kind == ricci::OneConeKind::PuncturedSphere) {
    list.push_back({{"vertex", r.chosen_vertex}, {"removed_star", true}});
  }
  return list;
}

nlohmann::json complex_json(ricci::Complex z) { return {z.real(), z.imag()}; }

nlohmann::json generators_json(const ricci::Uniformization& u) {
  nlohmann::json list = nlohmann::json::array();
  for (size_t i = 0; i < u.group.generators.size(); ++i) {
    const ricci::Mobius& g = u.group.generators[i];
    nlohmann::json j;
    j["name"] = generator_name(i);
    j["theta"] = g.theta();
    j["exp_i_theta"] = complex_json(std::polar(1.0, g.theta()));
    if (u.geometry == ricci::Geometry::hyperbolic) {
      // z -> e^{i theta} (z - z0) / (1 - conj(z0) z)
      j["z0"] = complex_json(g.z0());
      const Eigen::Matrix3d l = ricci::lorentz_matrix(g);
      j["klein"] = {
          {l(0, 0), l(0, 1), l(0, 2)}, {l(1, 0), l(1, 1), l(1, 2)}, {l(2, 0), l(2, 1), l(2, 2)}};
      j["translation_length"] = 2.0 * std::acosh(std::max(1.0, 0.5 * std::abs(g.m.trace().real())));
    } else {
      // z -> e^{i theta} z + t (a translation on the flat torus)
      j["translation"] = complex_json(g(0.0));
    }
    j["word"] = u.group.basis.generators[i].size();
    list.push_back(j);
  }
  return list;
}

nlohmann::json linear_work_json(const ricci::LinearWork& w) {
  return {{"factorizations", w.factorizations},
          {"back_substitutions", w.back_substitutions},
          {"right_hand_sides", w.right_hand_sides},
          {"solves", w.solves()}};
}

}  // namespace

nlohmann::ordered_json mesh_info_json(const std::string& path, const ricci::MeshDiagnosis& d) {
  nlohmann::ordered_json problems = nlohmann::ordered_json::array();
  for (const auto& problem : d.problems) problems.push_back(problem.message);
  return {{"file", path},
          {"vertices", d.vertices},
          {"edges", d.edges},
          {"faces", d.faces},
          {"components", d.components},
          {"boundary_loops", d.boundary_loops},
          {"euler_characteristic", d.euler_characteristic},
          {"genus", genus_json(d.genus)},
          {"manifold", d.edge_manifold && d.vertex_manifold},
          {"edge_manifold", d.edge_manifold},
          {"vertex_manifold", d.vertex_manifold},
          {"orientable", d.orientable},
          {"consistently_oriented", d.consistently_oriented},
          {"clean_manifold", d.clean_manifold()},
          {"degenerate_faces", d.degenerate_faces},
          {"duplicate_vertices", d.duplicate_vertices},
          {"duplicate_faces", d.duplicate_faces},
          {"unreferenced_vertices", d.unreferenced_vertices},
          {"non_triangle_faces", d.non_triangle_faces},
          {"non_manifold_edges", d.non_manifold_edges},
          {"non_manifold_vertices", d.non_manifold_vertices},
          {"non_finite_vertices", d.non_finite_vertices},
          {"boundary_edges", d.boundary_edges},
          {"bbox_diagonal", d.bbox_diagonal},
          {"min_angle_deg", d.non_triangle_faces < d.faces ? nlohmann::ordered_json(d.min_angle_deg)
                                                           : nlohmann::ordered_json()},
          {"problems", problems}};
}
nlohmann::json flow_report_json(const std::string& path, const ricci::Mesh& mesh,
                                const ricci::FlowOptions& options,
                                const ricci::RoutedFlowResult& routed) {
  const ricci::FlowResult& result = routed.flow;
  nlohmann::json j;
  j["mesh"] = path;
  j["status"] = ricci::to_string(result.status);
  j["iterations"] = result.iterations;
  j["factorizations"] = result.factorizations;
  j["max_curvature_error"] = result.max_error;
  j["seconds"] = result.timings.total;
  j["vertices"] = mesh.n_vertices();
  j["faces"] = mesh.n_faces();
  j["geometry"] = ricci::to_string(options.geometry);
  j["metric"] = routed.metric;
  j["intrinsic_flips"] = routed.flips();
  j["failed_attempts"] = result.failed_attempts;
  j["method"] = ricci::to_string(options.method);
  j["solver"] = ricci::to_string(result.solver);
  j["error_history"] = result.error_history;
  j["timings"] = {{"setup", result.timings.setup},
                  {"evaluation", result.timings.evaluation},
                  {"assembly", result.timings.assembly},
                  {"analysis", result.timings.analysis},
                  {"factorization", result.timings.factorization},
                  {"solve", result.timings.solve}};
  if (!result.converged()) j["message"] = result.message;
  return j;
}

std::string polygon_word_text(const ricci::FundamentalPolygon& polygon) {
  std::string text;
  for (const auto& letter : polygon.word) {
    if (!text.empty()) text += " ";
    text += (letter.kind == ricci::PolygonLetter::Kind::loop ? "a" : "b") +
            std::to_string(letter.index);
    if (letter.sign < 0) text += "^-1";
  }
  return text;
}

nlohmann::json atlas_report_json(const std::string& path, const ricci::Mesh& mesh,
                                 const ricci::OneConeAtlasResult& r) {
  return atlas_report_json(path, mesh.n_vertices(), mesh.n_faces(), r);
}

nlohmann::json atlas_report_json(const std::string& path, size_t vertices, size_t faces,
                                 const ricci::OneConeAtlasResult& r) {
  const auto& t = r.timings;
  const auto& work = r.linear_work;
  return {{"mesh", path},
          {"vertices", vertices},
          {"faces", faces},
          {"genus", r.problem.genus},
          {"boundary_loops", r.problem.boundary_loops},
          {"kind", ricci::to_string(r.problem.kind)},
          {"singularities", singularities_json(r)},
          {"valence_splits", r.problem.valence_splits},
          {"subdivisions", r.problem.subdivisions},
          {"polish_error_before", r.polish.error_before},
          {"polish_error_after", r.polish.error_after},
          {"polish_iterations", r.polish.iterations},
          {"polished", r.polished},
          {"flows_for_choice", r.flows_for_choice},
          {"solves_for_choice", r.solves_for_choice},
          {"linear_solves", work.total().solves()},
          {"linear_work",
           {{"choice", linear_work_json(work.choice)},
            {"flow", linear_work_json(work.flow)},
            {"polish", linear_work_json(work.polish)},
            {"total", linear_work_json(work.total())}}},
          {"newton_iterations", r.flow.iterations},
          {"metric", r.intrinsic ? "intrinsic-delaunay" : ricci::to_string(r.flow.metric.scheme)},
          {"intrinsic_flips", r.intrinsic_flips},
          {"removed_edges", r.removed_edges},
          {"failed_metrics", r.flow.failed_attempts},
          {"metric_route", r.flow.metric_name},
          {"quasi_conformal_area_mean", r.distortion.quasi_conformal_area_mean},
          {"max_curvature_error", r.flow.max_error},
          {"transition_residual", r.relative_transition_residual()},
          {"transition_residual_absolute",
           std::max(r.atlas.max_transition_residual, r.atlas.max_side_pairing_residual)},
          {"transition_pieces_unresolved", r.atlas.unresolved_transition_pieces},
          {"transition_residual_unresolved",
           r.atlas.max_unresolved_transition_residual /
               std::max(r.atlas.domain_diameter, 1e-300)},
          {"flipped_faces", r.atlas.layout.flipped_faces},
          {"layout_length_error", r.atlas.layout.max_relative_length_error},
          {"domain_length_error", r.atlas.domain_max_relative_length_error},
          {"domain_length_error_absolute",
           r.atlas.domain_diameter > 0
               ? r.atlas.domain_max_absolute_length_error / r.atlas.domain_diameter
               : 0.0},
          {"max_vertex_angle", r.atlas.layout.max_vertex_angle},
          {"relator_residual",
           r.atlas.relator_holonomy_translation / std::max(r.atlas.domain_diameter, 1e-300)},
          {"charts", r.atlas.charts.size()},
          {"uncovered_faces", r.atlas.uncovered_faces},
          {"polygon_word", polygon_word_text(r.atlas.polygon)},
          {"canonical_word", r.atlas.polygon.canonical},
          {"area_distortion", r.distortion.area_distortion},
          {"angle_ratio_p05", r.distortion.angle_ratio_p05},
          {"angle_ratio_p50", r.distortion.angle_ratio_p50},
          {"angle_ratio_p95", r.distortion.angle_ratio_p95},
          {"quasi_conformal_mean", r.distortion.quasi_conformal_mean},
          {"quasi_conformal_max", r.distortion.quasi_conformal_max},
          {"distortion_faces", r.distortion.faces},
          {"distortion_skipped_faces", r.distortion.skipped_faces},
          {"seconds", t.total},
          {"stage_seconds",
           {{"choice", t.choice},
            {"valence", t.valence},
            {"flow", t.flow},
            {"polish", t.polish},
            {"atlas", t.atlas},
            {"distortion", t.distortion}}},
          {"cpu_seconds", t.cpu_total},
          {"cpu_stage_seconds",
           {{"choice", t.cpu_choice},
            {"valence", t.cpu_valence},
            {"flow", t.cpu_flow},
            {"polish", t.cpu_polish},
            {"atlas", t.cpu_atlas},
            {"distortion", t.cpu_distortion}}}};
}

std::string generator_name(size_t i) {
  return std::string(i % 2 == 0 ? "a" : "b") + std::to_string(i / 2 + 1);
}

nlohmann::json uniformize_report_json(const std::string& path, const ricci::Mesh& mesh,
                                      const ricci::Uniformization& u) {
  nlohmann::json j;
  j["mesh"] = path;
  j["vertices"] = mesh.n_vertices();
  j["faces"] = mesh.n_faces();
  j["geometry"] = ricci::to_string(u.geometry);
  j["genus"] = u.genus;
  j["double_cover"] = u.doubled;
  j["metric"] = ricci::to_string(u.flow.metric.scheme);
  j["iterations"] = u.flow.iterations;
  j["max_curvature_error"] = u.flow.max_error;
  j["generators"] = generators_json(u);
  j["relation_residual"] = u.group.relation_residual;
  j["seconds"] = u.timings.total;
  j["timings"] = {{"double_cover", u.timings.double_cover},
                  {"flow", u.timings.flow},
                  {"cut", u.timings.cut},
                  {"layout", u.timings.layout},
                  {"polish", u.timings.polish},
                  {"group", u.timings.group}};
  if (u.geometry == ricci::Geometry::spherical) {
    j["sphere"] = {{"max_radius_error", u.sphere.max_radius_error},
                   {"flipped_faces", u.sphere.flipped_faces},
                   {"centroid_norm", u.sphere.centroid_norm}};
  } else {
    j["polygon_residual"] = u.group.polygon_residual;
    j["relation_residual_direct"] = u.group.relation_residual_direct;
    j["cycle_residual"] = u.group.cycle_residual;
    j["side_spread"] = u.pairings.max_spread;
    if (u.geometry == ricci::Geometry::hyperbolic) {
      j["polish"] = {{"curvature_error_before", u.polish.error_before},
                     {"curvature_error_after", u.polish.error_after},
                     {"iterations", u.polish.iterations}};
    }
    j["sides"] = 2 * u.pairings.arcs.size();
    j["root"] = u.cut.root.idx();
    j["layout"] = {{"seed_face", u.layout.seed_face},
                   {"flipped_faces", u.layout.flipped_faces},
                   {"max_relative_length_error", u.layout.max_relative_length_error},
                   {"max_radius", u.layout.max_radius}};
  }
  if (u.geometry == ricci::Geometry::euclidean) {
    j["modulus"] = complex_json(u.modulus);
    j["reduced_modulus"] = complex_json(u.reduced_modulus);
  }
  return j;
}

}  // namespace msp
