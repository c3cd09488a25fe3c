#pragma once
// Generator of the project's own test surfaces: smooth implicit surfaces of genus 0 to 10, meshed
// with CGAL (Mesh_3 surface facets, then isotropic remeshing to a target size), optionally
// opened by cutting end caps off with planes. The body lives in generate_cgal.cpp so CGAL stays
// out of every other translation unit.
#include <cstdint>
#include <string>

#include "ricci/mesh/mesh.h"

namespace ricci {

/// Largest genus generate_surface makes (a row of 10 fused tori, ~22 units long).
constexpr int kMaxGeneratedGenus = 10;

/// What to generate. The shapes, centred at the origin:
/// - genus 0: a smooth blob, the smooth union of three spheres along the x axis;
/// - genus g >= 1: g tori (R = 1, r = 0.35) centred on the x axis 2R apart, so neighbours touch
///   tangentially, joined by a smooth minimum into one smooth genus-g surface.
struct GenerateOptions {
  int genus = 1;               ///< 0 to kMaxGeneratedGenus.
  int holes = 0;               ///< Boundary loops: 0 closed, 1 or 2 (caps cut at the x ends).
  /// Depth of each cut (length units) from the surface's extreme x. The tori's tubes are 0.7
  /// thick, so a depth >= 0.7 cuts a ring open and changes the genus (generate_surface throws);
  /// the blob is ~2.5 long, so depth ~1.2 leaves about half of it (a disk-like cap).
  double hole_depth = 0.25;
  int target_faces = 3000;     ///< Wanted face count (the result lands within ~15%), >= 200.
  std::uint32_t seed = 1;      ///< Seeds CGAL's random generators: same seed, same mesh.
  int remesh_iterations = 8;   ///< Isotropic remeshing passes per attempt.
};

/// Meshes the surface `options` describes and checks it is a clean manifold of the requested
/// genus with `holes` boundary loops before returning it, outward-oriented.
/// \throw InvalidInputError for options out of range; Error if CGAL's output is not the
///        requested surface (a bug or an impossible size).
[[nodiscard]] Mesh generate_surface(const GenerateOptions& options);

/// Smallest corner angle of all faces, in degrees (180 for an empty mesh).
[[nodiscard]] double min_corner_angle_degrees(const Mesh& mesh);

/// A one-line description of the shape `options` names (for listings and --json).
[[nodiscard]] std::string describe_surface(const GenerateOptions& options);

}  // namespace ricci
