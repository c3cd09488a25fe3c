#include "ricci/flow/serial_blas.h"

#include <dlfcn.h>

#include <mutex>

namespace ricci {
namespace {

using GetThreads = int (*)();
using SetThreads = void (*)(int);

// OpenBLAS' thread controls, looked up once in the whole process (null with another BLAS): the
// BLAS is whichever libblas.so.3 the system's alternatives select, so it is not linked by name.
struct OpenBlasControls {
  GetThreads get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  SetThreads set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  [[nodiscard]] bool present() const { return get != nullptr && set != nullptr; }
};

const OpenBlasControls& controls() {
  static const OpenBlasControls c;
  return c;
}

using GetLevels = int (*)();
using SetLevels = void (*)(int);

// OpenMP's max-active-levels controls (null when no OpenMP runtime is loaded): libgomp comes
// with CHOLMOD, and the project itself is not compiled with OpenMP.
struct OpenMpControls {
  GetLevels get = reinterpret_cast<GetLevels>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
  SetLevels set = reinterpret_cast<SetLevels>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  [[nodiscard]] bool present() const { return get != nullptr && set != nullptr; }
};

const OpenMpControls& openmp_controls() {
  static const OpenMpControls c;
  return c;
}

std::mutex scope_mutex;
int open_scopes = 0;   // guarded by scope_mutex
int saved_threads = 0;  // the count before the first open scope

}  // namespace

SerialBlasScope::SerialBlasScope() {
  const OpenBlasControls& c = controls();
  if (!c.present()) return;
  const std::lock_guard<std::mutex> lock(scope_mutex);
  if (open_scopes++ == 0) {
    saved_threads = c.get();
    if (saved_threads != 1) c.set(1);
  }
}

SerialBlasScope::~SerialBlasScope() {
  const OpenBlasControls& c = controls();
  if (!c.present()) return;
  const std::lock_guard<std::mutex> lock(scope_mutex);
  if (--open_scopes == 0 && saved_threads != 1) c.set(saved_threads);
}

SerialOpenMpScope::SerialOpenMpScope() {
  const OpenMpControls& c = openmp_controls();
  if (!c.present()) return;
  saved_levels_ = c.get();
  // No active parallel region at level 0: every region runs on the encountering thread.
  if (saved_levels_ != 0) c.set(0);
}

SerialOpenMpScope::~SerialOpenMpScope() {
  if (saved_levels_ > 0) openmp_controls().set(saved_levels_);
}

}  // namespace ricci
