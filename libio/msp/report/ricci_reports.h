#pragma once
// The JSON reports of the libricci calls, under the keys `msp info --json`, `msp flow --json`,
// `msp atlas --json` and `msp uniformize --json` print; the Python binding returns the same.
#include <cstddef>
#include <string>

#include <ricci/flow/flow.h>
#include <ricci/hyperbolic/uniformize.h>
#include <ricci/intrinsic/routed_flow.h>
#include <ricci/mesh/diagnose.h>
#include <ricci/mesh/mesh.h>
#include <ricci/pipeline/one_cone_atlas.h>
#include <nlohmann/json.hpp>

namespace msp {

/// file, vertices, edges, faces, components, boundary_loops, euler_characteristic, genus (an
/// integer when it is one), manifold flags, defect counts, bbox_diagonal, min_angle_deg (null
/// without triangles), problems (messages), in that order. `path` names the input.
[[nodiscard]] nlohmann::ordered_json mesh_info_json(const std::string& path,
                                                    const ricci::MeshDiagnosis& diagnosis);

/// mesh, status, iterations, factorizations, max_curvature_error, seconds, vertices, faces,
/// geometry, metric (the route that ran: a scheme or intrinsic-delaunay), intrinsic_flips,
/// failed_attempts, method, solver, error_history, timings; message when the flow did not
/// converge.
[[nodiscard]] nlohmann::json flow_report_json(const std::string& path, const ricci::Mesh& mesh,
                                              const ricci::FlowOptions& options,
                                              const ricci::RoutedFlowResult& routed);

/// The fundamental polygon's boundary word, e.g. "a0 a1 a0^-1 a1^-1" (b: boundary loops).
[[nodiscard]] std::string polygon_word_text(const ricci::FundamentalPolygon& polygon);

/// mesh, counts, genus, kind, singularities, valence modification, polish, flow and atlas
/// residuals, polygon words, distortion, seconds and stage_seconds of a one-cone atlas.
[[nodiscard]] nlohmann::json atlas_report_json(const std::string& path, const ricci::Mesh& mesh,
                                               const ricci::OneConeAtlasResult& result);

/// The same report from the input's vertex and face counts, for an input handed over to the
/// pipeline (build_one_cone_atlas(Mesh&&)).
[[nodiscard]] nlohmann::json atlas_report_json(const std::string& path, size_t vertices,
                                               size_t faces,
                                               const ricci::OneConeAtlasResult& result);

/// "a1", "b1", "a2", ...: the name of canonical generator i.
[[nodiscard]] std::string generator_name(size_t i);

/// mesh, counts, geometry, genus, double_cover, flow figures, generators (name, theta, z0 and
/// Klein matrix in H2, translation on a torus), residuals, timings; sphere, layout or modulus
/// figures by geometry.
[[nodiscard]] nlohmann::json uniformize_report_json(const std::string& path,
                                                    const ricci::Mesh& mesh,
                                                    const ricci::Uniformization& u);

}  // namespace msp
