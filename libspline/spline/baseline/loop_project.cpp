// Closest points on a Loop limit surface by Gauss-Newton in the face parameters (loop_fit.h).
#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "ricci/mesh/errors.h"
#include "spline/baseline/loop_fit.h"

namespace spline {

namespace {

// Barycentric weights of the corners (c0, c1, c2) at a location.
Eigen::Vector3d barycentric(const LoopLocation& loc) { return {1.0 - loc.u - loc.v, loc.u, loc.v}; }

// Most faces one step may cross (enough to pass around a vertex).
constexpr int kMaxHops = 8;

// Gauss-Newton direction in the face's (u, v) that best reproduces the 3D displacement `move`.
Eigen::Vector2d parameter_step(const LoopPoint& p, const Eigen::Vector3d& move) {
  Eigen::Matrix<double, 3, 2> jac;
  jac << p.du, p.dv;
  const Eigen::Matrix2d h = jac.transpose() * jac;
  if (!(h.determinant() > 1e-30 * h.squaredNorm())) return Eigen::Vector2d::Zero();
  return h.ldlt().solve(jac.transpose() * move);
}

// Moves `loc` by `d` in its face's (u, v). A step that leaves the face stops on the edge; if a
// face lies across it, the rest of the step's 3D displacement continues in that face (the
// surface is C1 there, so both faces' derivatives span the same tangent plane).
LoopLocation walk(const LoopSurface& surface, const Eigen::MatrixX3d& patch_points, LoopLocation loc,
                  Eigen::Vector2d d, LoopPoint p) {
  for (int hop = 0; hop <= kMaxHops; ++hop) {
    const Eigen::Vector3d b = barycentric(loc);
    const Eigen::Vector3d db(-d[0] - d[1], d[0], d[1]);
    double t = 1.0;
    int exit_corner = -1;
    for (int k = 0; k < 3; ++k) {
      if (db[k] < 0.0 && b[k] + t * db[k] < 0.0) {
        t = std::max(0.0, b[k] / -db[k]);
        exit_corner = k;
      }
    }
    Eigen::Vector3d moved = b + t * db;
    if (exit_corner < 0) return {loc.face, moved[1], moved[2]};
    moved[exit_corner] = 0.0;
    moved = moved.cwiseMax(0.0) / moved.cwiseMax(0.0).sum();
    const int next = surface.neighbour(loc.face, exit_corner);
    if (next < 0 || hop == kMaxHops) return {loc.face, moved[1], moved[2]};
    const Eigen::Vector3d rest = (1.0 - t) * (p.du * d[0] + p.dv * d[1]);
    Eigen::Vector3d there = Eigen::Vector3d::Zero();
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) {
        if (surface.corner(next, j) == surface.corner(loc.face, k)) there[j] = moved[k];
      }
    }
    loc = {next, there[1], there[2]};
    p = surface.evaluate(patch_points, loc);
    d = parameter_step(p, rest);
  }
  return loc;
}

}  // namespace

LoopProjection project_to_loop_surface(const LoopSurface& surface, const Eigen::MatrixX3d& control,
                                       const Eigen::MatrixX3d& points, const std::vector<LoopLocation>& start,
                                       int steps) {
  if (static_cast<Eigen::Index>(start.size()) != points.rows()) {
    throw ricci::InvalidInputError("project_to_loop_surface: " + std::to_string(start.size()) +
                                   " start locations for " + std::to_string(points.rows()) + " points");
  }
  const Eigen::MatrixX3d patch_points = surface.patch_points(control);
  LoopProjection out;
  out.locations = start;
  out.distances.resize(points.rows());
  out.start_distances.resize(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d q = points.row(i).transpose();
    LoopLocation& loc = out.locations[static_cast<size_t>(i)];
    LoopPoint p = surface.evaluate(patch_points, loc);
    double best = (p.position - q).norm();
    out.start_distances[i] = best;
    for (int step = 0; step < steps && best > 0.0; ++step) {
      Eigen::Vector2d d = parameter_step(p, q - p.position);
      if (d.isZero()) break;
      bool improved = false;
      for (int halving = 0; halving < 4 && !improved; ++halving, d *= 0.5) {
        const LoopLocation trial = walk(surface, patch_points, loc, d, p);
        const LoopPoint tp = surface.evaluate(patch_points, trial);
        const double dist = (tp.position - q).norm();
        if (dist < best) {
          improved = true;
          best = dist;
          loc = trial;
          p = tp;
        }
      }
      if (!improved) break;
    }
    out.distances[i] = best;
  }
  return out;
}

}  // namespace spline
