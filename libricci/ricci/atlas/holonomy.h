#pragma once
// Holonomy of the flat metric: the deck transformation (rigid motion of the central chart) of
// every loop of the cut graph and of the canonical generators built from them. These are the
// group elements that pair the sides of a fundamental domain (Fuchsian-group style generators
// of the Euclidean cone structure; hyperbolic-and-real-projective-structure paper, section 3).
#include <vector>

#include "ricci/atlas/atlas.h"

namespace ricci {

/// rho(loop i) for every loop of atlas.cut, based at the root: develop the faces along the
/// loop's left side, starting and ending at a fixed face of the root's one-ring, composing the
/// side pairing of every cut arc crossed. rho is a homomorphism with
/// rho(w1 w2) = rho(w1).after(rho(w2)), so the polygon's relator maps to the identity.
/// Empty for open surfaces (their loops pass through holes). Uses only the central chart.
[[nodiscard]] std::vector<RigidMotion2> loop_holonomies(const Mesh& mesh, const AffineAtlas& atlas);

/// rho(word) from the loops' holonomies: the product of rho(letter)^sign, left to right.
/// Boundary letters are skipped.
[[nodiscard]] RigidMotion2 word_holonomy(const std::vector<RigidMotion2>& loop_holonomy,
                                         const std::vector<PolygonLetter>& word);

}  // namespace ricci
