#pragma once
// Uniformization of a surface by the Ricci flow (discrete-surface-ricci-flow §V): every closed
// surface gets the constant-curvature metric conformal to its mesh (S2 for genus 0, E2 for
// genus 1, H2 for genus >= 2) and the geometric structure built on it: the embedding on the unit
// sphere, the flat torus with its two translations and modulus, or the Poincaré-disk fundamental
// domain with its Fuchsian group and real projective (Klein) transitions. An open surface is
// replaced by its double cover, so its boundary loops become geodesics.
#include <complex>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ricci/flow/flow.h"
#include "ricci/hyperbolic/fuchsian.h"
#include "ricci/hyperbolic/layout_h2.h"
#include "ricci/hyperbolic/polish_h2.h"
#include "ricci/spherical/sphere_layout.h"
#include "ricci/topology/cut_graph.h"
#include "ricci/topology/slice.h"

namespace ricci {

struct UniformizeOptions {
  /// Flow settings (geometry is chosen from the genus; fall-back to other metrics is on). The
  /// tolerance is tighter than the flow's default: a layout's closure error is the curvature
  /// error summed over the region it encloses, so 1e-10 per vertex would cost 1e-8 over a
  /// thousand vertices.
  FlowOptions flow = [] {
    FlowOptions o;
    o.fall_back_to_other_metrics = true;
    o.tolerance = 1e-12;
    return o;
  }();
  /// Root vertex of the cut graph (index in the closed surface; clamped to a valid vertex);
  /// -1 = central_vertex under the flow's metric, where the loops, and the words of the
  /// relator Π [a_i, b_i], are shortest (the relator sees each local defect amplified by e^d,
  /// d its distance from the root: 0.13 at root 0 of a chain of ten tori, 3e-12 at its centre).
  int root_vertex = -1;
  /// With the automatic root (H2): while the relation residual is above this, the domain is
  /// built again from up to root_retries other roots (farthest-point samples of the metric from
  /// the central vertex), and the smallest residual is kept.
  double retry_relation_above = 1e-12;
  int root_retries = 6;
  /// Seed face of the disk / plane / sphere layout; -1 = the most central face.
  int seed_face = -1;
  /// Normalise the S2 embedding so the vertex centroid is at 0 (a Möbius map of the sphere).
  bool centre_sphere = true;
};

/// Seconds per stage.
struct UniformizeTimings {
  /// cut, layout and group add up over the roots tried (UniformizeOptions::root_retries).
  double double_cover = 0, flow = 0, cut = 0, layout = 0, polish = 0, group = 0, total = 0;
};

struct Uniformization {
  Geometry geometry = Geometry::hyperbolic;
  /// The closed surface that was uniformized: the input, or its double cover (doubled = true).
  Mesh surface;
  bool doubled = false;
  int genus = 0;  ///< Of `surface`.
  FlowResult flow;
  /// E2/H2: the cut graph, the sliced disk and its layout (positions by sliced vertex, in the
  /// plane or the Poincaré disk).
  CutGraph cut;
  /// Other roots the domain was built from (UniformizeOptions::retry_relation_above).
  int root_attempts = 0;
  SlicedMesh sliced;
  Eigen::VectorXcd positions;
  /// H2: the flow's lengths polished in extended precision (what the disk layout uses), with
  /// the curvature error before and after.
  PolishH2Result polish;
  LayoutH2Result layout;  ///< Orientation and closure figures (H2; E2 fills the same fields).
  DomainPairings pairings;
  HolonomyGroup group;
  /// E2: the translations of the canonical generators and the modulus tau = t_b / t_a (taken in
  /// the upper half plane), and tau reduced to the SL(2, Z) fundamental domain.
  std::vector<Complex> translations;
  Complex modulus{0, 0}, reduced_modulus{0, 0};
  /// S2: the embedding on the unit sphere.
  SphereLayoutResult sphere;
  UniformizeTimings timings;
  bool converged() const { return flow.converged(); }
};

/// Runs the flow and builds the structure. A flow that does not converge is returned as is
/// (converged() false, flow.message says why) without the later stages.
/// \throw TopologyError for a non-manifold or disconnected mesh, or an open surface whose double
///        cannot be built; InvalidInputError for degenerate faces.
[[nodiscard]] Uniformization uniformize(const Mesh& mesh, const UniformizeOptions& options = {});

/// tau moved into |Re tau| <= 1/2, |tau| >= 1 by tau -> tau + n and tau -> -1/tau.
/// \pre Im tau > 0.
[[nodiscard]] Complex reduce_modulus(Complex tau);

}  // namespace ricci
