#pragma once
// SplineSurfaces of the bundled models for the surface tests: fit_scan on a small domain (no
// cone refinement, to be fast), the cone's hole capped by fill_rim, the covered faces skipped.
// Built once per binary.
#include <map>
#include <memory>
#include <string>

#include "ricci/mesh/io.h"
#include "spline/fill/hole_fill.h"
#include "spline/fit/fit.h"
#include "spline/surface/spline_surface.h"

namespace spline::testing {

inline std::string bundled_model(const std::string& name) {
  return std::string(MSP_SOURCE_DIR) + "/models/" + name;
}

/// The surface of bundled model `name` with a domain of about `faces` faces.
inline const SplineSurface& fitted_surface(const std::string& name, int faces = 300) {
  static std::map<std::string, std::unique_ptr<SplineSurface>> cache;
  auto& slot = cache[name + "/" + std::to_string(faces)];
  if (slot) return *slot;
  ScanFitOptions options;
  options.domain_faces = faces;
  options.atlas.cone_refinement.levels = 0;
  ScanFitResult fit = fit_scan(ricci::read_mesh(bundled_model(name)), options);
  auto s = std::make_unique<SplineSurface>();
  s->domain = fit.atlas.problem.mesh;
  s->spline = fit.spline;
  s->singular_vertex = fit.atlas.problem.cone;
  const ManifoldSplineSpace& space = *s->spline.space;
  s->skipped_faces.assign(static_cast<std::size_t>(space.face_count()), 0);
  for (int f = 0; f < space.face_count(); ++f) s->skipped_faces[f] = space.in_domain(f) ? 0 : 1;
  for (const Rim& rim : find_rims(space, s->domain)) {
    for (int f : rim.covered_faces) s->skipped_faces[f] = 1;
    if (rim.kind == Rim::Kind::cone_hole) {
      s->fills.push_back(fill_rim(s->spline, s->domain, rim));
    } else {
      s->open_rims.push_back(rim);
    }
  }
  slot = std::move(s);
  return *slot;
}

}  // namespace spline::testing
