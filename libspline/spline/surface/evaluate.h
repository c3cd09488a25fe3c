#pragma once
// Evaluating a SplineSurface: position, first and second derivatives, unit normal, Gaussian and
// mean curvature (and the principal curvatures) at a point of the domain or of a fill patch.
//
// Frames. On the spline, derivatives are taken in the evaluating chart's coordinates: the
// neighbourhood chart of the point's face (ManifoldSplineSpace::chart_of), reported in `chart`.
// On a fill patch they are taken in the patch's parameter plane D (HoleFill::parameter), and
// `chart` is -1. The curvatures and the normal do not depend on the frame.
//
// Curvature convention. N = (F_u x F_v) / |F_u x F_v| (the domain faces' counter-clockwise
// orientation; on a fill, the patch's P_x x P_y). With the first fundamental form E, F, G and the
// second L = F_uu . N, M = F_uv . N, N' = F_vv . N:
//     K = (L N' - M^2) / (E G - F^2),   H = (E N' - 2 F M + G L) / (2 (E G - F^2)),
// k1 >= k2 the principal curvatures (H +- sqrt(H^2 - K)). A normal section curving towards N has
// positive normal curvature: a sphere of radius R with the outward normal has K = 1 / R^2 and
// H = -1 / R.
#include <Eigen/Core>
#include <vector>

#include "spline/surface/spline_surface.h"

namespace spline {

/// A point of a SplineSurface: a domain face with barycentric coordinates (fill -1), or a fill
/// patch with a parameter point in its domain D (point.face -1).
struct SurfaceLocation {
  DomainPoint point{-1, Eigen::Vector3d::Constant(1.0 / 3.0)};
  int fill = -1;  ///< index into SplineSurface::fills, -1 on the spline
  Eigen::Vector2d fill_parameter = Eigen::Vector2d::Zero();
};

/// Gaussian, mean and principal curvatures (see the header comment for the convention).
struct Curvatures {
  double gaussian = 0.0;  ///< K
  double mean = 0.0;      ///< H
  double k1 = 0.0, k2 = 0.0;  ///< principal curvatures, k1 >= k2
};

/// The surface's differential geometry at one point.
struct SurfaceDifferential {
  SurfaceLocation location;
  int chart = -1;  ///< frame of the derivatives: the atlas chart, -1 on a fill (D's frame)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d du = Eigen::Vector3d::Zero(), dv = Eigen::Vector3d::Zero();
  Eigen::Vector3d duu = Eigen::Vector3d::Zero(), duv = Eigen::Vector3d::Zero(),
                  dvv = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit; zero where F_u x F_v = 0
  Curvatures curvature;                              ///< zeros where the normal is zero
};

/// Curvatures from the derivatives of a parametrised surface (zeros when F_u x F_v = 0).
[[nodiscard]] Curvatures curvatures(const Eigen::Vector3d& du, const Eigen::Vector3d& dv,
                                    const Eigen::Vector3d& duu, const Eigen::Vector3d& duv,
                                    const Eigen::Vector3d& dvv);

/// The surface at a domain point. Barycentric coordinates must be finite, each >= -1e-6 and
/// sum to 1 within 1e-6; they are divided by their sum.
/// \throw ricci::InvalidInputError when the face is out of range, outside the spline's domain or
///        skipped (SplineSurface::skipped_faces: a fill covers it), or on bad coordinates.
[[nodiscard]] SurfaceDifferential evaluate_surface(const SplineSurface& surface,
                                                   const DomainPoint& point);

/// The surface at a location: a domain point as above, or a fill patch's parameter point, which
/// must be finite and inside the patch's domain D (within 1e-9 of its size).
/// \throw ricci::InvalidInputError on a fill index out of range or a point outside D, and as
///        above.
[[nodiscard]] SurfaceDifferential evaluate_surface(const SplineSurface& surface,
                                                   const SurfaceLocation& location);

/// Many domain points on `threads` threads (0: hardware concurrency); result i is point i.
/// \throw as the single-point call (the first failing point's error).
[[nodiscard]] std::vector<SurfaceDifferential> evaluate_surface(
    const SplineSurface& surface, const std::vector<DomainPoint>& points, int threads = 0);

/// True when `u` lies in fill `fill`'s domain D (the polygon of its boundary samples), allowing
/// `tolerance` times D's diameter outside it.
[[nodiscard]] bool in_fill_domain(const HoleFill& fill, const Eigen::Vector2d& u,
                                  double tolerance = 1e-9);

}  // namespace spline
