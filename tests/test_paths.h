// Where the tests find their meshes: the bundled models (models/) and the real meshes copied
// into tests/data/meshes/ (each file's source and licence in tests/data/meshes/INDEX.md). No
// test reads a file outside the repository.
#pragma once

#include <string>

namespace msp_test {

/// tests/data/meshes/RELATIVE, e.g. test_mesh("closed_g2/eight.off").
inline std::string test_mesh(const std::string& relative) {
  return std::string(MSP_TEST_DATA) + "/meshes/" + relative;
}

/// models/NAME, a bundled model, e.g. bundled_model("genus2.off").
inline std::string bundled_model(const std::string& name) {
  return std::string(MSP_SOURCE_DIR) + "/models/" + name;
}

}  // namespace msp_test
