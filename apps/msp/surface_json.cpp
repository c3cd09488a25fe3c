#include "msp/surface_json.h"

#include <cstdio>
#include <string>

#include <spline/basis/multi_index.h>

namespace msp {
namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// Shortest text that reads back as the same double.
std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

void write_triple(std::ostream& out, double a, double b, double c) {
  out << '[' << number(a) << ',' << number(b) << ',' << number(c) << ']';
}

}  // namespace

nlohmann::json location_json(const spline::SurfaceLocation& location) {
  if (location.fill >= 0) {
    return {{"fill", location.fill},
            {"parameter", {location.fill_parameter.x(), location.fill_parameter.y()}}};
  }
  return {{"face", location.point.face}, {"barycentric", vector_json(location.point.barycentric)}};
}

nlohmann::json differential_json(const spline::SurfaceDifferential& d) {
  return {{"location", location_json(d.location)},
          {"chart", d.chart},
          {"position", vector_json(d.position)},
          {"du", vector_json(d.du)},
          {"dv", vector_json(d.dv)},
          {"duu", vector_json(d.duu)},
          {"duv", vector_json(d.duv)},
          {"dvv", vector_json(d.dvv)},
          {"normal", vector_json(d.normal)},
          {"gaussian_curvature", d.curvature.gaussian},
          {"mean_curvature", d.curvature.mean},
          {"principal_curvatures", {d.curvature.k1, d.curvature.k2}}};
}

void write_bezier_json(const spline::BezierExport& patches, std::ostream& out) {
  out << "{\"format\":\"msp-bezier\",\"version\":1,\"degree\":" << patches.degree
      << ",\"multi_indices\":[";
  const auto betas = spline::multi_indices(patches.degree);
  for (std::size_t i = 0; i < betas.size(); ++i) {
    out << (i ? "," : "") << '[' << betas[i][0] << ',' << betas[i][1] << ',' << betas[i][2]
        << ']';
  }
  out << "],\"faces\":" << patches.faces << ",\"patches\":[";
  for (std::size_t p = 0; p < patches.patches.size(); ++p) {
    const spline::BezierPatch& patch = patches.patches[p];
    out << (p ? ",\n" : "\n") << "{\"face\":" << patch.face << ",\"vertices\":["
        << patch.vertices[0] << ',' << patch.vertices[1] << ',' << patch.vertices[2]
        << "],\"corners\":[";
    for (int k = 0; k < 3; ++k) {
      if (k) out << ',';
      write_triple(out, patch.corners(0, k), patch.corners(1, k), patch.corners(2, k));
    }
    out << "],\"control_points\":[";
    for (Eigen::Index r = 0; r < patch.control_points.rows(); ++r) {
      if (r) out << ',';
      write_triple(out, patch.control_points(r, 0), patch.control_points(r, 1),
                   patch.control_points(r, 2));
    }
    out << "]}";
  }
  out << "\n]}\n";
}

}  // namespace msp
