#pragma once
// A planar DMS spline space: a triangulation in the plane (a chart, or a planar domain), a knot
// cloud per vertex, and the (n + 1)(n + 2)/2 basis functions N_{I,beta} of every triangle I
// (triangle_basis.h). Function index of (I, beta): I * functions_per_triangle + position of beta
// in multi_indices(n).
//
// Partition of unity and polynomial reproduction hold at u when every triangle whose functions
// reach u is present, e.g. for u in a triangle all of whose vertices are interior vertices: each
// N_{J,beta} is supported in the hull of J's clouds, J slightly enlarged by the cloud radii.
//
// Cost: msp-bench dms prints it (docs/design-notes.md, "DMS basis", has figures). Queries are
// const and thread-safe.
#include <Eigen/Core>
#include <vector>

#include "spline/basis/blossom.h"
#include "spline/basis/multi_index.h"
#include "spline/basis/triangle_basis.h"
#include "spline/knots/knot_cloud.h"
#include "spline/planar/triangulation.h"

namespace spline {

/// One basis function N_{I,beta}.
struct BasisFunctionId {
  int triangle = 0;
  int beta = 0;  ///< position in multi_indices(n)
};

/// A basis function with its value and derivatives at a point.
struct BasisSample {
  int triangle = 0;
  int beta = 0;  ///< position in multi_indices(n)
  Jet jet;
};

/// Value, gradient and Hessian of a spline with control points in R^k at a point.
struct SplineJet {
  Eigen::VectorXd value;     ///< k
  Eigen::MatrixXd gradient;  ///< k x 2: d/dx, d/dy
  Eigen::MatrixXd hessian;   ///< k x 3: d2/dx2, d2/dxdy, d2/dy2
};

class PlanarDmsSpace {
 public:
  /// \pre clouds[v].knots[0] == positions[v], all clouds of one degree n in 1..kMaxDmsDegree.
  /// \throw ricci::InvalidInputError on an invalid triangulation (validate()), a cloud count other
  ///        than the vertex count, unequal degrees, or a cloud not starting at its vertex.
  PlanarDmsSpace(PlanarTriangulation triangulation, std::vector<KnotCloud> clouds);

  [[nodiscard]] int degree() const { return degree_; }
  [[nodiscard]] int triangle_count() const { return static_cast<int>(bases_.size()); }
  [[nodiscard]] int functions_per_triangle() const { return multi_index_count(degree_); }
  [[nodiscard]] int function_count() const { return triangle_count() * functions_per_triangle(); }
  [[nodiscard]] int function_index(int triangle, int beta) const {
    return triangle * functions_per_triangle() + beta;
  }
  [[nodiscard]] const PlanarTriangulation& triangulation() const { return triangulation_; }
  [[nodiscard]] const std::vector<KnotCloud>& clouds() const { return clouds_; }
  [[nodiscard]] const TriangleBasis& triangle_basis(int triangle) const {
    return bases_[static_cast<std::size_t>(triangle)];
  }

  /// The (I, beta) whose support (closed hull of V_beta^I) contains u.
  [[nodiscard]] std::vector<BasisFunctionId> support(const Eigen::Vector2d& u) const;

  /// Triangles whose clouds' convex hull contains u (candidates for non-zero functions).
  [[nodiscard]] std::vector<int> candidate_triangles(const Eigen::Vector2d& u) const;

  /// All basis functions with a non-zero value or derivative at u (BasisDerivatives::none:
  /// with a non-zero value, and the jets hold values only; first: with a non-zero value or
  /// gradient, Hessians zero).
  [[nodiscard]] std::vector<BasisSample> evaluate_basis(
      const Eigen::Vector2d& u, const TieBreak& tie = {},
      BasisDerivatives derivatives = BasisDerivatives::second) const;

  /// As evaluate_basis, over the given triangles only (ascending; those whose clouds' hull does
  /// not contain u are skipped): appends to `out`. For callers that know which triangles can
  /// matter (a manifold space keeps the ones around a point's face).
  void evaluate_basis_of(const Eigen::Vector2d& u, const std::vector<int>& triangles,
                         const TieBreak& tie, BasisDerivatives derivatives,
                         std::vector<BasisSample>& out) const;

  /// sum c_{I,beta} N_{I,beta} at u; control_points has function_count() rows, k columns.
  /// \throw ricci::InvalidInputError on a wrong row count.
  [[nodiscard]] SplineJet evaluate(const Eigen::Ref<const Eigen::MatrixXd>& control_points,
                                   const Eigen::Vector2d& u, const TieBreak& tie = {}) const;

  /// D_d^k of the spline for k = 0..max_order: (max_order + 1) x k.
  [[nodiscard]] Eigen::MatrixXd evaluate_directional(
      const Eigen::Ref<const Eigen::MatrixXd>& control_points, const Eigen::Vector2d& u,
      const Eigen::Vector2d& direction, int max_order, const TieBreak& tie = {}) const;

  /// Control points reproducing p (degree <= n) on every triangle: function_count() x k.
  [[nodiscard]] Eigen::MatrixXd control_points_of(const BivariatePolynomial& p) const;

 private:
  void build_grid();
  // Triangles whose cloud box meets u's grid cell (or a neighbouring one when u is on a cell
  // border), ascending: a superset of candidate_triangles(u).
  [[nodiscard]] std::vector<int> grid_triangles(const Eigen::Vector2d& u) const;
  void check_rows(const Eigen::Ref<const Eigen::MatrixXd>& control_points) const;
  template <int K>
  [[nodiscard]] SplineJet sum_jets(const Eigen::Ref<const Eigen::MatrixXd>& control_points,
                                   const std::vector<BasisSample>& samples) const;

  PlanarTriangulation triangulation_;
  std::vector<KnotCloud> clouds_;
  int degree_ = 0;
  std::vector<TriangleBasis> bases_;
  // Uniform grid over the triangles' cloud boxes: cell -> triangles whose box meets it.
  Eigen::Vector2d grid_origin_ = Eigen::Vector2d::Zero();
  double cell_size_ = 1.0;
  int columns_ = 0, rows_ = 0;
  std::vector<std::vector<int>> cells_;
};

}  // namespace spline
