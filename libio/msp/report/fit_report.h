#pragma once
// The JSON report of `msp fit` (issue 6) and of the Python binding's fit: spline::fit_surface's
// figures under the report's keys.
#include <string>

#include <spline/surface/fit_surface.h>
#include <nlohmann/json.hpp>

namespace msp {

/// genus, singularities, domain_faces, control_points, degree, fairness, fit_rms, fit_max,
/// bbox_diagonal, seam_normal_jump_max_deg, watertight, seconds (per stage and total), plus the
/// figures behind them. `path` is the input's name as given.
[[nodiscard]] nlohmann::json fit_report_json(const std::string& path,
                                             const spline::FittedSurface& fitted,
                                             const spline::FitSurfaceOptions& options);

}  // namespace msp
