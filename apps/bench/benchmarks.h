#pragma once
// Entry points of msp-bench's benchmarks (one file each; the table is in main.cpp).
namespace msp::bench {

/// DMS basis: build cost, memory and evaluation cost per point for degrees 2..5.
int run_dms_benchmark(int argc, char** argv);

}  // namespace msp::bench
