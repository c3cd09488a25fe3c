#pragma once
// Small one-cone atlases of the bundled models (simplified to a few hundred faces), built once.
#include <map>
#include <memory>
#include <string>

#include "ricci/mesh/io.h"
#include "ricci/mesh/simplify.h"
#include "ricci/pipeline/one_cone_atlas.h"
#include "spline/manifold/manifold_space.h"
#include "test_paths.h"

namespace spline::testing {

inline const ricci::OneConeAtlasResult& small_atlas(const std::string& model, int faces = 500) {
  static std::map<std::string, std::unique_ptr<ricci::OneConeAtlasResult>> cache;
  const std::string key = model + "/" + std::to_string(faces);
  auto& slot = cache[key];
  if (!slot) {
    const ricci::Mesh dense = ricci::read_mesh(msp_test::bundled_model(model));
    ricci::SimplifyOptions options;
    options.target_faces = faces;
    slot = std::make_unique<ricci::OneConeAtlasResult>(
        ricci::build_one_cone_atlas(ricci::simplify_mesh(dense, options).mesh));
  }
  return *slot;
}

inline std::shared_ptr<const ManifoldSplineSpace> small_space(const std::string& model, int degree,
                                                              int faces = 500) {
  const auto& a = small_atlas(model, faces);
  ManifoldSplineOptions options;
  options.degree = degree;
  return std::make_shared<const ManifoldSplineSpace>(a.problem.mesh, a.atlas, options);
}

}  // namespace spline::testing
