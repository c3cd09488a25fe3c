#pragma once
// Runs CHOLMOD's BLAS calls on the calling thread only, for the lifetime of a scope.
//
// Why: the BLAS the project installs (OpenBLAS, pthread build) hands large enough level-3 calls
// to worker threads that spin (sched_yield) while they wait for work. On the supernodal
// factorisations of the fits (<= 50k unknowns, the sparsity of a surface mesh: small supernodes)
// they add CPU time without lowering wall time: measured on the 2-core machine (msp-bench spline
// Horse row plus four constrained fits, perf stat): 7.0-7.2 s of task clock with the default two
// BLAS threads, 5.5-5.6 s with one, wall time 5.4-5.5 s either way.
//
// With another BLAS (no openblas_set_num_threads symbol in the process) the scope does nothing.
// Scopes may nest and overlap across threads: the first one entered sets one thread, the last
// one left restores the previous count. The thread count changes the order of some BLAS sums, so
// results move at rounding level: `msp fit models/genus2.off` (one correction round, whose
// constrained solves amplify rounding) gives fit_rms 0.0027610148 with two threads and
// 0.0027610134 with one, the seam's normal jump 0.342891 and 0.342883 degrees.
namespace ricci {

class SerialBlasScope {
 public:
  SerialBlasScope();
  ~SerialBlasScope();
  SerialBlasScope(const SerialBlasScope&) = delete;
  SerialBlasScope& operator=(const SerialBlasScope&) = delete;
};

}  // namespace ricci
