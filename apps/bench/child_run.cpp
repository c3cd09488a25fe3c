#include "bench/child_run.h"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "bench/benchmarks.h"
#include "ricci/util/memory.h"

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

namespace {
double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}
}  // namespace

std::string memory_note() {
  long pages = 0, resident = 0;
  if (FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(statm);
  }
  constexpr double kMb = 1024.0 * 1024.0;
  const auto whole_mb = [](double bytes) { return std::to_string(static_cast<int>(bytes / kMb)); };
  const double page = static_cast<double>(sysconf(_SC_PAGESIZE));
  std::string note = "RSS " + whole_mb(static_cast<double>(resident) * page) + " MB";
#ifdef __GLIBC__
  const struct mallinfo2 heap = mallinfo2();
  note += ", allocated " + whole_mb(static_cast<double>(heap.uordblks + heap.hblkhd)) +
          " MB (mmapped " + whole_mb(static_cast<double>(heap.hblkhd)) + ")";
#endif
  return note;
}

void print_child_row(nlohmann::json& row, const ricci::Mesh& mesh) {
  // The run's own peak, before the reference factorisation (at 1.6M faces its factor and the
  // Laplacian's triplets beside the mesh rise above the pipeline's peak).
  row["peak_mb"] = peak_rss_mb();
  ricci::release_free_memory();  // the pipeline's freed heap is not the reference's
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
  row["peak_mb_with_cholesky"] = peak_rss_mb();
  std::cout << row.dump() << std::endl;
}

std::string case_label(const std::string& path, int levels) {
  std::string name = path.substr(path.find_last_of('/') + 1);
  if (levels) name += " /" + std::to_string(levels);
  return name;
}

}  // namespace msp::bench
