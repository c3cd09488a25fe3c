// Conformal modules by the Ricci flow: dispatch on topology, the annulus (Algorithm 4) and the
// rectangle of a disk with four corners. The closed and hyperbolic modules are in
// module_uniformized.cpp.
#include "ricci/analysis/conformal_module.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <limits>
#include <queue>

#include "ricci/analysis/module_internal.h"
#include "ricci/layout/layout_e2.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/flat_flips.h"
#include "ricci/mesh/primitives.h"
#include "ricci/mesh/simplify.h"
#include "ricci/metric/mesh_tables.h"
#include "ricci/topology/double_cover.h"
#include "ricci/topology/slice.h"

namespace ricci {

std::string to_string(ModuleKind kind) {
  switch (kind) {
    case ModuleKind::Sphere: return "sphere";
    case ModuleKind::Annulus: return "annulus";
    case ModuleKind::Rectangle: return "rectangle";
    case ModuleKind::FlatTorus: return "flat-torus";
    case ModuleKind::CircleDomain: return "circle-domain";
    case ModuleKind::Hyperbolic: return "hyperbolic";
    case ModuleKind::Disk: return "disk";
    default: return "fuchsian";
  }
}

bool parse_module_kind(const std::string& name, ModuleKind& kind) {
  if (name == "auto") return false;
  for (ModuleKind k : {ModuleKind::Sphere, ModuleKind::Annulus, ModuleKind::Rectangle,
                       ModuleKind::FlatTorus, ModuleKind::CircleDomain, ModuleKind::Hyperbolic,
                       ModuleKind::Fuchsian, ModuleKind::Disk}) {
    if (name == to_string(k)) {
      kind = k;
      return true;
    }
  }
  throw InvalidInputError("unknown module kind '" + name +
                          "' (auto, annulus, rectangle, flat-torus, circle-domain, hyperbolic, "
                          "fuchsian)");
}

namespace detail {

void record_flow(const FlowResult& flow, const ModuleOptions& options, ModuleResult& result) {
  const bool floor = flow.status == FlowStatus::stalled && flow.max_error < options.accepted_error;
  result.converged = flow.converged() || floor;
  result.flow_iterations = flow.iterations;
  result.flow_error = flow.max_error;
  result.message = flow.message;
}

void copy_faces(const Mesh& mesh, CanonicalDomain& domain) {
  domain.faces.resize(static_cast<Eigen::Index>(mesh.n_faces()), 3);
  for (FaceHandle f : mesh.faces()) {
    int k = 0;
    for (VertexHandle v : mesh.fv_range(f)) domain.faces(f.idx(), k++) = v.idx();
  }
}

}  // namespace detail

namespace {

using Clock = std::chrono::steady_clock;

/// The single boundary loop run with the surface on its left (counter-clockwise in a planar
/// layout); MeshTables lists the face-less halfedges' order, the other way round.
std::vector<int> ccw_boundary(const MeshTables& tables) {
  std::vector<int> loop(tables.boundary_loops[0].rbegin(), tables.boundary_loops[0].rend());
  return loop;
}

/// Position of each vertex in `loop`, -1 elsewhere.
std::vector<int> loop_positions(const std::vector<int>& loop, int vertex_count) {
  std::vector<int> position(vertex_count, -1);
  for (size_t i = 0; i < loop.size(); ++i) position[loop[i]] = static_cast<int>(i);
  return position;
}

/// Four vertices a quarter of the boundary's 3D length apart, from the lowest-index one.
std::vector<int> default_corners(const Mesh& mesh, std::vector<int> loop) {
  if (loop.size() < 4) throw InvalidInputError("the boundary has fewer than four vertices");
  std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
  std::vector<double> arc(loop.size() + 1, 0.0);
  for (size_t i = 0; i < loop.size(); ++i) {
    const auto a = mesh.point(mesh.vertex_handle(loop[i]));
    const auto b = mesh.point(mesh.vertex_handle(loop[(i + 1) % loop.size()]));
    arc[i + 1] = arc[i] + (a - b).norm();
  }
  std::vector<int> corners;
  size_t i = 0;
  for (size_t k = 0; k < 4; ++k) {
    while (arc[i] < 0.25 * static_cast<double>(k) * arc.back()) ++i;
    i = std::min(i, loop.size() - (4 - k));  // leave room for the corners still to come
    corners.push_back(loop[i++]);
  }
  return corners;
}

/// The corners in the boundary's cyclic order from corner 0. \throw InvalidInputError.
std::vector<int> checked_corners(const Mesh& mesh, const std::vector<int>& loop,
                                 const std::vector<int>& given) {
  if (given.empty()) return default_corners(mesh, loop);
  if (given.size() != 4) {
    throw InvalidInputError("the rectangle module needs exactly four corner vertices, got " +
                            std::to_string(given.size()));
  }
  const int n = static_cast<int>(mesh.n_vertices());
  const std::vector<int> position = loop_positions(loop, n);
  for (int c : given) {
    if (c < 0 || c >= n) {
      throw InvalidInputError("corner vertex " + std::to_string(c) + " is out of range [0, " +
                              std::to_string(n) + ")");
    }
    if (position[c] < 0) {
      throw InvalidInputError("corner vertex " + std::to_string(c) + " is not on the boundary");
    }
  }
  std::vector<int> corners = given;
  const int loop_size = static_cast<int>(loop.size());
  const auto key = [&](int c) {
    return (position[c] - position[given[0]] + loop_size) % loop_size;
  };
  std::sort(corners.begin(), corners.end(), [&](int a, int b) { return key(a) < key(b); });
  if (std::adjacent_find(corners.begin(), corners.end()) != corners.end()) {
    throw InvalidInputError("the four corner vertices must be distinct");
  }
  return corners;
}

/// Genus 0, one boundary loop, four corners: the rectangle.
void rectangle_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                      ModuleResult& result) {
  const std::vector<int> loop = ccw_boundary(tables);
  result.corners = checked_corners(mesh, loop, options.corners);
  Targets targets;
  targets.curvature = Eigen::VectorXd::Zero(tables.num_vertices());
  for (int c : result.corners) targets.curvature[c] = 0.5 * M_PI;
  const FlowResult flow_result = flow(mesh, targets, options.flow);
  detail::record_flow(flow_result, options, result);
  const LayoutE2Result layout = layout_e2(mesh, flow_result.lengths);
  const auto at = [&](int v) { return Complex(layout.positions(v, 0), layout.positions(v, 1)); };
  Complex p[4];
  for (int k = 0; k < 4; ++k) p[k] = at(result.corners[k]);
  const double width = 0.5 * (std::abs(p[1] - p[0]) + std::abs(p[3] - p[2]));
  const double height = 0.5 * (std::abs(p[2] - p[1]) + std::abs(p[0] - p[3]));
  result.values = {height / width};
  result.names = {"aspect_ratio"};
  // Frame: corner 0 at 0, corner 1 at 1 (width 1).
  const Complex frame = std::abs(p[1] - p[0]) / (width * (p[1] - p[0]));
  const std::vector<int> position = loop_positions(loop, tables.num_vertices());
  const int loop_size = static_cast<int>(loop.size());
  result.roundness = 0;
  for (int k = 0; k < 4; ++k) {
    const Complex a = p[k], b = p[(k + 1) % 4];
    const Complex direction = (b - a) / std::abs(b - a);
    for (int i = position[result.corners[k]]; loop[i] != result.corners[(k + 1) % 4];
         i = (i + 1) % loop_size) {
      const double off = std::abs(((at(loop[i]) - a) / direction).imag()) / width;
      result.roundness = std::max(result.roundness, off);
    }
  }
  CanonicalDomain& domain = result.domain;
  domain.positions.resize(tables.num_vertices(), 2);
  for (int v = 0; v < tables.num_vertices(); ++v) {
    const Complex z = (at(v) - p[0]) * frame;
    domain.positions.row(v) << z.real(), z.imag();
  }
  detail::copy_faces(mesh, domain);
  domain.boundaries = {loop};
  domain.boundary_loop = {0};
  domain.corners = result.corners;
}

std::string topology_text(const SurfaceTopology& topology) {
  return "genus " + std::to_string(topology.genus) + " with " +
         std::to_string(topology.boundary_loops) + " boundary loop" +
         (topology.boundary_loops == 1 ? "" : "s");
}

/// The kind the topology gives.
ModuleKind natural_kind(const SurfaceTopology& t) {
  if (t.boundary_loops == 0) {
    return t.genus == 0 ? ModuleKind::Sphere
                        : (t.genus == 1 ? ModuleKind::FlatTorus : ModuleKind::Fuchsian);
  }
  if (t.genus == 0 && t.boundary_loops == 1) return ModuleKind::Rectangle;
  if (t.genus == 0 && t.boundary_loops == 2) return ModuleKind::Annulus;
  return t.genus == 0 ? ModuleKind::CircleDomain : ModuleKind::Hyperbolic;
}

/// \throw InvalidInputError when `kind` does not fit the topology.
void check_kind(ModuleKind kind, const SurfaceTopology& t) {
  const char* need = nullptr;
  switch (kind) {
    case ModuleKind::Sphere: need = "a closed genus-0 surface"; break;
    case ModuleKind::Annulus: need = "a genus-0 surface with two boundary loops"; break;
    case ModuleKind::Rectangle: need = "a genus-0 surface with one boundary loop"; break;
    case ModuleKind::FlatTorus: need = "a closed genus-1 surface"; break;
    case ModuleKind::CircleDomain:
      need = "a genus-0 surface with three or more boundary loops";
      break;
    case ModuleKind::Fuchsian: need = "a closed surface of genus 2 or more"; break;
    case ModuleKind::Disk: need = "a genus-0 surface with one boundary loop"; break;
    case ModuleKind::Hyperbolic:
      need = "an open surface of negative Euler characteristic (genus 0 with three or more "
             "boundary loops, or genus 1 or more with boundary)";
      break;
  }
  const bool hyperbolic_fits = t.boundary_loops > 0 && 2 - 2 * t.genus - t.boundary_loops < 0;
  const bool disk_fits = t.genus == 0 && t.boundary_loops == 1;
  if (kind != natural_kind(t) && !(kind == ModuleKind::Hyperbolic && hyperbolic_fits) &&
      !(kind == ModuleKind::Disk && disk_fits)) {
    throw InvalidInputError("the " + to_string(kind) + " module needs " + need + "; the mesh is " +
                            topology_text(t));
  }
}

}  // namespace

namespace {

/// The module of `mesh` as it is (topology already checked, `result` holds it).
void module_on(const Mesh& mesh, const ModuleOptions& options, ModuleResult& result) {
  result.faces_used = static_cast<int>(mesh.n_faces());
  const MeshTables tables = build_mesh_tables(mesh);
  switch (result.kind) {
    case ModuleKind::Sphere:
      result.converged = true;
      break;
    case ModuleKind::Annulus: detail::annulus_module(mesh, tables, options, result); break;
    case ModuleKind::Rectangle: rectangle_module(mesh, tables, options, result); break;
    case ModuleKind::FlatTorus:
    case ModuleKind::Fuchsian: detail::uniformized_module(mesh, options, result); break;
    case ModuleKind::CircleDomain:
      detail::circle_domain_module(mesh, tables, options, result);
      break;
    case ModuleKind::Hyperbolic: detail::hyperbolic_module(mesh, tables, options, result); break;
    case ModuleKind::Disk: detail::disk_module(mesh, tables, options, result); break;
  }
}

}  // namespace

ModuleResult conformal_module(const Mesh& mesh, const ModuleOptions& options) {
  const auto start = Clock::now();
  const SurfaceTopology topology = surface_topology(mesh);
  if (!topology.manifold) throw TopologyError("the mesh is not a 2-manifold");
  if (topology.components != 1) {
    throw TopologyError("the mesh has " + std::to_string(topology.components) +
                        " components; a conformal module needs one");
  }
  ModuleResult blank;
  blank.genus = topology.genus;
  blank.boundary_loops = topology.boundary_loops;
  blank.kind = natural_kind(topology);
  if (options.force_kind) {
    check_kind(options.kind, topology);
    blank.kind = options.kind;
  }
  if (blank.kind != ModuleKind::Disk && options.centre != -1) {
    throw InvalidInputError("a centre vertex is for the disk map; the module asked for is the " +
                            to_string(blank.kind));
  }
  if (blank.kind != ModuleKind::Rectangle && !options.corners.empty()) {
    throw InvalidInputError("corners are for the rectangle module of a disk; the mesh is " +
                            topology_text(topology));
  }
  ModuleResult result = blank;
  const bool intrinsic_first =
      options.intrinsic_circle_domain && blank.kind == ModuleKind::CircleDomain;
  if (!intrinsic_first) module_on(mesh, options, result);
  // Another triangulation helps a flow that broke triangles, not a circle domain that stays
  // out of round.
  const bool retry = options.retry && result.circle_iterations < options.max_circle_iterations;
  if (intrinsic_first || (!result.converged && retry && result.kind == ModuleKind::CircleDomain)) {
    // The same surface and vertices (interior edges between two boundary vertices split), its
    // flat metric by the flow with intrinsic Delaunay flips.
    const Mesh split = double_cover(mesh).original;
    const MeshTables tables = build_mesh_tables(split);
    result = blank;
    result.preparation = "intrinsic Delaunay";
    result.faces_used = static_cast<int>(split.n_faces());
    try {
      const auto metric = detail::intrinsic_flat_metric(split, tables, options.flow);
      detail::circle_domain_module(split, tables, options, result, metric.get());
    } catch (const SolverError& error) {
      result.converged = false;
      result.message = error.what();
    }
    if (intrinsic_first) {
      result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
      return result;
    }
  }
  if (!result.converged && retry) {
    Mesh flipped = mesh;
    if (flip_flat_edges_to_delaunay(flipped).flips > 0) {
      result = blank;
      result.preparation = "flat edges flipped";
      module_on(flipped, options, result);
    }
  }
  if (!result.converged && retry && options.corners.empty()) {
    SimplifyOptions remesh;
    remesh.target_faces = static_cast<int>(mesh.n_faces());
    const Mesh remeshed = simplify_mesh(mesh, remesh).mesh;
    result = blank;
    result.preparation = "remeshed";
    module_on(remeshed, options, result);
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

double module_distance(const ModuleResult& a, const ModuleResult& b) {
  if (a.kind != b.kind || a.values.size() != b.values.size()) {
    throw InvalidInputError("modules of different kinds (" + to_string(a.kind) + ", " +
                            std::to_string(a.values.size()) + " values; " + to_string(b.kind) +
                            ", " + std::to_string(b.values.size()) + " values) have no distance");
  }
  double sum = 0;
  for (size_t i = 0; i < a.values.size(); ++i) sum += std::pow(a.values[i] - b.values[i], 2);
  return std::sqrt(sum);
}

}  // namespace ricci
