#pragma once
// Returning freed memory to the system between the stages of a large computation.
//
// Why: glibc's malloc serves blocks below its (adaptive, up to 32 MB) mmap threshold from its
// heap and keeps them when freed; at 1.6M faces the choice's and the flow's per-vertex and
// per-edge arrays (6-32 MB each) leave hundreds of MB of freed but resident heap, which the
// next stage's factorisation adds to (docs/design-notes.md, "Memory at 1.6M faces by stage").
namespace ricci {

/// Gives the allocator's free pages back to the system (glibc: malloc_trim(0)); does nothing
/// with another C library. Costs a walk of the heap's free lists and, later, the page faults of
/// reusing that memory: call it between stages, not in loops.
void release_free_memory();

}  // namespace ricci
