#pragma once
// A seeded irregular planar triangulation for tests and benchmarks of the DMS basis.
#include "spline/planar/triangulation.h"

namespace spline {

/// (m+1) x (m+1) grid on [0,1]^2, interior vertices moved by up to jitter * h (h = 1 / m), each
/// square split by a random diagonal. Deterministic for a given seed on one standard library.
[[nodiscard]] PlanarTriangulation perturbed_grid(int m, double jitter, unsigned seed);

}  // namespace spline
