#pragma once
// Runs the real msp binary in a subprocess and captures its exit status, stdout and stderr
// (used by the info_*, models_* and bench_cli tests).
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace msp_test {

struct ProcessResult {
  int exit_status = -1;  ///< -1 when the process did not exit normally (crash, signal)
  std::string out;
  std::string err;
};

inline std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// Runs `binary` with `args`; stderr goes through a temporary file.
inline ProcessResult run_program(const std::string& binary, const std::vector<std::string>& args) {
  namespace fs = std::filesystem;
  static int counter = 0;
  const fs::path err_path =
      fs::temp_directory_path() /
      ("msp_info_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ".err");
  std::string command = shell_quote(binary);
  for (const auto& arg : args) command += " " + shell_quote(arg);
  command += " 2>" + shell_quote(err_path.string());
  ProcessResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[65536];
  size_t got;
  while ((got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.out.append(buffer, got);
  const int status = ::pclose(pipe);
  if (WIFEXITED(status)) result.exit_status = WEXITSTATUS(status);
  std::ifstream err(err_path);
  std::stringstream text;
  text << err.rdbuf();
  result.err = text.str();
  fs::remove(err_path);
  return result;
}

/// Runs MSP_BINARY (the msp tool) with `args`.
inline ProcessResult run_msp(const std::vector<std::string>& args) {
  return run_program(MSP_BINARY, args);
}

/// Number of lines of `text` ("a\n" and "a" are one line; "" is none).
inline int line_count(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  if (!text.empty() && text.back() != '\n') ++lines;
  return lines;
}

}  // namespace msp_test
