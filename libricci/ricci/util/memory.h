#pragma once
// Returning freed memory to the system between the stages of a large computation.
//
// Why: glibc's malloc serves blocks below its (adaptive, up to 32 MB) mmap threshold from its
// heap and keeps them when freed; at 1.6M faces the choice's and the flow's per-vertex and
// per-edge arrays (6-32 MB each) leave hundreds of MB of freed but resident heap, which the
// next stage's factorisation adds to (docs/design-notes.md, "Memory at 1.6M faces by stage").
#include <cstddef>

namespace ricci {

/// Gives the allocator's free pages back to the system (glibc: malloc_trim(0)) when a problem
/// of `vertices` vertices is large enough for it to pay: from kReleaseFreeMemoryFromVertices.
/// Below, re-faulting the pages costs more time than the memory is worth (figures in
/// docs/design-notes.md, "The 1.6M-face peak back under 1.2e9 bytes"). Does nothing with
/// another C library. Call it between stages, not in loops.
void release_free_memory(std::size_t vertices);

/// The problem size (vertices) from which release_free_memory and use_one_malloc_arena act.
constexpr std::size_t kReleaseFreeMemoryFromVertices = 200000;

/// From kReleaseFreeMemoryFromVertices on, makes every thread allocate from the process's main
/// heap (glibc: mallopt(M_ARENA_MAX, 1)), so that release_free_memory also returns what worker
/// threads freed (malloc_trim cannot return the top of a thread's own arena). Below, threads
/// keep their arenas: one shared heap slows smaller, allocation-heavy runs. For applications,
/// before the computation's threads allocate (arenas made earlier stay in use). Does nothing
/// with another C library.
void use_one_malloc_arena(std::size_t vertices);

/// Below kReleaseFreeMemoryFromVertices, keeps freed blocks in the process for the next stage
/// (glibc: mallopt raises M_MMAP_THRESHOLD to kKeptBlockBytes and M_TRIM_THRESHOLD to twice
/// that). A fit's stages allocate and free arrays of 1-30 MB; by default glibc maps and unmaps
/// them, so that each stage faults its pages in again (figures in docs/design-notes.md, "Freed
/// memory kept below 200k vertices"). From there on it does nothing: peak memory matters more
/// there (release_free_memory). Process-wide, for applications, once before the computation.
/// Does nothing with another C library.
void keep_freed_memory(std::size_t vertices);

/// Largest block keep_freed_memory has the allocator take from its heap rather than map.
constexpr std::size_t kKeptBlockBytes = std::size_t{256} << 20;

}  // namespace ricci
