#pragma once
// The one-extraordinary-point problem of the manifold-splines paper (section 4): which mesh the
// flow runs on and which curvature it aims for, by topology.
//   closed, genus 1   -> flat torus, no cone;
//   closed, genus >= 2 -> one cone of curvature 2*pi*chi at the chosen vertex, after valence
//                         modification;
//   closed, genus 0   -> the chosen vertex's star is removed (a cone of 4*pi has no flat
//                         realisation) and the new boundary carries the curvature 2*pi;
//   open               -> flat interior, boundary curvature 2*pi*chi spread by boundary length.
#include <string>
#include <vector>

#include "ricci/flow/flow.h"
#include "ricci/flow/targets.h"
#include "ricci/mesh/mesh.h"
#include "ricci/singularity/valence.h"

namespace ricci {

enum class OneConeKind { FlatTorus, SingleCone, PuncturedSphere, OpenSurface };

std::string to_string(OneConeKind kind);

struct OneConeProblem {
  OneConeKind kind = OneConeKind::FlatTorus;
  Mesh mesh;            ///< The mesh the flow runs on (valence-modified or punctured).
  int cone = -1;        ///< Cone vertex in `mesh` (SingleCone only), else -1.
  int chosen_vertex = -1;  ///< The input vertex the problem was built around, -1 if unused.
  /// mesh vertex index -> input vertex index, or -1 for a vertex added by an edge split.
  std::vector<int> input_vertex;
  Targets targets;
  int valence_splits = 0;
  int genus = 0;
  int boundary_loops = 0;
};

/// Builds the problem around `vertex` (ignored for genus 1 and open surfaces).
/// \pre a connected oriented 2-manifold triangle mesh.
/// \throw InvalidInputError for a vertex out of range or on the boundary when it is needed.
[[nodiscard]] OneConeProblem prepare_one_cone(const Mesh& mesh, int vertex,
                                              const ValenceOptions& valence = {});

/// Flow settings that reach one-cone targets: Thurston circle packing (weights in [0, pi/2]) from
/// min radii. The inversive-distance metric reproduces the mesh exactly but, measured on the
/// shared genus-2/3 scans, breaks triangles before a cone of curvature -4*pi or -8*pi is reached,
/// while circle packing with valence modification converges in 5-7 Newton steps.
[[nodiscard]] FlowOptions one_cone_flow_options();

/// Whether the mesh's topology asks for a singular vertex at all (closed, genus != 1).
[[nodiscard]] bool needs_singular_vertex(const Mesh& mesh);

/// Genus and boundary-loop count of a connected mesh.
[[nodiscard]] int mesh_genus(const Mesh& mesh);
[[nodiscard]] int count_boundary_loops(const Mesh& mesh);

}  // namespace ricci
