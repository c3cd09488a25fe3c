#include "bench/child_run.h"

#include <sys/resource.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "bench/benchmarks.h"

namespace msp::bench {

std::string self_executable() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

ChildResult run_child(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) throw std::runtime_error("cannot start " + command);
  ChildResult result;
  char buffer[4096];
  while (fgets(buffer, sizeof buffer, pipe.get())) result.output += buffer;
  try {
    result.json = nlohmann::json::parse(result.output);
    result.parsed = true;
  } catch (const std::exception&) {
    result.parsed = false;
  }
  return result;
}

void print_child_row(nlohmann::json& row, const ricci::Mesh& mesh) {
  double cholesky_cpu = 0.0;
  row["cholesky"] = cotangent_cholesky_seconds(mesh, &cholesky_cpu);
  row["cholesky_cpu"] = cholesky_cpu;
  // The measure: the run's seconds in solves of the same mesh (wall and CPU).
  if (row.contains("total_with_choice")) {
    row["solves"] = row["total_with_choice"].get<double>() / row["cholesky"].get<double>();
    if (row.contains("cpu_total_with_choice") && cholesky_cpu > 0) {
      row["cpu_solves"] = row["cpu_total_with_choice"].get<double>() / cholesky_cpu;
    }
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  row["peak_mb"] = usage.ru_maxrss / 1024.0;
  std::cout << row.dump() << std::endl;
}

std::string case_label(const std::string& path, int levels) {
  std::string name = path.substr(path.find_last_of('/') + 1);
  if (levels) name += " /" + std::to_string(levels);
  return name;
}

}  // namespace msp::bench
