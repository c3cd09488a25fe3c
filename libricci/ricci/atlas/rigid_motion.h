#pragma once
// Orientation-preserving rigid motions of the plane, x -> R(angle) x + translation: the
// transition maps of a flat affine atlas.
#include <vector>

#include <Eigen/Core>

namespace ricci {

struct RigidMotion2 {
  double angle = 0.0;  ///< Rotation angle in radians, in (-pi, pi].
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();

  [[nodiscard]] Eigen::Matrix2d rotation() const;
  [[nodiscard]] Eigen::Vector2d apply(const Eigen::Vector2d& x) const {
    return rotation() * x + translation;
  }
  [[nodiscard]] RigidMotion2 inverse() const;
  /// (this after other)(x) = this(other(x)).
  [[nodiscard]] RigidMotion2 after(const RigidMotion2& other) const;
};

/// Least-squares rigid motion taking `from` rows to `to` rows (2D Kabsch, no reflection).
/// `residual`, if given, receives max_i |motion(from_i) - to_i|.
/// \pre from.rows() == to.rows() >= 1. \throw InvalidInputError otherwise.
[[nodiscard]] RigidMotion2 fit_rigid_motion(const Eigen::MatrixX2d& from,
                                            const Eigen::MatrixX2d& to, double* residual = nullptr);

/// The same fit for points given as a base plus offsets (from_i = from_base + from_offsets.row(i),
/// likewise `to`) whose offsets are known to a finer absolute accuracy than the bases (the
/// double-double differences of a layout): the rotation and the residual come from the offsets
/// alone, so a cluster far smaller than the rounding of its coordinates keeps its angle.
/// \pre from_offsets.rows() == to_offsets.rows() >= 1. \throw InvalidInputError otherwise.
[[nodiscard]] RigidMotion2 fit_rigid_motion(const Eigen::Vector2d& from_base,
                                            const Eigen::MatrixX2d& from_offsets,
                                            const Eigen::Vector2d& to_base,
                                            const Eigen::MatrixX2d& to_offsets,
                                            double* residual = nullptr);

/// The same fit with the rotation given (e.g. from a layout's developed edge directions, which
/// keep an angle where even the offsets are below their rounding): the translation and the
/// residual from the offsets, as above.
/// \pre from_offsets.rows() == to_offsets.rows() >= 1. \throw InvalidInputError otherwise.
[[nodiscard]] RigidMotion2 fit_rigid_motion(double angle, const Eigen::Vector2d& from_base,
                                            const Eigen::MatrixX2d& from_offsets,
                                            const Eigen::Vector2d& to_base,
                                            const Eigen::MatrixX2d& to_offsets,
                                            double* residual = nullptr);

}  // namespace ricci
