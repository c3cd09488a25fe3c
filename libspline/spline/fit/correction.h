#pragma once
// The parameter correction keeping the basis values its projections end with, for the refit's
// assembly (detail::PointBasisValues): fit_scan's refit then evaluates no point again.
#include <Eigen/Core>
#include <vector>

#include "spline/fit/fit.h"
#include "spline/fit/normal_equations.h"

namespace spline::detail {

/// correct_parameters; when `kept` is not null, it receives every point's basis values at its
/// corrected parameter where the projection evaluated them there (all but the points outside the
/// domain and those whose projection the rim refused).
/// \throw ricci::InvalidInputError as correct_parameters.
[[nodiscard]] CorrectedParameters correct_parameters_keeping(
    const ManifoldSpline& spline, const std::vector<DomainPoint>& parameters,
    const Eigen::MatrixX3d& points, int iterations, int threads, PointBasisValues* kept);

}  // namespace spline::detail
