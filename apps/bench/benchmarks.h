#pragma once
// Entry points of the msp-bench benchmarks (one file each), dispatched by bench/main.cpp.
namespace msp::bench {

int run_flow_benchmark(int argc, char** argv);  // bench_flow.cpp
int run_flow_case(int argc, char** argv);       // bench_flow.cpp
int run_solver_benchmark(int argc, char** argv);  // bench_flow.cpp
int run_spline_benchmark(int argc, char** argv);      // bench_spline.cpp
int run_spline_fit_benchmark(int argc, char** argv);  // bench_spline.cpp

}  // namespace msp::bench
