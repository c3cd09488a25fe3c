#pragma once
// Atlases of test meshes built once per test binary (the pipeline takes 0.1-0.5 s each).
#include <string>

#include <ricci/mesh/io.h>
#include <ricci/pipeline/one_cone_atlas.h>
#include "test_paths.h"

namespace msp_test {

inline ricci::OneConeAtlasResult build_atlas(const std::string& model, int singular_vertex) {
  ricci::OneConeAtlasOptions options;
  options.singular_vertex = singular_vertex;
  return ricci::build_one_cone_atlas(ricci::read_mesh(msp_test::test_mesh(model)),
                                     options);
}

/// closed_g1/elk.off: a flat torus (no cone).
inline const ricci::OneConeAtlasResult& torus_atlas() {
  static const ricci::OneConeAtlasResult result = build_atlas("closed_g1/elk.off", -1);
  return result;
}

/// closed_g2/eight.off with its cone at vertex 570 (the automatic choice, given to save time).
inline const ricci::OneConeAtlasResult& genus2_atlas() {
  static const ricci::OneConeAtlasResult result = build_atlas("closed_g2/eight.off", 570);
  return result;
}

}  // namespace msp_test
