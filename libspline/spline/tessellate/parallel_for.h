#pragma once
// libricci's thread pool (ricci/util/parallel.h) under libspline's names. Spline evaluations are
// thread-safe (ManifoldSplineSpace caches its chart spaces under once_flags).
#include "ricci/util/parallel.h"

namespace spline {

using ricci::parallel_for;
using ricci::parallel_thread_count;
using ricci::run_workers;

}  // namespace spline
