#include "ricci/flow/serial_blas.h"

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <memory>
#include <thread>

namespace {

using GetThreads = int (*)();
using SetThreads = void (*)(int);

GetThreads openblas_get() {
  return reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
}
SetThreads openblas_set() {
  return reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
}

TEST(SerialBlasScope, OneThreadInsideNestedScopesAndTheOldCountAfter) {
  const GetThreads get = openblas_get();
  const SetThreads set = openblas_set();
  if (get == nullptr || set == nullptr) GTEST_SKIP() << "the process' BLAS is not OpenBLAS";
  const int before = get();
  set(2);  // a count to restore, also on a one-core machine
  {
    const ricci::SerialBlasScope outer;
    EXPECT_EQ(get(), 1);
    {
      const ricci::SerialBlasScope inner;
      EXPECT_EQ(get(), 1);
    }
    EXPECT_EQ(get(), 1);  // the outer scope is still open
  }
  EXPECT_EQ(get(), 2);
  set(before);
}

TEST(SerialBlasScope, OverlappingScopesOnTwoThreadsRestoreOnceBothClose) {
  const GetThreads get = openblas_get();
  const SetThreads set = openblas_set();
  if (get == nullptr || set == nullptr) GTEST_SKIP() << "the process' BLAS is not OpenBLAS";
  const int before = get();
  set(2);
  auto first = std::make_unique<ricci::SerialBlasScope>();
  int inside_second = 0;
  std::thread other([&] {
    const ricci::SerialBlasScope second;
    first.reset();  // the first scope closes while the second is open
    inside_second = get();
  });
  other.join();
  EXPECT_EQ(inside_second, 1);
  EXPECT_EQ(get(), 2);
  set(before);
}

using GetLevels = int (*)();
using SetLevels = void (*)(int);

// Max-active-levels 0 inside (nested scopes too), the thread's old value after; another
// thread's value is its own and stays.
TEST(SerialOpenMpScope, NoActiveLevelInsideAndTheOldValueAfter) {
  const auto get = reinterpret_cast<GetLevels>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
  const auto set = reinterpret_cast<SetLevels>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  if (get == nullptr || set == nullptr) GTEST_SKIP() << "no OpenMP runtime in the process";
  const int before = get();
  set(3);
  {
    const ricci::SerialOpenMpScope outer;
    EXPECT_EQ(get(), 0);
    int other_thread = -1;
    std::thread other([&] { other_thread = get(); });
    other.join();
    EXPECT_GT(other_thread, 0);
    {
      const ricci::SerialOpenMpScope inner;
      EXPECT_EQ(get(), 0);
    }
    EXPECT_EQ(get(), 0);
  }
  EXPECT_EQ(get(), 3);
  set(before);
}

}  // namespace
