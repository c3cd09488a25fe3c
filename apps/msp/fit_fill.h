#pragma once
// The hole-filling stage of `msp fit` (libspline's fill/hole_fill.h): which rims are capped,
// which faces the tessellation skips, welding the patches in, and distances to the patches.
#include <string>
#include <vector>

#include <ricci/mesh/mesh.h>
#include <Eigen/Core>

#include "msp/fit_pipeline.h"

namespace msp {

/// Caps the cone's hole and excluded-face holes (and the boundaries with fill_boundaries);
/// fills run.fills, filled_rims, open_rims, fill_failures and the seam figures. Returns, by
/// face of `domain`, the faces the tessellation must skip: outside the domain, or covered by a
/// rim's patch (the band where the spline's partition of unity fails; skipped even when that
/// rim stays open).
[[nodiscard]] std::vector<char> fill_rims(FitRun& run, const ricci::Mesh& domain,
                                          const FitRunOptions& options);

/// Tessellates every patch at run.tessellation.density and welds it into run.tessellation.
void append_fills(FitRun& run);

/// Distance from `target` to the nearest patch (Gauss-Newton in the patch's domain from its
/// nearest tessellation vertex), -1 when there is none.
[[nodiscard]] double distance_to_fills(const FitRun& run, const Eigen::Vector3d& target,
                                       int iterations);

}  // namespace msp
