#include "ricci/hyperbolic/uniformize.h"

#include <cmath>

#include "ricci/layout/layout_e2.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/primitives.h"
#include "ricci/topology/double_cover.h"
#include "ricci/util/stopwatch.h"

namespace ricci {
namespace {

Geometry geometry_of_genus(int genus) {
  return genus == 0 ? Geometry::spherical
                    : (genus == 1 ? Geometry::euclidean : Geometry::hyperbolic);
}

/// The flat torus: translations of the canonical generators and the modulus.
void torus_modulus(Uniformization& u) {
  for (const Mobius& g : u.group.generators) u.translations.push_back(g(0.0));
  if (u.translations.size() != 2) return;
  Complex tau = u.translations[1] / u.translations[0];
  if (tau.imag() < 0) tau = u.translations[0] / u.translations[1];
  u.modulus = tau;
  u.reduced_modulus = reduce_modulus(tau);
}

/// Cut at `root`, slice, lay out the disk (H2: from the polished lengths in u.polish, or E2)
/// and build the holonomy group; the stages' seconds are added to u.timings.
void build_domain(Uniformization& u, const UniformizeOptions& options, int root) {
  Stopwatch t;
  u.cut = compute_cut_graph(u.surface, VertexHandle(root), u.flow.lengths);
  u.sliced = slice_along(u.surface, u.cut.is_cut_edge);
  check_disk(u.sliced, "uniformize");
  u.timings.cut += t.seconds();
  t.restart();
  const Eigen::VectorXd lengths = sliced_edge_lengths(u.sliced, u.flow.lengths);
  if (u.geometry == Geometry::hyperbolic) {
    // The flow's metric in quad precision (see polish_h2.h), carried onto the sliced edges.
    LengthsQ precise(u.sliced.mesh.n_edges());
    for (auto e : u.sliced.mesh.edges()) {
      const auto original = u.sliced.to_original_edge[static_cast<size_t>(e.idx())];
      precise[static_cast<size_t>(e.idx())] = u.polish.quad_lengths[static_cast<size_t>(original)];
    }
    u.layout = layout_h2(u.sliced.mesh, precise, {options.seed_face});
    u.positions = u.layout.positions;
  } else {
    LayoutE2Options e2;
    e2.seed_face = options.seed_face;
    const LayoutE2Result flat = layout_e2(u.sliced.mesh, lengths, e2);
    u.positions.resize(flat.positions.rows());
    for (Eigen::Index i = 0; i < flat.positions.rows(); ++i) {
      u.positions[i] = Complex(flat.positions(i, 0), flat.positions(i, 1));
    }
    u.layout.seed_face = flat.seed_face;
    u.layout.min_signed_area = flat.min_signed_area;
    u.layout.flipped_faces = flat.flipped_faces;
    u.layout.max_relative_length_error = flat.max_relative_length_error;
    u.layout.max_radius = u.positions.cwiseAbs().maxCoeff();
  }
  u.timings.layout += t.seconds();
  t.restart();
  if (u.geometry == Geometry::hyperbolic) {
    u.pairings = domain_pairings(u.surface, u.cut, u.sliced, u.positions, u.geometry,
                                 u.layout.precise_positions, u.layout.quad_positions);
    u.group = holonomy_group(u.surface, u.cut, u.sliced, u.pairings, u.positions);
  } else {
    // Translations carry the unit of length; the residuals are taken on the domain scaled to
    // unit size (scale-free), then the maps are conjugated back to the mesh's units.
    const double size = std::max(u.positions.cwiseAbs().maxCoeff(), 1e-300);
    u.pairings = domain_pairings(u.surface, u.cut, u.sliced, u.positions / size, u.geometry);
    // Frame centres are disk isometries: in the plane the residual is taken as it is.
    u.group = holonomy_group(u.surface, u.cut, u.sliced, u.pairings);
    const Mobius to_mesh = Mobius::from_matrix(Eigen::Vector2cd(size, 1.0).asDiagonal());
    auto back = [&](Mobius& m) { m = to_mesh * m * to_mesh.inverse(); };
    for (Mobius& m : u.pairings.edge_pairing) back(m);
    for (CutArc& a : u.pairings.arcs) {
      back(a.pairing);
      a.precise_pairing = MobiusL(to_mesh) * a.precise_pairing * MobiusL(to_mesh.inverse());
      a.quad_pairing =
          MobiusQ(MobiusL(to_mesh)) * a.quad_pairing * MobiusQ(MobiusL(to_mesh.inverse()));
    }
    for (Mobius& m : u.group.loop_holonomy) back(m);
    for (Mobius& m : u.group.generators) back(m);
    torus_modulus(u);
  }
  u.timings.group += t.seconds();
}

/// The domain and group from options.root_vertex, or from the central vertex and, while the
/// relation residual stays above options.retry_relation_above (H2), from other roots spread over
/// the surface, the smallest residual kept: which root keeps the relator's partial products
/// small is not seen before the layout (casting, genus 9: 4e-9 from the central vertex, 1e-20
/// to 4e-10 from others).
void build_domain_from_best_root(Uniformization& u, const UniformizeOptions& options) {
  const int last = static_cast<int>(u.surface.n_vertices()) - 1;
  if (options.root_vertex >= 0) return build_domain(u, options, std::min(options.root_vertex, last));
  const VertexHandle centre = central_vertex(u.surface, u.flow.lengths);
  build_domain(u, options, centre.idx());
  if (u.geometry != Geometry::hyperbolic || !(u.group.relation_residual > options.retry_relation_above)) {
    return;
  }
  const Stopwatch t;
  const std::vector<VertexHandle> roots =
      spread_vertices(u.surface, centre, u.flow.lengths, options.root_retries + 1);
  u.timings.cut += t.seconds();
  for (size_t k = 1; k < roots.size(); ++k) {
    Uniformization attempt = u;
    build_domain(attempt, options, roots[k].idx());
    u.timings = attempt.timings;
    ++u.root_attempts;
    if (attempt.group.relation_residual < u.group.relation_residual) {
      const int attempts = u.root_attempts;
      u = std::move(attempt);
      u.root_attempts = attempts;
    }
    if (!(u.group.relation_residual > options.retry_relation_above)) break;
  }
}

}  // namespace

Complex reduce_modulus(Complex tau) {
  for (int it = 0; it < 100; ++it) {
    tau -= std::round(tau.real());
    if (std::norm(tau) >= 1.0 - 1e-15) break;
    tau = -1.0 / tau;
  }
  return tau;
}

Uniformization uniformize(const Mesh& mesh, const UniformizeOptions& options) {
  const Stopwatch start;
  Uniformization u;
  const SurfaceTopology topology = surface_topology(mesh);
  if (!topology.manifold) throw TopologyError("uniformize: the mesh is not a 2-manifold");
  if (topology.components != 1) {
    throw TopologyError("uniformize: the mesh has " + std::to_string(topology.components) +
                        " components (one expected)");
  }
  if (topology.boundary_loops > 0) {
    Stopwatch t;
    u.surface = double_cover(mesh).mesh;
    u.doubled = true;
    u.timings.double_cover = t.seconds();
    u.genus = 2 * topology.genus + topology.boundary_loops - 1;
  } else {
    u.surface = mesh;
    u.genus = topology.genus;
  }
  u.geometry = geometry_of_genus(u.genus);
  FlowOptions flow_options = options.flow;
  flow_options.geometry = u.geometry;
  Stopwatch t;
  u.flow = flow(u.surface, uniform_target(u.surface, u.geometry), flow_options);
  u.timings.flow = t.seconds();
  if (u.flow.converged()) {
    if (u.geometry == Geometry::spherical) {
      t.restart();
      SphereLayoutOptions s;
      s.seed_face = std::max(options.seed_face, 0);
      s.centre = options.centre_sphere;
      u.sphere = layout_sphere(u.surface, u.flow.lengths, s);
      u.timings.layout = t.seconds();
    } else {
      if (u.geometry == Geometry::hyperbolic) {
        // The flow's metric in quad precision (see polish_h2.h), for every root tried.
        const Stopwatch polish;
        u.polish = polish_h2_lengths(u.surface, u.flow.lengths, u.flow.target);
        u.timings.polish = polish.seconds();
      }
      build_domain_from_best_root(u, options);
    }
  }
  u.timings.total = start.seconds();
  return u;
}

}  // namespace ricci
