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

RigidMotion2 fit_rigid_motion(const Eigen::MatrixX2d& from, const Eigen::MatrixX2d& to,
                              double* residual) {
  if (from.rows() != to.rows() || from.rows() == 0) {
    throw InvalidInputError("rigid motion fit: " + std::to_string(from.rows()) + " and " +
                            std::to_string(to.rows()) + " points");
  }
  const Eigen::RowVector2d cf = from.colwise().mean(), ct = to.colwise().mean();
  // Cross-covariance of the centred sets; the optimal angle maximises trace(R^T H).
  const Eigen::Matrix2d h = (from.rowwise() - cf).transpose() * (to.rowwise() - ct);
  RigidMotion2 m;
  m.angle = std::atan2(h(0, 1) - h(1, 0), h(0, 0) + h(1, 1));
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

}  // namespace ricci
