#pragma once
// Runs CHOLMOD's BLAS calls (SerialBlasScope) and its OpenMP loops (SerialOpenMpScope) on the
// calling thread only, for the lifetime of a scope.
//
// Why: OpenBLAS' worker threads spin while they wait for work; on the small supernodes of a
// surface mesh's factorisation they add CPU time without lowering wall time
// (docs/design-notes.md, "Serial BLAS").
//
// With another BLAS (no openblas_set_num_threads symbol in the process) the scope does nothing.
// Scopes may nest and overlap across threads: the first one entered sets one thread, the last
// one left restores the previous count. The thread count changes the order of some BLAS sums, so
// results move at rounding level.
namespace ricci {

class SerialBlasScope {
 public:
  SerialBlasScope();
  ~SerialBlasScope();
  SerialBlasScope(const SerialBlasScope&) = delete;
  SerialBlasScope& operator=(const SerialBlasScope&) = delete;
};

/// Runs the OpenMP regions the calling thread enters (CHOLMOD's own loops) on that thread only,
/// for the lifetime of the scope: OpenMP's max-active-levels is 0 on this thread, then restored.
///
/// Why: Debian's CHOLMOD asks for 4 OpenMP threads (a num_threads clause, so OMP_NUM_THREADS
/// does not reach it) for loops that copy and scatter a supernode; its workers spin and wake
/// through futexes at every supernode (docs/design-notes.md, "CHOLMOD's OpenMP"). The results
/// do not depend on the thread count. The setting is the thread's own (an OpenMP task ICV), so
/// make the scope on the thread that calls CHOLMOD. Without OpenMP in the process it does
/// nothing.
class SerialOpenMpScope {
 public:
  SerialOpenMpScope();
  ~SerialOpenMpScope();
  SerialOpenMpScope(const SerialOpenMpScope&) = delete;
  SerialOpenMpScope& operator=(const SerialOpenMpScope&) = delete;

 private:
  int saved_levels_ = -1;  // -1: nothing to restore
};

}  // namespace ricci
