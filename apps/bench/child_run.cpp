#include "bench/child_run.h"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <thread>

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

// Resident pages now (/proc/self/statm; 0 when it cannot be read).
long resident_pages() {
  long pages = 0, resident = 0;
  if (FILE* statm = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(statm, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(statm);
  }
  return resident;
}
}  // namespace

std::string memory_note() {
  const long resident = resident_pages();
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

ReferenceSolve reference_solve(const ricci::Mesh& mesh) {
  ReferenceSolve reference;
  reference.seconds = cotangent_cholesky_seconds(mesh, &reference.cpu_seconds);
  ricci::release_free_memory(mesh.n_vertices());
  reference.peak_mb = peak_rss_mb();
  return reference;
}

struct RssSampler::State {
  std::atomic<bool> running{true};
  std::atomic<long> peak_pages{0}, window_pages{0};
  std::thread thread;
};

namespace {
// `peak` raised to `pages` (one writer: the sampling thread; window_peak_mb resets).
void raise_to(std::atomic<long>& peak, long pages) {
  long seen = peak.load();
  while (pages > seen && !peak.compare_exchange_weak(seen, pages)) {
  }
}

double pages_mb(long pages) {
  return static_cast<double>(pages) * static_cast<double>(sysconf(_SC_PAGESIZE)) /
         (1024.0 * 1024.0);
}
}  // namespace

RssSampler::RssSampler(int period_ms) : state_(std::make_unique<State>()) {
  State* state = state_.get();
  state->thread = std::thread([state, period_ms] {
    while (state->running.load()) {
      const long now = resident_pages();
      raise_to(state->peak_pages, now);
      raise_to(state->window_pages, now);
      std::this_thread::sleep_for(std::chrono::milliseconds(period_ms));
    }
  });
}

double RssSampler::window_peak_mb() {
  const long now = resident_pages();
  raise_to(state_->peak_pages, now);
  return pages_mb(std::max(state_->window_pages.exchange(now), now));
}

RssSampler::~RssSampler() { (void)stop(); }

double RssSampler::stop() {
  if (state_->thread.joinable()) {
    state_->running.store(false);
    state_->thread.join();
  }
  raise_to(state_->peak_pages, resident_pages());
  return pages_mb(state_->peak_pages.load());
}

void print_row_after_reference(nlohmann::json& row, const ReferenceSolve& reference) {
  row["cholesky"] = reference.seconds;
  row["cholesky_cpu"] = reference.cpu_seconds;
  if (row.contains("total_with_choice")) {
    row["solves"] = row["total_with_choice"].get<double>() / reference.seconds;
    if (row.contains("cpu_total_with_choice") && reference.cpu_seconds > 0) {
      row["cpu_solves"] = row["cpu_total_with_choice"].get<double>() / reference.cpu_seconds;
    }
  }
  row["reference_peak_mb"] = reference.peak_mb;
  row["peak_mb"] = peak_rss_mb();
  row["peak_mb_with_cholesky"] = row["peak_mb"];
  std::cout << row.dump() << std::endl;
}

void print_child_row(nlohmann::json& row, const ricci::Mesh& mesh) {
  // The run's own peak, before the reference factorisation (at 1.6M faces its factor and the
  // Laplacian's triplets beside the mesh rise above the pipeline's peak).
  row["peak_mb"] = peak_rss_mb();
  // the pipeline's freed heap is not the reference's
  ricci::release_free_memory(mesh.n_vertices());
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
