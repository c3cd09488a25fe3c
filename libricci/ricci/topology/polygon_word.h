#pragma once
// The boundary word of the fundamental polygon obtained by slicing along a cut graph: which loop
// each side belongs to and with which orientation, and whether it reads a1 b1 a1^-1 b1^-1 ...
#include <vector>

#include "ricci/topology/cut_graph.h"
#include "ricci/topology/slice.h"

namespace ricci {

struct PolygonLetter {
  enum class Kind { loop, boundary };
  Kind kind = Kind::loop;
  int index = 0;  ///< Loop index into CutGraph::loops, or boundary loop index.
  int sign = 1;   ///< +1: the side runs along the loop's direction; -1 against it.
  bool operator==(const PolygonLetter& o) const {
    return kind == o.kind && index == o.index && sign == o.sign;
  }
};

struct FundamentalPolygon {
  /// Sides met walking the disk boundary counter-clockwise (interior on the left), starting
  /// anywhere: one letter per side of a loop's generator edge (the tree parts of the cut graph
  /// are contracted to the root, as in the group presentation) and one per original boundary
  /// loop. Every loop appears twice, once with each sign.
  std::vector<PolygonLetter> word;
  /// True when the loop letters, up to rotation, read x1 y1 x1^-1 y1^-1 x2 y2 x2^-1 y2^-1 ...
  bool canonical = false;
  /// When canonical: the loop indices in the order x1 y1 x2 y2 ... (the a_i, b_i).
  std::vector<int> canonical_order;
};

/// Reads the boundary word of the sliced disk.
/// \pre `sliced` is `mesh` sliced along `cut.is_cut_edge` and is a disk (check_disk).
/// \throw TopologyError if the sliced mesh has no boundary or a loop does not appear exactly
///        twice with opposite signs.
[[nodiscard]] FundamentalPolygon fundamental_polygon_word(const Mesh& mesh, const CutGraph& cut,
                                                          const SlicedMesh& sliced);

/// True when `loop_letters` (loop letters only) is, up to rotation, x1 y1 x1^-1 y1^-1 ...;
/// fills `order` with the loop indices x1 y1 x2 y2 ... when it is.
[[nodiscard]] bool is_canonical_word(const std::vector<PolygonLetter>& loop_letters,
                                     std::vector<int>* order = nullptr);

/// A word in the loops of a cut graph: letters (loop index, sign), read left to right.
using LoopWord = std::vector<PolygonLetter>;

/// A canonical system of generators of the fundamental group (of the surface with its holes
/// capped), each written as a word in the cut graph's loops, based at the root.
struct CanonicalBasis {
  /// 2g words: a1, b1, a2, b2, ... The relator a1 b1 a1^-1 b1^-1 ... ag bg ag^-1 bg^-1, with
  /// every generator replaced by its word, equals the polygon's loop word up to rotation.
  std::vector<LoopWord> generators;
};

/// Canonical generators from the polygon's loop word by the classical cut-and-paste
/// normalisation (x B y C x^-1 D y^-1 T becomes x' y' x'^-1 y'^-1 D C B T with
/// x' = x C^-1 D^-1 and y' = D C B y D^-1). Boundary letters are dropped (holes capped).
/// The generators are homotopy classes: their curves are not re-routed on the mesh.
/// \throw TopologyError if the loop letters are not an orientable one-vertex surface word
///        (a letter not appearing once each way, or one linked with no other).
[[nodiscard]] CanonicalBasis canonical_basis(const std::vector<PolygonLetter>& word);

/// Free reduction (cancels x x^-1 pairs) followed by cyclic reduction.
[[nodiscard]] LoopWord cyclically_reduced(LoopWord word);

/// True when a and b are equal as cyclic words (one is a rotation of the other).
[[nodiscard]] bool same_cyclic_word(const LoopWord& a, const LoopWord& b);

}  // namespace ricci
