#pragma once
// Fitted manifold splines of real models (fit_scan on a simplified domain), built once per
// binary: the surfaces whose rims the fill tests fill.
#include <map>
#include <memory>
#include <string>

#include "ricci/mesh/io.h"
#include "spline/fit/fit.h"
#include "test_paths.h"

namespace spline::testing {

/// fit_scan of the model at `path` (absolute) with a domain of about `faces` faces and
/// `cone_levels` levels of refinement around the cone (ricci::ConeRefinementOptions; -1: the
/// pipeline's default); `smoothing` >= 0 sets FitOptions::smoothing and sparse_smoothing both.
inline const ScanFitResult& fitted_scan(const std::string& path, int faces = 1000,
                                        int cone_levels = -1, double smoothing = -1.0) {
  static std::map<std::string, std::unique_ptr<ScanFitResult>> cache;
  auto& slot = cache[path + "/" + std::to_string(faces) + "/" + std::to_string(cone_levels) +
                     "/" + std::to_string(smoothing)];
  if (!slot) {
    ScanFitOptions options;
    options.domain_faces = faces;
    if (cone_levels >= 0) options.atlas.cone_refinement.levels = cone_levels;
    if (smoothing >= 0.0) options.fit.smoothing = options.fit.sparse_smoothing = smoothing;
    slot = std::make_unique<ScanFitResult>(fit_scan(ricci::read_mesh(path), options));
  }
  return *slot;
}


}  // namespace spline::testing
