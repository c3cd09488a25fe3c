#pragma once
// Global closest-point queries on a triangle soup and on a set of segments (an AABB tree each):
// what a distance between a delivered surface and a scan is measured with. Bodies use CGAL (in
// soup_distance_cgal.cpp only).
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace ricci {

/// The nearest point of a soup to a query: the primitive's index (triangle or segment), the
/// point and its distance.
struct SoupHit {
  int primitive = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = 0.0;
};

/// Closest points on the triangles (rows of positions by index). Degenerate triangles (a
/// repeated index, or collinear corners) are left out of the tree. The tree is built once; queries
/// are const and may run on several threads.
class TriangleSoupDistance {
 public:
  /// \throw InvalidInputError for an index out of range, a non-finite position used by a
  ///        triangle, or no non-degenerate triangle.
  TriangleSoupDistance(const Eigen::MatrixX3d& positions,
                       const std::vector<std::array<int, 3>>& triangles);
  ~TriangleSoupDistance();
  TriangleSoupDistance(const TriangleSoupDistance&) = delete;
  TriangleSoupDistance& operator=(const TriangleSoupDistance&) = delete;

  [[nodiscard]] SoupHit closest(const Eigen::Vector3d& query) const;
  /// closest(query) searched from `hint`, this tree's answer for another query: the search
  /// starts within the hint's distance instead of a nearest-vertex look-up, so a nearby query's
  /// hint makes it faster. The same distance; between primitives at exactly equal distance the
  /// one returned may differ.
  /// \throw InvalidInputError when hint.primitive is not a triangle of the tree.
  [[nodiscard]] SoupHit closest(const Eigen::Vector3d& query, const SoupHit& hint) const;
  /// Distance of every row of `queries` (#Q by 3).
  [[nodiscard]] Eigen::VectorXd distances(const Eigen::MatrixX3d& queries) const;
  /// Triangles kept in the tree (the non-degenerate ones).
  [[nodiscard]] int triangle_count() const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

/// Closest points on segments (pairs of rows of `positions`); zero-length segments are kept as
/// points. \throw InvalidInputError for an index out of range, a non-finite position or no
/// segment.
class SegmentSoupDistance {
 public:
  SegmentSoupDistance(const Eigen::MatrixX3d& positions,
                      const std::vector<std::array<int, 2>>& segments);
  ~SegmentSoupDistance();
  SegmentSoupDistance(const SegmentSoupDistance&) = delete;
  SegmentSoupDistance& operator=(const SegmentSoupDistance&) = delete;

  [[nodiscard]] SoupHit closest(const Eigen::Vector3d& query) const;
  [[nodiscard]] Eigen::VectorXd distances(const Eigen::MatrixX3d& queries) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace ricci
