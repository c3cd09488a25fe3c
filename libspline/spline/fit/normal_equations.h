#pragma once
// Normal equations of a least-squares problem over a manifold spline space, assembled face by
// face. Every row of face I (a data point in I, a thin-plate quadrature row of I) involves only
// functions of I's reaching faces (ManifoldSplineSpace::reaching_faces, about 13 faces), so the
// rows of one face accumulate into a small dense local Gram matrix (each sparse row adds its own
// outer product), whose non-zeros are then added to the global lower triangle. This replaces a
// sparse A^T A product over all rows, whose per-entry cost dominated the fit on large point sets
// (msp-bench spline, horse row).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <vector>

#include "spline/manifold/manifold_space.h"

namespace spline::detail {

/// Rows of one face: data points (value rows) and thin-plate quadrature points (three Hessian
/// rows each), all evaluated in chart_of(face).
struct FaceRowsSpec {
  std::vector<int> points;              ///< indices into the parameters / points
  double thin_plate_weight = 0.0;       ///< per unit of quadrature weight (0: no thin-plate rows)
};

/// The data rows of one face, kept so the residuals need no second evaluation: row i (the i-th
/// point of the face) has entries start[i] .. start[i + 1] - 1.
struct FaceDataRows {
  std::vector<int> start{0};
  std::vector<int> function;
  std::vector<double> value;
  std::vector<Eigen::Vector2d> gradient;  ///< empty unless the assembly was asked to keep them
};

/// Basis samples a step already evaluated at the points, for a later step to take instead of
/// evaluating them again: the correction's projections start from the fit's (values and
/// gradients) and end with the refit's (values). Point k's samples, in
/// ManifoldSplineSpace::evaluate_basis' order in chart_of(face), are entries first[k] ..
/// first[k] + count[k] - 1 of block[k]'s arrays (blocks: each written by one thread), valid at
/// the parameter at[k] (face -1: none kept). gradient is empty when only values were kept.
/// Callers take them only where at[k] equals their own parameter bit for bit.
struct PointBasisValues {
  std::vector<DomainPoint> at;
  std::vector<int> block, first, count;
  std::vector<std::vector<int>> function;
  std::vector<std::vector<double>> value;
  std::vector<std::vector<Eigen::Vector2d>> gradient;

  /// Whether point k's values are kept for the parameter p.
  [[nodiscard]] bool holds(std::size_t k, const DomainPoint& p) const {
    return k < at.size() && at[k].face >= 0 && at[k].face == p.face &&
           at[k].barycentric == p.barycentric;
  }
  /// Whether point k's gradients are kept too.
  [[nodiscard]] bool holds_gradients(std::size_t k, const DomainPoint& p) const {
    return holds(k, p) && !gradient.empty();
  }
};

struct NormalEquations {
  Eigen::SparseMatrix<double> lower;  ///< lower triangle of A^T A (+ anchor on the diagonal)
  Eigen::MatrixX3d rhs;               ///< A^T b (+ anchor * initial)
  std::vector<FaceDataRows> data_rows;  ///< by domain face
};

/// Sum over faces (by domain index) of B_I^T B_I and B_I^T targets, plus anchor * I and
/// anchor * initial. Faces are split between `threads` workers (each with its own accumulator,
/// summed in a fixed order: the result does not depend on scheduling). `known`: values already
/// evaluated at some points (the same bits as evaluating them here), or null. keep_gradients:
/// the data rows also keep the basis gradients (FaceDataRows::gradient).
/// \throw as ManifoldSplineSpace::evaluate_basis.
[[nodiscard]] NormalEquations assemble_normal_equations(
    const ManifoldSplineSpace& space, const std::vector<FaceRowsSpec>& rows_by_face,
    const std::vector<DomainPoint>& parameters, const Eigen::MatrixX3d& points, double anchor,
    const Eigen::MatrixX3d& initial, int threads, const PointBasisValues* known = nullptr,
    bool keep_gradients = false);

/// The data rows' samples (moved out of `equations`) as PointBasisValues at `parameters`, the
/// points of rows_by_face; the other points hold none.
[[nodiscard]] PointBasisValues take_data_rows(NormalEquations& equations,
                                              const std::vector<FaceRowsSpec>& rows_by_face,
                                              const std::vector<DomainPoint>& parameters);

/// F(u_k) - p_k for every point listed in rows_by_face (others: zero rows), from the kept rows.
[[nodiscard]] Eigen::MatrixX3d residuals_at_parameters(const NormalEquations& equations,
                                                       const std::vector<FaceRowsSpec>& rows_by_face,
                                                       const Eigen::MatrixX3d& points,
                                                       const Eigen::MatrixX3d& control_points);

/// The 6-point quadrature rule on a triangle (Dunavant, exact for degree 4): barycentrics and
/// weights summing to one.
struct QuadraturePoint {
  Eigen::Vector3d bary;
  double weight;
};
[[nodiscard]] const std::vector<QuadraturePoint>& triangle_quadrature();

}  // namespace spline::detail
