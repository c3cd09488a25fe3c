#pragma once
// Side pairings of a fundamental domain laid out in the disk (H2) or the plane (E2), and the
// holonomy representation of the fundamental group they generate: for a closed hyperbolic
// surface the Fuchsian group, whose canonical generators a1 b1 ... ag bg satisfy
// Π [a_i, b_i] = I (hyperbolic-and-real-projective-structure §4.3; discrete-surface-ricci-flow
// §V). Every map is a Mobius matrix (SU(1,1) in H2, Euclidean motions in E2).
#include <vector>

#include <Eigen/Core>

#include "ricci/hyperbolic/mobius.h"
#include "ricci/hyperbolic/mobius_q.h"
#include "ricci/metric/geometry.h"
#include "ricci/topology/cut_graph.h"
#include "ricci/topology/polygon_word.h"
#include "ricci/topology/slice.h"

namespace ricci {

/// A maximal chain of cut edges between branch points of the cut graph (vertices where the
/// number of cut edges is not 2): one pair of sides of the sliced disk.
struct CutArc {
  /// Original halfedges along the arc, in order; each one's face is on the arc's left side.
  std::vector<HalfedgeHandle> halfedges;
  /// The loop whose generator (cotree) edge lies on the arc, or -1 for a pure tree arc.
  int loop = -1;
  /// The map taking the right side's copy of the domain edge onto the left side's
  /// (so pairing(domain) is the neighbour of the domain across the left side): the mean of the
  /// per-edge maps.
  Mobius pairing;
  /// `pairing` in extended precision: the relator residuals and the generators are multiplied
  /// from these (long words of large matrices amplify double rounding to 1e-8 on genus 4).
  MobiusL precise_pairing;
  /// `pairing` in quad precision, from the layout's quad positions when given (else
  /// precise_pairing): the residuals and the generators are multiplied from these.
  MobiusQ quad_pairing;
  /// max over the arc's edges of mobius_distance(edge map, first edge map): the paper's
  /// "generators from different edges of the same side agree" check.
  double spread = 0.0;
};

struct DomainPairings {
  /// Per original edge index: for a cut edge e, the map P_e taking the copy of e in
  /// face(halfedge(e, 1)) onto the copy in face(halfedge(e, 0)); identity for uncut edges.
  std::vector<Mobius> edge_pairing;
  std::vector<char> is_cut_edge;
  std::vector<CutArc> arcs;
  double max_spread = 0.0;  ///< Max of the arcs' spreads.
};

/// Pairings of every cut edge from the layout of the sliced disk (positions by sliced vertex
/// index; in the disk for hyperbolic, the plane for euclidean), grouped into arcs.
/// `precise_positions` (optional, the same in extended precision, e.g. from layout_h2) are used
/// instead of `positions` when given, and `quad_positions` (optional, quad precision, hyperbolic
/// only) instead of both.
/// \pre `sliced` is `mesh` cut along `cut.is_cut_edge`, closed mesh; geometry is hyperbolic or
///      euclidean. \throw InvalidInputError for the spherical geometry or a size mismatch.
[[nodiscard]] DomainPairings domain_pairings(const Mesh& mesh, const CutGraph& cut,
                                             const SlicedMesh& sliced,
                                             const Eigen::VectorXcd& positions, Geometry geometry,
                                             const std::vector<ComplexL>& precise_positions = {},
                                             const std::vector<ComplexQ>& quad_positions = {});

/// A letter of a word in the arcs' pairings: arcs[arc].pairing^sign.
struct ArcLetter {
  int arc = 0;
  int sign = 1;
};
using ArcWord = std::vector<ArcLetter>;

/// Cancels adjacent x x^-1 pairs. Evaluating a reduced word multiplies fewer (and smaller)
/// matrices, which is what keeps the products accurate to 1e-9.
[[nodiscard]] ArcWord freely_reduced(const ArcWord& word);

/// Free reduction, then cancels a first letter against an inverse last letter while possible: a
/// conjugate of the word (w R w^-1 -> R), equal to the identity exactly when the word is.
[[nodiscard]] ArcWord cyclically_reduced(const ArcWord& word);

/// distance_to_identity of the word's product, evaluated well-conditioned: the word cyclically
/// reduced, its product measured in the frame centred at the candidate point whose images
/// under the word's prefixes stay closest to it (the prefixes of a vertex-cycle relator move
/// that region least). Conjugation keeps "= I" exact, so this tests the relation. The quad
/// pairings are multiplied in double-quad (~226 bits) and conjugated once: the partial products
/// reach norm ~1e11 at genus 9, and a quad product's own rounding, amplified by their squares,
/// would hide the pairings' residual.
[[nodiscard]] double conditioned_residual(const DomainPairings& pairings, const ArcWord& word,
                                          const std::vector<Complex>& candidates);

/// A corner of the fundamental domain: a vertex where three or more cut edges meet, the arcs
/// crossed turning once around it (from the face of its first outgoing halfedge), and the
/// position of its copy in that face.
struct VertexCycle {
  int vertex = -1;
  ArcWord word;
  Complex centre{0, 0};
};

/// The vertex cycles of a closed surface's cut graph, `positions` the layout of the sliced disk.
/// Poincaré's polygon theorem: together with the side pairings they generate every relation of
/// the group, Π [a_i, b_i] among them (a product of their conjugates).
/// \throw InvalidInputError for positions or a cut of the wrong size.
[[nodiscard]] std::vector<VertexCycle> vertex_cycles(const Mesh& mesh, const CutGraph& cut,
                                                     const SlicedMesh& sliced,
                                                     const DomainPairings& pairings,
                                                     const Eigen::VectorXcd& positions);

/// max over the cycles of distance_to_identity of the cycle's product (ProductReal, as
/// conditioned_residual) in the frame centred at its vertex's copy: each cycle's defect where
/// it lives (its curvature error, the layout's local error), which no conjugation by a long
/// word amplifies.
[[nodiscard]] double vertex_cycle_residual(const DomainPairings& pairings,
                                           const std::vector<VertexCycle>& cycles);

/// The product of the arcs' pairings along `word`, left to right (multiplied in extended
/// precision from the precise pairings, rounded to double at the end).
[[nodiscard]] Mobius evaluate(const DomainPairings& pairings, const ArcWord& word);

/// rho(loop i) for every loop of the cut graph as a reduced word in the arc pairings, based at
/// the root: develop the faces along the loop's left side from a fixed face at the root back to
/// it, recording every cut arc crossed (crossing an arc from its left face to its right face
/// multiplies by its pairing on the right). rho(w1 w2) = rho(w1) rho(w2).
/// \pre closed surface. \throw InvalidInputError for a surface with boundary.
[[nodiscard]] std::vector<ArcWord> loop_arc_words(const Mesh& mesh, const CutGraph& cut,
                                                  const DomainPairings& pairings);

/// A word in the loops rewritten in the arcs (each loop letter replaced by its arc word or the
/// inverse of it), freely reduced.
[[nodiscard]] ArcWord arc_word(const std::vector<ArcWord>& loop_words, const LoopWord& word);

/// mobius_distance(a1 b1 a1^-1 b1^-1 ... ag bg ag^-1 bg^-1, I) for generators a1 b1 a2 b2 ...,
/// multiplied as given. \pre an even count.
[[nodiscard]] double relation_residual(const std::vector<Mobius>& generators);

/// The holonomy group of a closed surface's domain: canonical generators and the checks.
struct HolonomyGroup {
  FundamentalPolygon polygon;
  CanonicalBasis basis;
  std::vector<ArcWord> loop_words;       ///< rho of each cut-graph loop, in arc letters.
  std::vector<Mobius> loop_holonomy;     ///< rho of each cut-graph loop.
  std::vector<ArcWord> generator_words;  ///< basis.generators in arc letters.
  std::vector<Mobius> generators;        ///< rho(a1), rho(b1), ...
  /// ||rho(polygon word) - I|| (the word cyclically reduced in arc letters before multiplying):
  /// the domain closes up around the root.
  double polygon_residual = 0.0;
  /// ||Π [a_i, b_i] - I|| for the canonical generators, the relator written in arc letters and
  /// evaluated by conditioned_residual (cyclically reduced, in the best-conditioned frame). Cyclic
  /// reduction conjugates (the relator of the canonical basis is a rotation A P A^-1 of the
  /// polygon's), so the test "= I" is unchanged, but the conjugator's rounding, amplified by
  /// ||rho(A)||², is left out; what remains are the vertex cycles of the cut graph's branch points.
  double relation_residual = 0.0;
  /// The same product multiplied from the generator matrices as they are (rounding of long
  /// products of large matrices included).
  double relation_residual_direct = 0.0;
  /// vertex_cycle_residual of the domain's corners (0 without positions): the relations'
  /// defect in the frames where they live. relation_residual is this amplified by the
  /// conjugating words, up to the square of their norms (e^d for words that move by d).
  double cycle_residual = 0.0;
};

/// Loop holonomies, the polygon word and the canonical generators as its words. `positions`
/// (the layout of the sliced disk, optional) supplies the frame centres tried by
/// conditioned_residual for the residuals.
/// \throw TopologyError from the polygon word when the slice is not a disk.
[[nodiscard]] HolonomyGroup holonomy_group(const Mesh& mesh, const CutGraph& cut,
                                           const SlicedMesh& sliced, const DomainPairings& pairings,
                                           const Eigen::VectorXcd& positions = {});

}  // namespace ricci
