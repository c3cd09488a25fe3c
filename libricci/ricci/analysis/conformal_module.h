#pragma once
// Conformal modules: the coordinates of a surface in its Teichmüller space, the "fingerprint"
// two conformally equivalent surfaces share (ricci-flow-3d-shape-analysis §5.1, Algorithms 4
// and 6; ALGORITHMS.md). Each is computed by the Ricci flow to a canonical domain:
//   annulus     genus 0, two boundaries: flat metric with geodesic boundaries, sliced along the
//               shortest path between them, laid out as a strip of period T and height H, and
//               carried by z = exp(2πi w / T) to the annulus r < |z| < 1; module
//               (1/2π) log(1/r) = H / |T| (Algorithm 4);
//   rectangle   genus 0, one boundary, four corner vertices: flat metric with geodesic curvature
//               π/2 at the corners and 0 elsewhere on the boundary; module = the rectangle's
//               height / width (the sides from corner 1 to 2 and 3 to 0 against 0 to 1, 2 to 3);
//   flat torus  genus 1, closed: the modulus τ of the flat torus reduced to the SL(2, Z)
//               fundamental domain |Re τ| <= 1/2, |τ| >= 1 (values Re τ, Im τ);
//   circle      genus 0, n + 1 >= 3 boundaries: the unit disk with n circular holes (the
//   domain      flat metric whose loops have constant geodesic curvature, by a fixed point of
//               the flow's boundary targets), boundaries ordered by 3D length (c0 the longest,
//               the unit circle), normalised by a Möbius map so that c1 is centred at 0 and
//               c2's centre lies on the positive real axis; module = (r1, x2, r2, x3, y3, r3,
//               ...) (Algorithm 7's answer, by another iteration);
//   hyperbolic  open surfaces with χ < 0 and genus >= 1 (or asked for, genus 0 with 3+
//               boundaries): the hyperbolic metric with geodesic boundaries; module = the
//               boundaries' hyperbolic lengths, longest first (Algorithm 6; complete for a
//               pair of pants, a partial invariant beyond);
//   fuchsian    genus >= 2, closed: the translation lengths 2 acosh(|tr|/2) of the canonical
//               Fuchsian generators a1 b1 ... of uniformize(). They are conformal invariants of
//               the marked surface only: another cut graph (basis) gives other numbers, so the
//               distance between such vectors is not a conformal invariant (`invariant` false).
//   disk        genus 0, one boundary, asked for: the conformal map onto the unit disk (flat
//               metric whose boundary has constant geodesic curvature, by the circle domain's
//               fixed point), the centre vertex at 0 and the boundary vertex nearest to it
//               (edge paths, 3D lengths) at 1. Every disk is conformal to the unit disk: no
//               values; the map is the answer (domain, roundness).
// A closed genus-0 surface has no module (every one is conformal to the sphere): kind Sphere,
// no values.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ricci/flow/flow.h"
#include "ricci/hyperbolic/mobius.h"
#include "ricci/mesh/mesh.h"

namespace ricci {

enum class ModuleKind {
  Sphere,
  Annulus,
  Rectangle,
  FlatTorus,
  CircleDomain,
  Hyperbolic,
  Fuchsian,
  Disk
};

/// "sphere", "annulus", "rectangle", "flat-torus", "circle-domain", "hyperbolic", "fuchsian",
/// "disk".
std::string to_string(ModuleKind kind);
/// The inverse of to_string, plus "auto" (returns false for it).
/// \throw InvalidInputError for an unknown name.
bool parse_module_kind(const std::string& name, ModuleKind& kind);

struct ModuleOptions {
  /// Flow settings. The modules need the metric conformal to the mesh, so there is no fall-back
  /// to the combinatorial metric; the tolerance is tight because the layout sums the curvature
  /// error over the domain.
  FlowOptions flow = [] {
    FlowOptions o;
    o.tolerance = 1e-11;
    return o;
  }();
  /// A flow that stalls at its rounding floor (large meshes in H2) is accepted when its
  /// max |K - K̄| is below this (radians).
  double accepted_error = 1e-7;
  /// Circle domain: the iteration stops when no boundary target changes by more than this
  /// (radians), or after max_circle_iterations flows.
  double circle_tolerance = 1e-9;
  int max_circle_iterations = 100;
  /// Circle domain: once the targets change by less than 1e-3, the domain is laid out after
  /// each flow, and the iteration stops when no normalised centre or radius moved by more than
  /// this since the last flow (the targets may keep sliding along the Möbius maps of the disk,
  /// which do not move the normalised module).
  double circle_module_tolerance = 1e-7;
  /// Circle domain: a result whose boundary vertices leave their fitted circles by more than
  /// this fraction of the radius is reported as not converged.
  double max_roundness = 0.05;
  /// Kind of module asked for; false = chosen from the topology (see the file comment).
  bool force_kind = false;
  ModuleKind kind = ModuleKind::Annulus;
  /// When the flow does not converge on the mesh as given (slivers put the inversive-distance
  /// metric against the triangle inequality): the circle domain by the intrinsic flow (see
  /// intrinsic_circle_domain), then again after Delaunay flips of the edges between
  /// coplanar faces (the surface unchanged), then, without given corners, on the mesh
  /// isotropically remeshed at the same face count (another triangulation of nearly the same
  /// surface). ModuleResult::preparation says which mesh the module is of.
  bool retry = true;
  /// Circle domain: the flat metric by the conformal flow with intrinsic Delaunay flips on the
  /// double cover (any conformal factor, where the fixed-connectivity flow breaks triangles),
  /// on the mesh with its interior edges between boundary vertices split; the domain is drawn
  /// through the flipped triangulation. false: only when the fixed-connectivity flow fails
  /// (with retry), before the other retries; preparation "intrinsic Delaunay" says so.
  bool intrinsic_circle_domain = false;
  /// Rectangle: four distinct boundary vertices (vertex indices). They are taken in the
  /// boundary's order with the surface on the left (counter-clockwise) from the first one
  /// given, so corners 0-1 and 2-3 span the width. Empty = four vertices a quarter of the
  /// boundary's 3D length apart, from the lowest-index boundary vertex.
  std::vector<int> corners;
  /// Disk: the interior vertex sent to 0; -1 = the interior vertex farthest from the boundary
  /// along edge paths (3D lengths).
  int centre = -1;
};

/// The canonical domain for pictures: the mesh sliced open and laid out (annulus in the unit
/// disk, rectangle of width 1, the flat torus's parallelogram with a = 1, the circle domain,
/// the Poincaré disk).
struct CanonicalDomain {
  Eigen::MatrixX3i faces;      ///< #F by 3, into positions.
  Eigen::MatrixX2d positions;  ///< By vertex of the sliced mesh.
  /// Boundary polylines (indices into positions; closed for the annulus and the rectangle,
  /// one per boundary edge in the Poincaré disk) and the boundary loop each belongs to.
  std::vector<std::vector<int>> boundaries;
  std::vector<int> boundary_loop;
  std::vector<int> corners;  ///< Rectangle corners (indices into positions).
};

struct ModuleResult {
  ModuleKind kind = ModuleKind::Sphere;
  int genus = 0;
  int boundary_loops = 0;
  /// The module as coordinates (the vector msp index compares), with a name for each:
  /// annulus {module}, rectangle {aspect_ratio}, flat torus {re_tau, im_tau}, circle domain
  /// {r1, x2, r2, x3, y3, r3, ...}, hyperbolic {length_0, ...}, fuchsian {a1, b1, ...}.
  std::vector<double> values;
  std::vector<std::string> names;
  /// False when equal surfaces may give different values (fuchsian: depends on the basis).
  bool invariant = true;
  /// Shape of the canonical domain: annulus, the largest deviation of a boundary vertex's
  /// log-radius from its loop's mean; rectangle, the largest distance of a boundary vertex from
  /// its side's line, over the width; circle domain, the largest |distance to the centre -
  /// radius| / radius of a boundary vertex; 0 for the others.
  double roundness = 0;
  /// The mesh the module was computed on: "as given", "intrinsic Delaunay" (the mesh's
  /// vertices, new ones appended where an interior edge joined two boundary vertices; `domain`
  /// is the flipped triangulation with a vertex where it crosses a loop), "flat edges flipped"
  /// (vertex indices kept) or "remeshed" (new vertices; `corners` and `domain` refer to them).
  std::string preparation = "as given";
  int faces_used = 0;  ///< Faces of that mesh.
  /// The mesh vertices of the rectangle's corners (or of the annulus's cut path ends; the
  /// disk's centre and the boundary vertex at 1).
  std::vector<int> corners;
  CanonicalDomain domain;
  /// The flow: converged or not (not converged: the values are a best effort), iterations,
  /// max |K - K̄|, the failure paragraph.
  bool converged = false;
  int circle_iterations = 0;  ///< Circle domain: flows run (one per target update).
  int flow_iterations = 0;
  double flow_error = 0;
  std::string message;
  double seconds = 0;  ///< Wall clock of the whole call.
};

/// The conformal module of a mesh (see the file comment).
/// \pre a connected oriented triangle 2-manifold without degenerate faces.
/// \throw InvalidInputError when the asked kind does not fit the topology, for bad corners
///        (not four, out of range, not on the boundary, repeated), or a centre vertex not asked
///        for the disk, out of range or on the boundary; TopologyError for a
///        non-manifold or disconnected mesh.
[[nodiscard]] ModuleResult conformal_module(const Mesh& mesh, const ModuleOptions& options = {});

/// Euclidean distance between two modules of the same kind and length (the paper's Fig. 14).
/// \throw InvalidInputError for different kinds or lengths.
[[nodiscard]] double module_distance(const ModuleResult& a, const ModuleResult& b);

}  // namespace ricci
