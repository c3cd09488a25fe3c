#pragma once
// Runs CHOLMOD's BLAS calls on the calling thread only, for the lifetime of a scope.
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

}  // namespace ricci
