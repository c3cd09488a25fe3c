#pragma once
// The parameter correction taking the basis samples the fit's assembly evaluated at its start
// and keeping those its projections end with, for the refit's assembly
// (detail::PointBasisValues): each point's basis is evaluated once less at each end.
#include <Eigen/Core>
#include <vector>

#include "spline/fit/fit.h"
#include "spline/fit/normal_equations.h"

namespace spline::detail {

/// correct_parameters; `start`, when not null, holds basis values and gradients at (some of)
/// the parameters (the fit's assembly kept them: take_data_rows), which the projections take
/// instead of evaluating their starts; `kept`, when not null, receives every point's basis values
/// at its corrected parameter where the projection evaluated them there (all but the points
/// outside the domain and those whose projection the rim refused).
/// \throw ricci::InvalidInputError as correct_parameters.
[[nodiscard]] CorrectedParameters correct_parameters_keeping(
    const ManifoldSpline& spline, const std::vector<DomainPoint>& parameters,
    const Eigen::MatrixX3d& points, int iterations, int threads, const PointBasisValues* start,
    PointBasisValues* kept);

}  // namespace spline::detail
