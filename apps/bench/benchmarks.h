#pragma once
// Entry points of the msp-bench benchmarks (one file each), dispatched by bench/main.cpp.
#include <string>

#include <Eigen/SparseCore>

#include "ricci/mesh/mesh.h"

namespace msp::bench {

/// The folder of the model collection the benchmarks read by default: the environment variable
/// MSP_SHARED_MODELS, else CMake's -DMSP_SHARED_MODELS=DIR (empty by default).
/// \throw std::runtime_error saying how to set it when neither names a folder.
std::string shared_models();

/// Seconds of one CHOLMOD supernodal analyse + factorise + solve of the mesh's cotangent
/// Laplacian (best of 3): the unit the benchmarks' ratios divide by (bench_one_cone.cpp).
double cotangent_cholesky_seconds(const ricci::Mesh& mesh, double* cpu_seconds = nullptr);

int run_flow_benchmark(int argc, char** argv);  // bench_flow.cpp
int run_flow_case(int argc, char** argv);       // bench_flow.cpp
int run_solver_benchmark(int argc, char** argv);  // bench_flow.cpp
int run_spline_benchmark(int argc, char** argv);      // bench_spline.cpp
int run_spline_fit_benchmark(int argc, char** argv);  // bench_spline.cpp
int run_mesh_io_benchmark(int argc, char** argv);  // bench_mesh_io.cpp

/// DMS basis: build cost, memory and evaluation cost per point for degrees 2..5.
int run_dms_benchmark(int argc, char** argv);  // bench_dms.cpp
int run_singularity_benchmark(int argc, char** argv);  // bench_singularity.cpp
int run_topology_benchmark(int argc, char** argv);  // bench_topology.cpp
int run_loop_benchmark(int argc, char** argv);    // bench_loop.cpp
int run_fill_benchmark(int argc, char** argv);    // bench_fill.cpp
/// Issue 19: cap_holes alone on `msp fit --spline` files: seconds, patch unknowns, seam.
int run_caps_benchmark(int argc, char** argv);  // bench_caps.cpp
int run_one_cone_benchmark(int argc, char** argv);  // bench_one_cone.cpp
int run_one_cone_case(int argc, char** argv);       // bench_one_cone.cpp
int run_atlas_replay(int argc, char** argv);        // bench_atlas_replay.cpp
/// Writes the flat metric of a one-cone run for `atlas-replay` (bench_atlas_replay.cpp).
void save_flat_metric(const std::string& path, const ricci::Mesh& mesh, const Eigen::VectorXd& lengths,
                      const Eigen::VectorXd& lengths_low, const Eigen::VectorXd& target, int root);
int run_intrinsic_benchmark(int argc, char** argv);  // bench_intrinsic.cpp

/// Lower triangle of the mesh's cotangent Laplacian plus 1e-8 times its mean diagonal (SPD).
Eigen::SparseMatrix<double> regularised_cotangent_laplacian(const ricci::Mesh& mesh);  // bench_one_cone.cpp
/// Best of 3 CHOLMOD supernodal analyse + factorise + solve of `L`, wall seconds (that run's CPU
/// seconds in `cpu_seconds` when given).
double one_cholesky_seconds(const Eigen::SparseMatrix<double>& L,
                            double* cpu_seconds = nullptr);  // bench_one_cone.cpp
int run_uniformize_benchmark(int argc, char** argv);  // bench_uniformize.cpp
/// The delivered .glb measured against its scan from outside (issue 15's checker).
int run_check_glb(int argc, char** argv);  // bench_check_glb.cpp
int run_eval_benchmark(int argc, char** argv);        // bench_surface.cpp
int run_bezier_benchmark(int argc, char** argv);      // bench_surface.cpp
int run_spline_file_benchmark(int argc, char** argv);  // bench_spline_file.cpp
/// Issue 17: conformal module and surface matching at ~20k and ~100k faces.
int run_match_benchmark(int argc, char** argv);  // bench_match.cpp
/// Issue 15: control points the adaptive and the uniform domain need for a fit RMS goal.
int run_adaptive_benchmark(int argc, char** argv);  // bench_adaptive.cpp
/// Issue 19: msp fit's stages at 1, 4 and 16 times a scan's faces (1.6M from venus).
int run_fit_scale_benchmark(int argc, char** argv);  // bench_fit_scale.cpp
int run_fit_scale_case(int argc, char** argv);       // bench_fit_scale.cpp
/// The mesh at `path` refined by midpoint subdivision `levels` times, every vertex then moved
/// along its normal by a seeded normal deviate of `sigma` bounding-box diagonals (scanner noise):
/// the larger scans of fit-scale and decimate (bench_fit_scale.cpp).
ricci::Mesh refined_scan(const std::string& path, int levels, double sigma);
/// ricci::quadric_decimate (msp fit's first simplification stage): CPU seconds and a hash of the
/// result, to check that a faster decimation collapses the same edges (bench_decimate.cpp).
int run_decimate_benchmark(int argc, char** argv);

}  // namespace msp::bench
