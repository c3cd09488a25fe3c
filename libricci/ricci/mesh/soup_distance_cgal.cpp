#include "ricci/mesh/soup_distance.h"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include <cmath>
#include <string>
#include <utility>

#include "ricci/mesh/cgal_convert.h"
#include "ricci/mesh/errors.h"

namespace ricci {
namespace {

using cgal::Kernel;
using cgal::Point3;
using Triangle3 = Kernel::Triangle_3;
using Segment3 = Kernel::Segment_3;
using TriangleIterator = std::vector<Triangle3>::const_iterator;
using SegmentIterator = std::vector<Segment3>::const_iterator;
using TrianglePrimitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using SegmentPrimitive = CGAL::AABB_segment_primitive<Kernel, SegmentIterator>;
using TriangleTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, TrianglePrimitive>>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>>;

// The row `index` of `positions` as a CGAL point, checked.
Point3 checked_point(const Eigen::MatrixX3d& positions, int index, const char* what) {
  if (index < 0 || index >= positions.rows()) {
    throw InvalidInputError(std::string(what) + ": index " + std::to_string(index) +
                            " out of range (" + std::to_string(positions.rows()) + " positions)");
  }
  const Eigen::Vector3d p = positions.row(index).transpose();
  if (!p.allFinite()) {
    throw InvalidInputError(std::string(what) + ": position " + std::to_string(index) +
                            " is not finite");
  }
  return Point3(p.x(), p.y(), p.z());
}

Eigen::Vector3d to_vector(const Point3& p) { return Eigen::Vector3d(p.x(), p.y(), p.z()); }

// The nearest primitive of a tree holding `first`'s primitives; `original` maps their order to
// the soup's indices.
template <class Iterator>
SoupHit hit_of(const Point3& point, Iterator primitive, Iterator first,
               const std::vector<int>& original, const Eigen::Vector3d& query) {
  SoupHit hit;
  hit.primitive = original[static_cast<std::size_t>(primitive - first)];
  hit.point = to_vector(point);
  hit.distance = (hit.point - query).norm();
  return hit;
}

template <class Tree, class Iterator>
SoupHit closest_in(const Tree& tree, Iterator first, const std::vector<int>& original,
                   const Eigen::Vector3d& query) {
  const auto [point, primitive] =
      tree.closest_point_and_primitive(Point3(query.x(), query.y(), query.z()));
  return hit_of(point, primitive, first, original, query);
}

}  // namespace

struct TriangleSoupDistance::Tree {
  std::vector<Triangle3> triangles;
  std::vector<int> original;  // soup index of each kept triangle
  std::vector<int> kept;      // by soup index: its place in `triangles`, -1 if left out
  CGAL::AABB_tree<CGAL::AABB_traits<Kernel, TrianglePrimitive>> tree;
  TriangleIterator first;
};

TriangleSoupDistance::TriangleSoupDistance(const Eigen::MatrixX3d& positions,
                                           const std::vector<std::array<int, 3>>& triangles)
    : tree_(std::make_unique<Tree>()) {
  tree_->triangles.reserve(triangles.size());
  tree_->kept.assign(triangles.size(), -1);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const Triangle3 triangle(checked_point(positions, tri[0], "triangle soup"),
                             checked_point(positions, tri[1], "triangle soup"),
                             checked_point(positions, tri[2], "triangle soup"));
    if (triangle.is_degenerate()) continue;
    tree_->kept[t] = static_cast<int>(tree_->triangles.size());
    tree_->triangles.push_back(triangle);
    tree_->original.push_back(static_cast<int>(t));
  }
  if (tree_->triangles.empty()) {
    throw InvalidInputError("triangle soup: no non-degenerate triangle");
  }
  tree_->first = tree_->triangles.cbegin();
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
}

TriangleSoupDistance::~TriangleSoupDistance() = default;

int TriangleSoupDistance::triangle_count() const {
  return static_cast<int>(tree_->triangles.size());
}

SoupHit TriangleSoupDistance::closest(const Eigen::Vector3d& query) const {
  return closest_in(tree_->tree, tree_->first, tree_->original, query);
}

SoupHit TriangleSoupDistance::closest(const Eigen::Vector3d& query, const SoupHit& hint) const {
  const auto& kept = tree_->kept;
  if (hint.primitive < 0 || hint.primitive >= static_cast<int>(kept.size()) ||
      kept[static_cast<std::size_t>(hint.primitive)] < 0) {
    throw InvalidInputError("triangle soup: hint primitive " + std::to_string(hint.primitive) +
                            " is not a triangle of the tree");
  }
  const auto start = std::make_pair(Point3(hint.point.x(), hint.point.y(), hint.point.z()),
                                    tree_->first + kept[static_cast<std::size_t>(hint.primitive)]);
  const auto [point, primitive] =
      tree_->tree.closest_point_and_primitive(Point3(query.x(), query.y(), query.z()), start);
  return hit_of(point, primitive, tree_->first, tree_->original, query);
}

Eigen::VectorXd TriangleSoupDistance::distances(const Eigen::MatrixX3d& queries) const {
  Eigen::VectorXd out(queries.rows());
  for (Eigen::Index i = 0; i < queries.rows(); ++i) {
    const Eigen::Vector3d q = queries.row(i).transpose();
    const Point3 p(q.x(), q.y(), q.z());
    out[i] = std::sqrt(CGAL::to_double(tree_->tree.squared_distance(p)));
  }
  return out;
}

struct SegmentSoupDistance::Tree {
  std::vector<Segment3> segments;
  std::vector<int> original;
  CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>> tree;
  SegmentIterator first;
};

SegmentSoupDistance::SegmentSoupDistance(const Eigen::MatrixX3d& positions,
                                         const std::vector<std::array<int, 2>>& segments)
    : tree_(std::make_unique<Tree>()) {
  tree_->segments.reserve(segments.size());
  for (std::size_t s = 0; s < segments.size(); ++s) {
    tree_->segments.emplace_back(checked_point(positions, segments[s][0], "segment soup"),
                                 checked_point(positions, segments[s][1], "segment soup"));
    tree_->original.push_back(static_cast<int>(s));
  }
  if (tree_->segments.empty()) throw InvalidInputError("segment soup: no segment");
  tree_->first = tree_->segments.cbegin();
  tree_->tree.insert(tree_->segments.cbegin(), tree_->segments.cend());
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
}

SegmentSoupDistance::~SegmentSoupDistance() = default;

SoupHit SegmentSoupDistance::closest(const Eigen::Vector3d& query) const {
  return closest_in(tree_->tree, tree_->first, tree_->original, query);
}

Eigen::VectorXd SegmentSoupDistance::distances(const Eigen::MatrixX3d& queries) const {
  Eigen::VectorXd out(queries.rows());
  for (Eigen::Index i = 0; i < queries.rows(); ++i) out[i] = closest(queries.row(i)).distance;
  return out;
}

}  // namespace ricci
