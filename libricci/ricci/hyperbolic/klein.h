#pragma once
// The real projective structure of a hyperbolic surface (hyperbolic-and-real-projective-structure
// §5): the Klein model of H2 is the unit disk in the affine chart x0 = 1 of RP2, geodesics are
// straight chords, and the isometries are the projective maps of SO+(2,1), which preserve the
// Minkowski form <x, y> = x0 y0 - x1 y1 - x2 y2 on the hyperboloid x0² - x1² - x2² = 1.
#include <Eigen/Core>

#include "ricci/hyperbolic/mobius.h"

namespace ricci {

/// The hyperboloid point (x0, x1, x2) = (1 + |z|², 2 Re z, 2 Im z) / (1 - |z|²) of a disk point.
[[nodiscard]] Eigen::Vector3d hyperboloid_from_poincare(Complex z);

/// Klein coordinates 2z / (1 + |z|²) of a Poincaré-disk point (x1/x0, x2/x0 on the hyperboloid).
[[nodiscard]] Complex klein_from_poincare(Complex z);
/// Inverse: k / (1 + sqrt(1 - |k|²)).
[[nodiscard]] Complex poincare_from_klein(Complex k);

/// The 3x3 matrix L with hyperboloid(M(z)) = L hyperboloid(z) for a disk isometry M (SU(1,1)),
/// acting on homogeneous Klein coordinates (x0 : x1 : x2); L^T J L = J with J = diag(1, -1, -1).
/// From X(x) = ½ [[x0, x1 + i x2], [x1 - i x2, x0]] -> M X M^* (SU(1,1) -> SO+(2,1)); the same map
/// up to scale as the paper's (1/λ) O T of §5.3.
[[nodiscard]] Eigen::Matrix3d lorentz_matrix(const Mobius& map);

/// The projective map L applied to the Klein point k: (L (1, Re k, Im k)) dehomogenised.
[[nodiscard]] Complex apply_projective(const Eigen::Matrix3d& transition, Complex k);

}  // namespace ricci
