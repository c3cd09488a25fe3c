#pragma once
// Where a closed genus-0 surface's puncture goes. Its one-cone atlas removes the cone's star
// (the puncture) and a planar patch fills it (fill_rim, G1 to the surface around the rim). How
// well a patch meets the rim depends on how much the surface turns there, which the atlas'
// choice (least area distortion, ricci/singularity/choose.h) ignores: among the vertices whose
// flows verified a distortion close to the best, the one with the flattest neighbourhood wins.
#include <vector>

#include "ricci/mesh/mesh.h"
#include "ricci/singularity/choose.h"

namespace spline {

struct PunctureChoiceOptions {
  /// Candidates: vertices whose verified area distortion is at most (1 + this) times the best
  /// verified one. 0: the distortion's choice alone.
  double distortion_tolerance = 0.03;
  /// The neighbourhood scored: the faces with a corner within rings - 1 vertex rings of the
  /// vertex (1: its star; 3, by default: the hole find_rims grows by one layer and the kept
  /// faces along its rim, whose tangent planes the patch meets).
  int rings = 3;
  /// The flattest candidate replaces the distortion's choice only when its spread is at most
  /// (1 - this) times that choice's: the spread of a few coarse faces is a rough predictor of
  /// the seam, and a small gain is not worth the distortion.
  double min_spread_gain = 0.25;
};

struct PunctureChoice {
  int vertex = -1;                ///< the chosen vertex, -1 when the mesh needs none
  double area_distortion = 0.0;   ///< its verified flow's (NaN when no flow verified it)
  double normal_spread_deg = 0.0;  ///< its neighbourhood's (star_normal_spread_deg)
  int distortion_vertex = -1;     ///< the least-distortion choice (SingularityChoice::vertex)
  double distortion_spread_deg = 0.0;  ///< that vertex's neighbourhood's spread
  int candidates = 0;             ///< verified vertices within the tolerance
  ricci::SingularityChoice choice;  ///< the distortion's choice, as choose_singularity made it
};

/// The largest angle (degrees) between the normal of one of `faces` and their area-weighted
/// mean normal: 0 for a flat set; 180 when the mean vanishes (a closed set). Zero-area faces
/// are skipped. \pre every index is a face of `mesh`.
[[nodiscard]] double faces_normal_spread_deg(const ricci::Mesh& mesh,
                                             const std::vector<int>& faces);

/// The largest angle (degrees) between the normal of a face with a corner within rings - 1
/// vertex rings of `vertex` and the area-weighted mean normal of those faces.
/// \throw ricci::InvalidInputError when the vertex is out of range or rings < 1.
[[nodiscard]] double star_normal_spread_deg(const ricci::Mesh& mesh, int vertex, int rings);

/// choose_singularity(mesh, singularity), then among its verified vertices within the
/// distortion tolerance of the best, the one of least star_normal_spread_deg (ties: least
/// distortion) when it gains enough (min_spread_gain). Without verified flows (large meshes)
/// the distortion's choice stands.
/// \pre as choose_singularity. \throw as choose_singularity; ricci::InvalidInputError when
///      options.rings < 1, options.distortion_tolerance < 0 or min_spread_gain outside [0, 1].
[[nodiscard]] PunctureChoice choose_puncture(const ricci::Mesh& mesh,
                                             const ricci::SingularityOptions& singularity,
                                             const PunctureChoiceOptions& options = {});

}  // namespace spline
