#pragma once
// Hole filling (manifold-splines paper, section 5: "we use planar triangular B-splines to fill
// these holes with G1 continuity along the boundaries"; ALGORITHMS.md section 7).
//
// A rim is a closed loop of domain edges with exactly one domain face: the cone's one-ring hole,
// an open scan's boundary loop, or the hole left by excluded faces. A rim is filled by a planar
// DMS spline patch P over a convex polygon D (the rim laid out on a circle by 3D arc length,
// clockwise in rim order so that P's normal agrees in orientation with the surface's). P's
// control points minimise
//   seam terms: |P - S|^2 and h^2 (n_S . dP/dx)^2, h^2 (n_S . dP/dy)^2 at samples of every rim
//               edge (position and tangent plane: G1), heavily weighted;
//   a weak cross-boundary term h^2 |dP/dnu - target|^2 (S's derivative across the rim edge,
//               continued by the per-edge similarity chart -> D), which keeps P regular;
//   the thin-plate energy of P (quadrature),
// with S the surrounding spline evaluated one-sided in the rim edge's domain face.
//
// Rim sample convention (the weld shared with the tessellator): rim edge j is sampled at d + 1
// points t_i = i / d, i = 0..d, linear in the barycentric coordinates of its domain face from the
// start vertex (t = 0) to the end vertex (t = 1): rim_edge_barycentric(edge, t). Sample (j, d) is
// the same surface point as sample (j + 1, 0).
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "ricci/mesh/mesh.h"
#include "spline/basis/planar_space.h"
#include "spline/knots/knot_cloud.h"
#include "spline/manifold/manifold_space.h"

namespace spline {

/// One rim edge: a domain face and its corner k opposite the edge (corner numbering of
/// manifold_space.h: corner k = to_vertex of the k-th halfedge of ricci::face_halfedges). The
/// edge runs from corner (k + 1) % 3 (start) to corner (k + 2) % 3 (end): the face's own
/// counter-clockwise direction, so the face is on the left and the hole on the right.
struct RimEdge {
  int face = -1;
  int corner = 0;
};

[[nodiscard]] inline int rim_edge_start_corner(const RimEdge& edge) { return (edge.corner + 1) % 3; }
[[nodiscard]] inline int rim_edge_end_corner(const RimEdge& edge) { return (edge.corner + 2) % 3; }

/// Barycentric coordinates (face corner order) of the point at t in [0, 1] of the rim edge:
/// (1 - t) at the start corner, t at the end corner, 0 at the opposite corner.
[[nodiscard]] Eigen::Vector3d rim_edge_barycentric(const RimEdge& edge, double t);

/// A closed loop of rim edges, chained: edges[j]'s end vertex is edges[j + 1]'s start vertex
/// (cyclically). Each edge has a kept domain face on its left and, on its right, a face the
/// patch replaces (covered_faces), a face outside the domain, or the mesh boundary.
struct Rim {
  enum class Kind {
    cone_hole,  ///< around the cone's one-ring (faces with atlas.in_domain == 0)
    boundary,   ///< along an open surface's boundary loop
    excluded,   ///< around faces the spline space excluded (excluded_faces()) only
  };
  std::vector<RimEdge> edges;
  Kind kind = Kind::cone_hole;
  /// Domain faces inside the rim that the patch replaces (ascending): the faces FindRimsOptions::
  /// grow added to the hole. A tessellation of the spline must skip them (and the faces outside
  /// the domain); the patch covers them.
  std::vector<int> covered_faces;
};

struct FindRimsOptions {
  /// Layers of domain faces added to every hole (all domain faces touching a rim vertex, per
  /// layer) before the rims are taken. Why: no basis function lives on the faces outside the
  /// domain, so the spline's partition of unity fails in a thin band along the domain's rim
  /// (measured on genus2.off at 1000 faces: sum of basis values 0.25-0.4 on the rim edges; the
  /// surface there collapses towards the origin) and within a cloud radius of the rim vertices.
  /// One layer puts every seam point more than a triangle height from the old rim vertices,
  /// beyond the clouds (radius < inradius / 2): the partition of unity holds on the seam
  /// (tested). 0: the rims are the domain's own (the cone's one-ring link, the boundary loops).
  int grow = 1;
};
/// Mesh vertex index of each rim edge's start vertex (so vertex j is shared by edges j - 1, j).
/// \pre `mesh` is the space's domain mesh.
[[nodiscard]] std::vector<int> rim_vertices(const Rim& rim, const ricci::Mesh& mesh);

/// Every rim: closed loops of edges with exactly one kept face (a domain face not covered, see
/// FindRimsOptions::grow). Cone holes first, then boundary loops, then excluded-face holes;
/// within a kind by smallest face index. A vertex where the kept region touches itself is passed
/// through by turning to the first rim edge around it, so loops never reuse an edge.
/// \pre `mesh` is the mesh the space was built on.
/// \throw ricci::InvalidInputError when the mesh has another face count than the space or
///        grow < 0.
[[nodiscard]] std::vector<Rim> find_rims(const ManifoldSplineSpace& space, const ricci::Mesh& mesh,
                                         const FindRimsOptions& options = {});

struct FillOptions {
  int degree = 3;  ///< degree of the patch's DMS spline, 1..kMaxDmsDegree
  /// Patch triangulation edges per rim edge along the boundary (its resolution: the patch
  /// triangles' size is about rim edge length / refinement).
  int refinement = 2;
  /// Cap on rim edges * refinement: long boundary loops get a coarser patch (cost grows with the
  /// square of the boundary's vertex count).
  int max_boundary_vertices = 160;
  /// Samples per rim edge of the seam measurement stored in HoleFill (the issue asks for 100).
  int samples_per_edge = 100;
  /// Samples per rim edge in the least-squares objective.
  int fit_samples_per_edge = 12;
  double position_weight = 1e6;  ///< weight of |P - S|^2 (dimensionless, see the header comment)
  double tangent_weight = 1e6;   ///< weight of the tangent-plane (G1) rows
  double cross_weight = 1e-2;    ///< weight of the weak cross-boundary derivative rows
  double smoothing = 1.0;        ///< weight of the thin-plate energy
  /// Boundary loops only: refuse (throw) when the loop projected onto its least-squares plane
  /// is not a simple polygon (the fill would fold).
  bool require_simple_projection = true;
  KnotCloudOptions knots;
};

/// Position, first derivatives in D's coordinates and unit normal (Pu x Pv) of the patch.
struct PatchPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d du = Eigen::Vector3d::Zero(), dv = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< zero where degenerate
};

/// A filled rim: the planar patch, its domain D and the seam figures.
struct HoleFill {
  Rim rim;
  /// The patch's planar DMS space: its triangulation covers D and a collar around it (so every
  /// function reaching D is present: partition of unity and polynomial reproduction on D).
  std::shared_ptr<const PlanarDmsSpace> space;
  Eigen::MatrixX3d control_points;  ///< space->function_count() rows
  /// D: a convex polygon; corners[j] is the parameter point of rim edge j's start vertex. D's
  /// corners are clockwise in rim order (the patch's counter-clockwise triangles then glue to
  /// the surface's with one orientation).
  std::vector<Eigen::Vector2d> corners;
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< a point inside D (the circle's centre)
  double diagonal = 1.0;  ///< bounding-box diagonal of the domain mesh: unit of the gaps

  // Seam figures (measure_seam at FillOptions::samples_per_edge).
  double max_normal_jump_deg = 0.0;  ///< max angle between the surface's and patch's normals
  double max_position_gap = 0.0;     ///< max |P - S| / diagonal
  double rms_position_gap = 0.0;     ///< RMS |P - S| / diagonal
  int seam_samples = 0;

  /// Parameter point in D of rim sample (edge j, t): (1 - t) corners[j] + t corners[j + 1].
  [[nodiscard]] Eigen::Vector2d parameter(int edge, double t) const;
  /// The patch at a parameter point (D, or its collar).
  [[nodiscard]] PatchPoint evaluate(const Eigen::Vector2d& u) const;
  /// Value, gradient and Hessian (3 components) of the patch at a parameter point.
  [[nodiscard]] SplineJet jet(const Eigen::Vector2d& u) const;
};

/// Fills one rim of `spline` (see the header comment for the method).
/// \pre `domain_mesh` is the spline space's mesh; `rim` came from find_rims on them.
/// \throw ricci::InvalidInputError on bad options, an empty rim, or a boundary loop whose
///        projection onto its least-squares plane is not simple (the message names the loop);
///        ricci::SolverError when the least-squares system cannot be solved.
[[nodiscard]] HoleFill fill_rim(const ManifoldSpline& spline, const ricci::Mesh& domain_mesh,
                                const Rim& rim, const FillOptions& options = {});

struct SeamReport {
  double max_normal_jump_deg = 0.0;
  double max_position_gap = 0.0;  ///< relative to fill.diagonal
  double rms_position_gap = 0.0;  ///< relative to fill.diagonal
  int samples = 0;
};

/// Normal-angle jump (degrees) and position gap between the surrounding spline (evaluated on
/// the rim edge inside its domain face, one-sided) and the patch, at samples_per_edge + 1
/// samples per rim edge (t = i / samples_per_edge). Normals are compared with their orientation
/// (a flipped patch reports ~180 degrees).
/// \throw ricci::InvalidInputError when samples_per_edge < 1.
[[nodiscard]] SeamReport measure_seam(const ManifoldSpline& spline, const HoleFill& fill,
                                      int samples_per_edge = 100);

/// The patch triangulated at density d (d segments per rim edge).
/// Vertex indices: i >= 0 is the interior vertex i (rows of positions/normals/parameters);
/// i < 0 is rim sample -(1 + (j * d + s)) for rim edge j, sample s in 0..d-1 (sample (j, d) is
/// (j + 1, 0)). The rim samples are not in `positions`: the caller welds them to the surface's
/// own vertices at rim_edge_barycentric(edge j, s / d). Triangles are oriented like the
/// surrounding surface (counter-clockwise in the atlas charts), so surface + patches form a
/// consistently oriented closed surface.
struct PatchTessellation {
  Eigen::MatrixX3d positions, normals;  ///< interior vertices
  Eigen::MatrixX2d parameters;          ///< interior vertices, in D
  Eigen::MatrixX3i triangles;
};

/// \throw ricci::InvalidInputError when d < 1.
[[nodiscard]] PatchTessellation tessellate_fill(const HoleFill& fill, int d);

}  // namespace spline
