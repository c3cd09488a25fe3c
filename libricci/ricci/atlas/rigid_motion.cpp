#include "ricci/atlas/rigid_motion.h"

#include <cmath>
#include <string>

#include "ricci/mesh/errors.h"

namespace ricci {

Eigen::Matrix2d RigidMotion2::rotation() const {
  const double c = std::cos(angle), s = std::sin(angle);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

RigidMotion2 RigidMotion2::inverse() const {
  RigidMotion2 inv;
  inv.angle = -angle;
  inv.translation = -(inv.rotation() * translation);
  return inv;
}

RigidMotion2 RigidMotion2::after(const RigidMotion2& other) const {
  RigidMotion2 c;
  c.angle = std::remainder(angle + other.angle, 2.0 * M_PI);
  c.translation = rotation() * other.translation + translation;
  return c;
}

namespace {

void check_counts(Eigen::Index from, Eigen::Index to) {
  if (from != to || from == 0) {
    throw InvalidInputError("rigid motion fit: " + std::to_string(from) + " and " +
                            std::to_string(to) + " points");
  }
}

// The angle maximising trace(R^T H), H the cross-covariance of the centred sets.
double kabsch_angle(const Eigen::Matrix2d& h) {
  return std::atan2(h(0, 1) - h(1, 0), h(0, 0) + h(1, 1));
}

}  // namespace

RigidMotion2 fit_rigid_motion(const Eigen::MatrixX2d& from, const Eigen::MatrixX2d& to,
                              double* residual) {
  check_counts(from.rows(), to.rows());
  const Eigen::RowVector2d cf = from.colwise().mean(), ct = to.colwise().mean();
  RigidMotion2 m;
  const Eigen::Matrix2d h = (from.rowwise() - cf).transpose() * (to.rowwise() - ct);
  m.angle = kabsch_angle(h);
  m.translation = ct.transpose() - m.rotation() * cf.transpose();
  if (residual) {
    *residual = 0.0;
    for (Eigen::Index i = 0; i < from.rows(); ++i) {
      *residual =
          std::max(*residual, (m.apply(from.row(i).transpose()) - to.row(i).transpose()).norm());
    }
  }
  return m;
}

RigidMotion2 fit_rigid_motion(const Eigen::Vector2d& from_base, const Eigen::MatrixX2d& from_offsets,
                              const Eigen::Vector2d& to_base, const Eigen::MatrixX2d& to_offsets,
                              double* residual) {
  check_counts(from_offsets.rows(), to_offsets.rows());
  const Eigen::RowVector2d cf = from_offsets.colwise().mean(), ct = to_offsets.colwise().mean();
  const Eigen::Matrix2d h =
      (from_offsets.rowwise() - cf).transpose() * (to_offsets.rowwise() - ct);
  return fit_rigid_motion(kabsch_angle(h), from_base, from_offsets, to_base, to_offsets, residual);
}

RigidMotion2 fit_rigid_motion(double angle, const Eigen::Vector2d& from_base,
                              const Eigen::MatrixX2d& from_offsets, const Eigen::Vector2d& to_base,
                              const Eigen::MatrixX2d& to_offsets, double* residual) {
  check_counts(from_offsets.rows(), to_offsets.rows());
  const Eigen::RowVector2d cf = from_offsets.colwise().mean(), ct = to_offsets.colwise().mean();
  const Eigen::MatrixX2d from_centred = from_offsets.rowwise() - cf;
  const Eigen::MatrixX2d to_centred = to_offsets.rowwise() - ct;
  RigidMotion2 m;
  m.angle = angle;
  const Eigen::Matrix2d r = m.rotation();
  m.translation = to_base + ct.transpose() - r * (from_base + cf.transpose());
  if (residual) {
    *residual = 0.0;
    for (Eigen::Index i = 0; i < from_centred.rows(); ++i) {
      *residual = std::max(
          *residual, (r * from_centred.row(i).transpose() - to_centred.row(i).transpose()).norm());
    }
  }
  return m;
}

}  // namespace ricci
