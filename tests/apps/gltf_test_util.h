#pragma once
// Helpers for the glTF tests: running the Khronos validator (tools/validate.mjs) on a file.
#include <array>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace msp_test {

/// The validator's JSON report of `path`, or nullopt when node or tools/node_modules is missing
/// (the install script installs both; the caller then skips).
inline std::optional<nlohmann::json> run_gltf_validator(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path tools = fs::path(MSP_SOURCE_DIR) / "tools";
  if (!fs::exists(tools / "node_modules" / "gltf-validator")) return std::nullopt;
  if (std::system("command -v node >/dev/null 2>&1") != 0) return std::nullopt;
  const std::string command =
      "node '" + (tools / "validate.mjs").string() + "' --json '" + path + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return std::nullopt;
  std::string output;
  std::array<char, 4096> chunk{};
  while (size_t n = fread(chunk.data(), 1, chunk.size(), pipe)) output.append(chunk.data(), n);
  pclose(pipe);
  return nlohmann::json::parse(output, nullptr, false);
}

}  // namespace msp_test
