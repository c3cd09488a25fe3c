#pragma once
// SplineSurfaces of bundled models for the spline-file and editing tests: fit_scan on a small
// domain (no cone refinement, to stay fast), the rims of find_rims, the cone's hole filled by
// fill_rim, boundary rims left open, and the skipped faces as msp fit marks them.
#include <map>
#include <memory>
#include <string>

#include "spline/fill/fill_fixtures.h"
#include "spline/fill/hole_fill.h"
#include "spline/surface/spline_surface.h"

namespace spline::testing {

/// The surface of models/`model` at about `faces` domain faces; built once per binary.
inline const SplineSurface& small_surface(const std::string& model, int faces = 300) {
  static std::map<std::string, std::unique_ptr<SplineSurface>> cache;
  auto& slot = cache[model + "/" + std::to_string(faces)];
  if (!slot) {
    const ScanFitResult& fit = fitted_scan(bundled_model(model), faces, 0);
    auto surface = std::make_unique<SplineSurface>();
    surface->domain = fit.atlas.problem.mesh;
    surface->spline = fit.spline;
    surface->singular_vertex = fit.atlas.problem.cone;
    const ManifoldSplineSpace& space = *fit.spline.space;
    surface->skipped_faces.assign(surface->domain.n_faces(), 0);
    for (int f = 0; f < space.face_count(); ++f) surface->skipped_faces[f] = !space.in_domain(f);
    for (const Rim& rim : find_rims(space, surface->domain)) {
      for (int f : rim.covered_faces) surface->skipped_faces[f] = 1;
      if (rim.kind == Rim::Kind::boundary) {
        surface->open_rims.push_back(rim);
      } else {
        surface->fills.push_back(fill_rim(fit.spline, surface->domain, rim));
      }
    }
    slot = std::move(surface);
  }
  return *slot;
}

}  // namespace spline::testing
