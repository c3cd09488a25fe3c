#pragma once
// The closest point of a SplineSurface (spline and fill patches) to a point in space, found
// globally: a tessellation of the whole surface in a bounding-volume tree gives every
// tessellation triangle that can hold the answer (those whose distance, less the triangle's
// deviation from the surface, is below the best distance found), and from each candidate
// triangle, lowest bound first, Newton's method on |S(u) - q|^2 runs in the face's chart,
// walking across edges into neighbouring faces, clamped at the rim of the tessellated region
// (skipped faces, the cone's hole, open boundaries) and, on a patch, at its domain D's boundary.
//
// The deviation of a triangle from the surface is measured at the triangle's centre and edge
// midpoints when the index is built, doubled as a safety margin: where the surface bends within
// a triangle more than that, a finer ClosestPointOptions::density is needed.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "spline/surface/evaluate.h"
#include "spline/surface/spline_surface.h"

namespace spline {

struct ClosestPointOptions {
  /// Tessellation of the candidate search: density d samples per domain edge (d^2 triangles per
  /// face) and per rim edge of a fill patch. Higher: tighter deviation bounds, a larger tree.
  int density = 4;
  int iterations = 40;  ///< Newton steps per candidate (each stops early when converged)
  int threads = 0;      ///< building the index and batch queries; 0 = hardware concurrency
};

struct ClosestPoint {
  SurfaceLocation location;  ///< a domain point, or a fill patch and its parameter point
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double distance = 0.0;
  int candidates = 0;  ///< candidate triangles Newton's method ran from
};

/// A reusable closest-point index of one surface (which must outlive it). Queries are const
/// and thread-safe.
class ClosestPointIndex {
 public:
  /// \throw ricci::InvalidInputError for density < 1 or iterations < 1, or a surface with
  ///        nothing tessellated; as tessellate and tessellate_fill.
  explicit ClosestPointIndex(const SplineSurface& surface, const ClosestPointOptions& options = {});
  ~ClosestPointIndex();
  ClosestPointIndex(const ClosestPointIndex&) = delete;
  ClosestPointIndex& operator=(const ClosestPointIndex&) = delete;

  /// \throw ricci::InvalidInputError when `target` is not finite.
  [[nodiscard]] ClosestPoint find(const Eigen::Vector3d& target) const;
  /// One row of `targets` (#Q by 3) per result, on the options' threads.
  [[nodiscard]] std::vector<ClosestPoint> find_all(const Eigen::MatrixX3d& targets) const;

  /// Triangles of the candidate tessellation (for tests and statistics).
  [[nodiscard]] int triangle_count() const;

 private:
  struct Data;
  std::unique_ptr<Data> data_;
};

/// One query: builds a ClosestPointIndex and asks it (use the index for many points).
[[nodiscard]] ClosestPoint closest_point(const SplineSurface& surface,
                                         const Eigen::Vector3d& target,
                                         const ClosestPointOptions& options = {});

}  // namespace spline
