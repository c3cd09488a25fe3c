#include "ricci/util/memory.h"

#include <cstdlib>  // a standard header first: it defines __GLIBC__ with the GNU C library

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ricci {

void release_free_memory(std::size_t vertices) {
#if defined(__GLIBC__)
  if (vertices >= kReleaseFreeMemoryFromVertices) malloc_trim(0);
#else
  (void)vertices;
#endif
}

void use_one_malloc_arena(std::size_t vertices) {
#if defined(__GLIBC__)
  if (vertices >= kReleaseFreeMemoryFromVertices) mallopt(M_ARENA_MAX, 1);
#else
  (void)vertices;
#endif
}

void keep_freed_memory(std::size_t vertices) {
#if defined(__GLIBC__)
  if (vertices >= kReleaseFreeMemoryFromVertices) return;
  mallopt(M_MMAP_THRESHOLD, static_cast<int>(kKeptBlockBytes));
  mallopt(M_TRIM_THRESHOLD, static_cast<int>(2 * kKeptBlockBytes));
#else
  (void)vertices;
#endif
}

}  // namespace ricci
