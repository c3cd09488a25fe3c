#pragma once
// Affine atlas of a surface with a flat metric that has at most one cone (manifold-splines
// paper, section 4, steps 4-5): the central chart is the layout of the
// fundamental domain; further charts cover the cut paths, unfolded across the cut; every pair
// of overlapping charts is related by a rigid motion, computed and checked.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "ricci/atlas/rigid_motion.h"
#include "ricci/layout/layout_e2.h"
#include "ricci/mesh/mesh.h"
#include "ricci/topology/cut_graph.h"
#include "ricci/topology/polygon_word.h"
#include "ricci/topology/slice.h"

namespace ricci {

enum class ChartKind {
  central,   ///< The laid-out fundamental domain (every face once).
  cut_path,  ///< Two-ring neighbourhood of one cut path (loop or boundary connector).
  vertex,    ///< Two-ring of one vertex: only where no other chart holds a face's neighbourhood.
  /// The neighbourhood of one face (its vertices' stars): where even the vertex two-rings wrap
  /// around a handle only a few edges thick (CAD meshes), so they develop into several pieces.
  face,
};

/// One planar chart: a set of original faces, each placed once, with chart-local vertex copies.
struct Chart {
  ChartKind kind = ChartKind::central;
  /// cut_path: index into AffineAtlas::cut_paths(); vertex: the original vertex; face: the
  /// original face; central: -1.
  int source = -1;
  std::vector<int> faces;  ///< Original face indices, ascending.
  /// Row r: chart vertices of the corners of faces[r], corner k = to_vertex of the k-th halfedge
  /// of face_halfedges(mesh, face) (topology/slice.h).
  Eigen::MatrixX3i corners;
  std::vector<int> to_original_vertex;  ///< By chart vertex.
  Eigen::MatrixX2d positions;           ///< By chart vertex.

  /// Row of `face` in faces/corners, or -1 if the chart does not hold it.
  [[nodiscard]] int slot(int face) const;
};

/// Rigid motion between two charts on one connected piece of their overlap.
struct Transition {
  int chart_a = -1, chart_b = -1;  ///< chart_a < chart_b.
  RigidMotion2 motion;             ///< Coordinates of chart_a -> coordinates of chart_b.
  std::vector<int> faces;          ///< Original faces of the overlap piece, ascending.
  double residual = 0.0;           ///< max over shared vertices of |motion(x_a) - x_b|.
};

/// The two sides of one arc of the cut graph (a maximal path between branch points, the root
/// and boundary vertices) in the central chart, and the deck transformation pairing them.
struct SidePairing {
  std::vector<HalfedgeHandle> halfedges;  ///< The arc, walked in order.
  int loop = -1;  ///< The loop whose generator edge lies on this arc, or -1 (tree parts).
  /// Maps the left side (faces of `halfedges`) to the right side (faces of their opposites).
  RigidMotion2 motion;
  double residual = 0.0;
};

struct AtlasOptions {
  /// The root is a cone (its one-ring leaves the spline domain) when its curvature exceeds this
  /// in absolute value (radians). Genus-1 and open surfaces have a flat root.
  double cone_tolerance = 1e-6;
  /// Two developed copies of a vertex are glued when closer than this times the mean edge length.
  double glue_tolerance = 1e-6;
  LayoutE2Options layout;
};

struct AffineAtlas {
  CutGraph cut;
  SlicedMesh sliced;
  LayoutE2Result layout;  ///< Layout of sliced.mesh: the central chart's positions.
  FundamentalPolygon polygon;
  bool root_is_cone = false;
  double root_curvature = 0.0;
  std::vector<char> in_domain;  ///< By face: 0 for the cone's one-ring (outside the spline domain).
  std::vector<Chart> charts;    ///< charts[0] is the central chart.
  std::vector<Transition> transitions;
  std::vector<SidePairing> side_pairings;
  /// By face: a chart holding the face and every domain face sharing a vertex with it as one
  /// glued planar piece; -1 outside the domain.
  std::vector<int> neighbourhood_chart;
  int uncovered_faces = 0;       ///< Domain faces with no such chart (0 when all is well).
  double domain_diameter = 0.0;  ///< Bounding-box diagonal of the central chart.
  /// Layout accuracy on the spline domain: max relative edge-length error over the edges of
  /// domain faces in the central chart. (layout.max_relative_length_error also covers the
  /// cone's one-ring, whose edges can be many orders of magnitude shorter than the chart's
  /// coordinates, so their relative error is bounded by the coordinates' rounding.)
  double domain_max_relative_length_error = 0.0;
  /// Same edges, absolute error |d - l| (the floor is the rounding of the chart coordinates,
  /// about 1e-16 times domain_diameter, which dominates the relative error of tiny edges).
  double domain_max_absolute_length_error = 0.0;
  /// Over the transition pieces with a face both charts place faithfully (fitted on those
  /// faces); pieces with none (faces next to a large cone, below the rounding of both charts'
  /// coordinates, which no neighbourhood chart relies on) are counted apart.
  double max_transition_residual = 0.0;
  int unresolved_transition_pieces = 0;
  double max_unresolved_transition_residual = 0.0;  ///< over those pieces, all their faces
  double max_side_pairing_residual = 0.0;

  /// Canonical generators a1 b1 ... ag bg as words in the cut graph's loops (holes capped);
  /// the cut graph itself keeps tree-cotree order (see polygon.canonical).
  CanonicalBasis canonical;
  /// Closed surfaces: holonomy (deck transformation in the central chart) of each loop and of
  /// each canonical generator (atlas/holonomy.h); empty for open surfaces.
  std::vector<RigidMotion2> loop_holonomy;
  std::vector<RigidMotion2> canonical_holonomy;
  /// |rho(relator)| as a motion: rotation angle and translation length of the image of the
  /// polygon's relator, which is the identity for an exact flat metric.
  double relator_holonomy_angle = 0.0;
  double relator_holonomy_translation = 0.0;

  /// Cut paths in chart order: the loops, then the boundary connectors.
  [[nodiscard]] const CutPath& cut_path(int index) const;
  [[nodiscard]] int cut_path_count() const;

  /// A chart holding `face` with its vertex-neighbourhood as one planar piece, or -1.
  [[nodiscard]] int chart_of_face_neighbourhood(int face) const {
    return neighbourhood_chart[face];
  }
  /// Position of corner k of `face` in `chart`. \throw InvalidInputError if the chart lacks it.
  [[nodiscard]] Eigen::Vector2d corner_position(int chart, int face, int corner) const;
  /// The three corner positions of `face` in `chart`, one per row.
  [[nodiscard]] Eigen::Matrix<double, 3, 2> face_positions(int chart, int face) const;
  /// The motion from chart_a to chart_b valid around `face` (held by both), if any.
  [[nodiscard]] std::optional<RigidMotion2> transition(int chart_a, int chart_b, int face) const;
  /// Maps a point of chart_a near `face` to chart_b. \throw InvalidInputError if the two charts
  /// do not both hold `face`.
  [[nodiscard]] Eigen::Vector2d map(const Eigen::Vector2d& point, int chart_a, int chart_b,
                                    int face) const;

  std::vector<std::vector<int>> face_transitions;  ///< By face: indices into transitions.
};

/// Builds the atlas: cut graph rooted at `root`, slicing, layout, cut-path charts, vertex
/// charts where needed, transitions and side pairings.
/// \pre `edge_lengths` (by edge index) is flat everywhere except possibly at `root` (and on the
///      boundary of an open surface), e.g. the one-cone metric of the Ricci flow.
/// \throw InvalidInputError / TopologyError from the stages (bad lengths, not a disk, ...).
[[nodiscard]] AffineAtlas build_affine_atlas(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                                             VertexHandle root, const AtlasOptions& options = {});

/// As above with the long-double metric edge_lengths + lengths_low (low parts by edge index,
/// e.g. PolishE2Result::lengths_low; empty for none): the layout and the charts develop it.
/// \throw also InvalidInputError if lengths_low is neither empty nor of the lengths' size.
[[nodiscard]] AffineAtlas build_affine_atlas(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                                             const Eigen::VectorXd& lengths_low, VertexHandle root,
                                             const AtlasOptions& options = {});

/// Completes `atlas`, whose `cut` and `sliced` were made beforehand (compute_cut_graph rooted
/// at the root, slice_along its cut edges; e.g. beside the polish, with the unpolished lengths):
/// only the paths are taken, their lengths measured again with edge_lengths; then as above.
/// \pre `atlas.cut` and `atlas.sliced` were made from `mesh` (sizes are checked).
/// \throw InvalidInputError on a size mismatch; as above otherwise.
void complete_affine_atlas(const Mesh& mesh, const Eigen::VectorXd& edge_lengths,
                           const Eigen::VectorXd& lengths_low, const AtlasOptions& options,
                           AffineAtlas& atlas);

}  // namespace ricci
