#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

#include <unistd.h>

#include "ricci/util/memory.h"

// Defined when AddressSanitizer's runtime is linked in (its allocator ignores malloc_trim),
// whether or not this file was compiled with it (scripts/sanitize-launcher.sh instruments a
// few sources and links the whole program with the runtime).
extern "C" void __asan_init() __attribute__((weak));
// The same for ThreadSanitizer's runtime, whose allocator ignores malloc_trim and mallopt too.
extern "C" void __tsan_init() __attribute__((weak));

namespace {

// Whether a sanitizer's allocator serves malloc: the glibc tunings under test do not apply.
bool sanitizer_allocator() { return &__asan_init != nullptr || &__tsan_init != nullptr; }

// Resident bytes of this process (Linux: /proc/self/statm).
long resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  long total = 0, resident = 0;
  statm >> total >> resident;
  return resident * sysconf(_SC_PAGESIZE);
}

}  // namespace

// release_free_memory gives freed heap pages back from its problem size on, and not below.
TEST(ReleaseFreeMemory, ReturnsFreedHeapPagesFromItsProblemSize) {
#if !defined(__GLIBC__) || !defined(__linux__)
  GTEST_SKIP() << "malloc_trim and /proc/self/statm: glibc on Linux only";
#else
  if (sanitizer_allocator()) GTEST_SKIP() << "a sanitizer's allocator: no malloc_trim";
  // 96 MB in 64 KB blocks (below the mmap threshold: on the heap), each followed by a small
  // block that stays, so that freeing the large ones leaves holes free() cannot trim.
  void* (*volatile allocate)(std::size_t) = std::malloc;  // not elided with its free
  constexpr std::size_t kBlock = 64 << 10;
  constexpr int kBlocks = 1536;
  std::vector<void*> large, small;
  for (int i = 0; i < kBlocks; ++i) {
    large.push_back(allocate(kBlock));
    std::memset(large.back(), 1, kBlock);
    small.push_back(allocate(64));
  }
  for (void* p : large) std::free(p);
  const long freed = resident_bytes();
  ricci::release_free_memory(ricci::kReleaseFreeMemoryFromVertices - 1);
  const long below = resident_bytes();
  ricci::release_free_memory(ricci::kReleaseFreeMemoryFromVertices);
  const long at = resident_bytes();
  for (void* p : small) std::free(p);
  constexpr long kMB = 1 << 20;
  EXPECT_LT(freed - below, 8 * kMB) << "trimmed below the problem size";
  EXPECT_GT(below - at, 64 * kMB) << "the freed heap stayed resident";
#endif
}

// keep_freed_memory leaves a large freed block resident below its problem size (glibc would
// otherwise have mapped it apart and unmapped it on free), and changes nothing from it on.
TEST(KeepFreedMemory, KeepsALargeFreedBlockBelowItsProblemSize) {
#if !defined(__GLIBC__) || !defined(__linux__)
  GTEST_SKIP() << "mallopt and /proc/self/statm: glibc on Linux only";
#else
  if (sanitizer_allocator()) GTEST_SKIP() << "a sanitizer's allocator: no mallopt";
  void* (*volatile allocate)(std::size_t) = std::malloc;  // not elided with its free
  constexpr long kMB = 1 << 20;
  constexpr std::size_t kBlock = 48 << 20;  // above glibc's largest adaptive mmap threshold
  const auto resident_after_free = [&] {
    void* p = allocate(kBlock);
    std::memset(p, 1, kBlock);
    const long used = resident_bytes();
    std::free(p);
    return used - resident_bytes();  // what the free gave back
  };
  ricci::keep_freed_memory(ricci::kReleaseFreeMemoryFromVertices);  // does nothing
  EXPECT_GT(resident_after_free(), 40 * kMB) << "glibc kept a mapped block";
  ricci::keep_freed_memory(ricci::kReleaseFreeMemoryFromVertices - 1);
  EXPECT_LT(resident_after_free(), 8 * kMB) << "the freed block went back to the system";
  ricci::release_free_memory(ricci::kReleaseFreeMemoryFromVertices);  // the test's 48 MB
#endif
}
