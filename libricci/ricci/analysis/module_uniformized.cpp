// Conformal modules read off the uniformization: the flat torus's reduced modulus, the Fuchsian
// generators' translation lengths, and the hyperbolic boundary lengths of an open surface.
#include <algorithm>
#include <cmath>
#include <functional>

#include "ricci/analysis/module_internal.h"
#include "ricci/hyperbolic/uniformize.h"
#include "ricci/hyperbolic/layout_h2.h"
#include "ricci/mesh/errors.h"
#include "ricci/topology/cut_graph.h"
#include "ricci/topology/slice.h"

namespace ricci::detail {

void uniformized_module(const Mesh& mesh, const ModuleOptions& options, ModuleResult& result) {
  UniformizeOptions uniformize_options;
  uniformize_options.flow = options.flow;
  // The layouts' closure needs the uniformize default's tighter tolerance.
  uniformize_options.flow.tolerance = std::min(options.flow.tolerance, 1e-12);
  const Uniformization u = uniformize(mesh, uniformize_options);
  record_flow(u.flow, options, result);
  if (!u.converged()) return;
  const Eigen::Index n = u.positions.size();
  CanonicalDomain& domain = result.domain;
  domain.positions.resize(n, 2);
  copy_faces(u.sliced.mesh, domain);
  if (result.kind == ModuleKind::FlatTorus) {
    result.values = {u.reduced_modulus.real(), u.reduced_modulus.imag()};
    result.names = {"re_tau", "im_tau"};
    // The parallelogram of the first translation = 1.
    const Complex frame = u.translations.empty() ? Complex(1) : 1.0 / u.translations[0];
    for (Eigen::Index v = 0; v < n; ++v) {
      const Complex z = u.positions[v] * frame;
      domain.positions.row(v) << z.real(), z.imag();
    }
    return;
  }
  result.invariant = false;
  for (size_t i = 0; i < u.group.generators.size(); ++i) {
    const double trace = std::abs(u.group.generators[i].m.trace().real());
    result.values.push_back(2.0 * std::acosh(std::max(1.0, 0.5 * trace)));
    result.names.push_back(std::string(i % 2 == 0 ? "a" : "b") + std::to_string(i / 2 + 1));
  }
  for (Eigen::Index v = 0; v < n; ++v) {
    domain.positions.row(v) << u.positions[v].real(), u.positions[v].imag();
  }
}

void hyperbolic_module(const Mesh& mesh, const MeshTables& tables, const ModuleOptions& options,
                       ModuleResult& result) {
  FlowOptions flow_options = options.flow;
  flow_options.geometry = Geometry::Hyperbolic;
  Targets targets;
  targets.curvature = Eigen::VectorXd::Zero(tables.num_vertices());
  const FlowResult flow_result = flow(mesh, targets, flow_options);
  record_flow(flow_result, options, result);
  std::vector<double> lengths;
  for (const std::vector<int>& loop : tables.boundary_loops) {
    double length = 0;
    for (size_t i = 0; i < loop.size(); ++i) {
      const HalfedgeHandle h = mesh.find_halfedge(mesh.vertex_handle(loop[i]),
                                                  mesh.vertex_handle(loop[(i + 1) % loop.size()]));
      length += flow_result.lengths[mesh.edge_handle(h).idx()];
    }
    lengths.push_back(length);
  }
  std::sort(lengths.begin(), lengths.end(), std::greater<double>());
  result.values = lengths;
  for (size_t i = 0; i < lengths.size(); ++i) result.names.push_back("length_" + std::to_string(i));
  if (!result.converged) return;
  // The picture: the surface cut to a disk along tree paths from a root to every loop (and
  // along 2g loops with genus), laid out in the Poincaré disk; its boundaries are geodesic arcs.
  const int root = tables.boundary_loops[0][0];
  const CutGraph cut = compute_cut_graph(mesh, mesh.vertex_handle(root), flow_result.lengths);
  const SlicedMesh sliced = slice_along(mesh, cut.is_cut_edge);
  check_disk(sliced, "hyperbolic slice");
  const LayoutH2Result layout =
      layout_h2(sliced.mesh, sliced_edge_lengths(sliced, flow_result.lengths));
  CanonicalDomain& domain = result.domain;
  const int n = static_cast<int>(sliced.mesh.n_vertices());
  domain.positions.resize(n, 2);
  for (int v = 0; v < n; ++v) {
    domain.positions.row(v) << layout.positions[v].real(), layout.positions[v].imag();
  }
  copy_faces(sliced.mesh, domain);
  // Every copy of each boundary edge, as two-point polylines, by loop.
  std::vector<int> loop_of(tables.num_vertices(), -1);
  for (size_t k = 0; k < tables.boundary_loops.size(); ++k) {
    for (int v : tables.boundary_loops[k]) loop_of[v] = static_cast<int>(k);
  }
  for (HalfedgeHandle h : sliced.mesh.halfedges()) {
    if (!sliced.mesh.is_boundary(h)) continue;
    const int a = sliced.mesh.from_vertex_handle(h).idx();
    const int b = sliced.mesh.to_vertex_handle(h).idx();
    const int original = sliced.to_original_halfedge[h.idx()];
    if (original < 0 || !mesh.is_boundary(mesh.halfedge_handle(original))) continue;
    domain.boundaries.push_back({a, b});
    domain.boundary_loop.push_back(loop_of[sliced.to_original_vertex[a]]);
  }
}

}  // namespace ricci::detail
