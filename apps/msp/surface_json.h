#pragma once
// JSON of the surface evaluation API (spline/surface): one evaluated point for `msp eval`, and
// the Bezier export's file for `msp bezier` (format: docs/bezier.md).
#include <nlohmann/json.hpp>
#include <ostream>

#include <spline/surface/bezier.h>
#include <spline/surface/closest_point.h>
#include <spline/surface/evaluate.h>

namespace msp {

/// {face, barycentric} or {fill, parameter}.
[[nodiscard]] nlohmann::json location_json(const spline::SurfaceLocation& location);

/// location, chart, position, du, dv, duu, duv, dvv, normal, gaussian_curvature,
/// mean_curvature, principal_curvatures [k1, k2].
[[nodiscard]] nlohmann::json differential_json(const spline::SurfaceDifferential& d);

/// The Bezier export as the documented JSON file (streamed: it can be large).
void write_bezier_json(const spline::BezierExport& patches, std::ostream& out);

}  // namespace msp
