// msp-bench flow / flow-one / solvers: E2 Ricci-flow figures on real meshes refined by midpoint
// subdivision, each size in a child process so its peak memory is its own.
#include <sys/resource.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <nlohmann/json.hpp>
#include <ricci/flow/flow.h>
#include <ricci/flow/flow_state.h>
#include <ricci/flow/hessian.h>
#include <ricci/flow/linear_solver.h>
#include <ricci/mesh/io.h>
#include <ricci/metric/curvature.h>
#include <ricci/metric/subdivide.h>

#include "bench/benchmarks.h"
#include "bench/child_run.h"
#include "msp/cli.h"
#include "ricci/util/stopwatch.h"

namespace msp::bench {

namespace {

using Sparse = Eigen::SparseMatrix<double>;

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// A field of /proc/self/status in kB (VmRSS, VmHWM).
long status_kb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(field + ":", 0) == 0) return std::stol(line.substr(field.size() + 1));
  }
  return -1;
}

// Resets VmHWM to the current RSS (Linux clear_refs 5), so the next peak is the flow's own.
void reset_peak_memory() { std::ofstream("/proc/self/clear_refs") << "5"; }

ricci::Mesh load(const std::string& path, int levels) {
  ricci::Mesh mesh = ricci::read_mesh(path);
  for (int i = 0; i < levels; ++i) mesh = ricci::subdivide_midpoint(mesh);
  return mesh;
}

// Lower triangle of the cotangent Laplacian with vertex 0 dropped (SPD), the system a
// one-linear-solve method (BFF) factorises once.
Sparse cotangent_laplacian(const ricci::Mesh& mesh) {
  const ricci::MeshTables t = ricci::build_mesh_tables(mesh);
  const Eigen::MatrixX3d angles =
      ricci::corner_angles(t, ricci::mesh_edge_lengths(mesh), ricci::Geometry::euclidean);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(9 * t.num_faces());
  for (int f = 0; f < t.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int i = t.face_vertices(f, (k + 1) % 3) - 1, j = t.face_vertices(f, (k + 2) % 3) - 1;
      const double w = 0.5 / std::tan(angles(f, k));
      if (i >= 0) triplets.emplace_back(i, i, w);
      if (j >= 0) triplets.emplace_back(j, j, w);
      if (i >= 0 && j >= 0) triplets.emplace_back(std::max(i, j), std::min(i, j), -w);
    }
  }
  Sparse L(t.num_vertices() - 1, t.num_vertices() - 1);
  L.setFromTriplets(triplets.begin(), triplets.end());
  L.makeCompressed();
  return L;
}

// Best of `repeats` wall (and CPU) times of analyse + factorise + solve with the backend.
double one_cholesky_seconds(const Sparse& L, ricci::LinearSolver kind, int repeats, double& cpu) {
  double best = 1e300;
  cpu = 1e300;
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(L.rows());
  for (int r = 0; r < repeats; ++r) {
    ricci::SymmetricFactorization solver(kind);
    const ricci::Stopwatch t0;
    const double cpu0 = cpu_seconds();
    solver.analyze(L);
    if (!solver.factorize(L)) throw std::runtime_error("cotangent Laplacian factorisation failed");
    const Eigen::VectorXd x = solver.solve(rhs);
    best = std::min(best, t0.seconds());
    cpu = std::min(cpu, cpu_seconds() - cpu0);
    if (!x.allFinite()) throw std::runtime_error("cotangent Laplacian solve is not finite");
  }
  return best;
}

}  // namespace

int run_flow_case(int argc, char** argv) {
  Args args(argc, argv, {});
  args.require_known({"levels", "gradient-max-faces", "repeats"});
  args.require_positionals(1, "msp-bench flow-one MESH [--levels N] [--gradient-max-faces F]");
  const int levels = args.get_int("levels", 0);
  const ricci::Mesh mesh = load(args.positionals()[0], levels);
  const ricci::Targets target = ricci::uniform_target(mesh, ricci::Geometry::euclidean);
  ricci::FlowOptions options;
  options.fall_back_to_other_metrics = true;
  const int repeats = args.get_int("repeats", mesh.n_faces() > 500000 ? 1 : 2);

  reset_peak_memory();
  const long rss_before = status_kb("VmRSS");
  ricci::FlowResult best;
  double best_cpu = 0;
  for (int r = 0; r < repeats; ++r) {
    const double cpu0 = cpu_seconds();
    ricci::FlowResult result = ricci::flow(mesh, target, options);
    const double cpu = cpu_seconds() - cpu0;
    if (r == 0 || result.timings.total < best.timings.total) {
      best = std::move(result);
      best_cpu = cpu;
    }
  }
  const long peak = status_kb("VmHWM");

  const Sparse L = cotangent_laplacian(mesh);
  double cholesky_cpu = 0;
  const double cholesky =
      one_cholesky_seconds(L, ricci::LinearSolver::cholmod_supernodal, 3, cholesky_cpu);

  nlohmann::json j;
  j["mesh"] = args.positionals()[0];
  j["levels"] = levels;
  j["faces"] = mesh.n_faces();
  j["vertices"] = mesh.n_vertices();
  j["status"] = ricci::to_string(best.status);
  j["metric"] = ricci::to_string(best.metric.scheme);
  j["iterations"] = best.iterations;
  j["factorizations"] = best.factorizations;
  j["error"] = best.max_error;
  j["newton_seconds"] = best.timings.total;
  j["newton_cpu_seconds"] = best_cpu;
  j["factorization_seconds"] = best.timings.factorization + best.timings.analysis;
  j["evaluation_seconds"] = best.timings.evaluation;
  j["assembly_seconds"] = best.timings.assembly;
  j["flow_peak_mb"] = (peak - rss_before) / 1024.0;
  j["process_peak_mb"] = peak / 1024.0;
  j["cholesky_seconds"] = cholesky;
  j["cholesky_cpu_seconds"] = cholesky_cpu;
  if (static_cast<int>(mesh.n_faces()) <= args.get_int("gradient-max-faces", 0)) {
    ricci::FlowOptions gradient = options;
    gradient.fall_back_to_other_metrics = false;
    gradient.scheme = best.metric.scheme;
    gradient.method = ricci::FlowMethod::gradient_descent;
    gradient.max_gradient_iterations = 100000;
    const ricci::FlowResult g = ricci::flow(mesh, target, gradient);
    j["gradient_seconds"] = g.timings.total;
    j["gradient_iterations"] = g.iterations;
    j["gradient_status"] = ricci::to_string(g.status);
  }
  std::cout << j.dump() << std::endl;
  return 0;
}

int run_flow_benchmark(int argc, char** argv) {
  Args args(argc, argv, {"no-1m"});
  args.require_known({"no-1m", "gradient-max-faces"});
  const std::string gradient_max = std::to_string(args.get_int("gradient-max-faces", 7000));
  struct Case {
    std::string path;
    int levels;
  };
  const std::string self = self_executable();
  const std::string m = shared_models();
  std::vector<Case> cases = {{m + "/closed_g1/elk.off", 0},        {m + "/closed_g1/knot1.off", 0},
                             {m + "/bench/torus_10k.obj", 0},      {m + "/closed_g1/kitten_nf20k.off", 0},
                             {m + "/closed_g1/rocker-arm.off", 0}, {m + "/closed_g1/kitten_nf20k.off", 1},
                             {m + "/bench/torus_100k.obj", 0},     {m + "/closed_g1/rocker-arm.off", 1},
                             {m + "/closed_g1/kitten_nf20k.off", 2}};
  if (!args.has("no-1m")) cases.push_back({m + "/closed_g1/kitten_nf20k.off", 3});

  std::cout << "E2 flat metric (K = 0 on genus 1), tolerance 1e-10, default options with metric\n"
               "fall-back; 'newton s' is the wall time of ricci::flow (best of 2 below 500k faces,\n"
               "including any failed metric attempt), 'cpu s' its CPU time; 'chol s' is one CHOLMOD\n"
               "supernodal analyse + factorise + solve of the cotangent Laplacian (best of 3);\n"
               "'ratio' = newton s / chol s, 'cpu rat' the same in CPU time (robust to a loaded\n"
               "machine); 'flow MB' the peak RSS the flow adds; GD = gradient descent to 1e-10\n"
               "(+ = stopped at 100000 iterations).\n\n";
  std::cout << std::left << std::setw(26) << "mesh" << std::right << std::setw(9) << "faces"
            << std::setw(6) << "iter" << std::setw(10) << "error" << std::setw(10) << "newton s"
            << std::setw(9) << "cpu s" << std::setw(9) << "chol s" << std::setw(8) << "ratio" << std::setw(9) << "cpu rat"
            << std::setw(10) << "flow MB" << std::setw(9) << "B/face" << std::setw(10) << "GD s"
            << std::setw(9) << "GD iter"
            << "  metric\n";
  for (const Case& c : cases) {
    const std::string command = "'" + self + "' flow-one '" + c.path + "' --levels " +
                                std::to_string(c.levels) + " --gradient-max-faces " + gradient_max;
    const ChildResult child = run_child(command);
    const std::string name = case_label(c.path, c.levels);
    if (!child.parsed) {
      std::cout << std::left << std::setw(26) << name << " failed (child output: " << child.output
                << ")\n";
      continue;
    }
    const nlohmann::json& j = child.json;
    const double ratio = j["newton_seconds"].get<double>() / j["cholesky_seconds"].get<double>();
    const double cpu_ratio =
        j["newton_cpu_seconds"].get<double>() / j["cholesky_cpu_seconds"].get<double>();
    std::ostringstream gd_s, gd_it;
    if (j.contains("gradient_seconds")) {
      gd_s << std::fixed << std::setprecision(2) << j["gradient_seconds"].get<double>();
      gd_it << j["gradient_iterations"].get<int>()
            << (j["gradient_status"] == "converged" ? "" : "+");
    } else {
      gd_s << "-";
      gd_it << "-";
    }
    std::cout << std::left << std::setw(26) << name << std::right << std::setw(9)
              << j["faces"].get<int>() << std::setw(6) << j["iterations"].get<int>()
              << std::setw(10) << std::scientific << std::setprecision(1) << j["error"].get<double>()
              << std::fixed << std::setprecision(3) << std::setw(10) << j["newton_seconds"].get<double>()
              << std::setw(9) << j["newton_cpu_seconds"].get<double>() << std::setw(9)
              << j["cholesky_seconds"].get<double>() << std::setprecision(1) << std::setw(8) << ratio << std::setw(9) << cpu_ratio
              << std::setw(10) << j["flow_peak_mb"].get<double>() << std::setprecision(0)
              << std::setw(9) << j["flow_peak_mb"].get<double>() * 1048576.0 / j["faces"].get<int>()
              << std::setw(10) << gd_s.str() << std::setw(9) << gd_it.str() << "  "
              << j["metric"].get<std::string>() << (j["status"] == "converged" ? "" : " NOT CONVERGED")
              << std::endl;
  }
  return 0;
}

int run_solver_benchmark(int argc, char** argv) {
  Args args(argc, argv, {"no-1m"});
  args.require_known({"no-1m"});
  const std::string m = shared_models();
  std::vector<std::pair<std::string, int>> cases = {{m + "/bench/torus_10k.obj", 0},
                                                    {m + "/bench/torus_100k.obj", 0}};
  if (!args.has("no-1m")) cases.push_back({m + "/closed_g1/kitten_nf20k.off", 3});
  std::cout << "Factorisations of the E2 Newton Hessian at the initial inversive-distance metric\n"
               "(vertex 0 pinned); seconds, best of 2: symbolic analysis, numeric factorisation,\n"
               "solve.\n\n";
  std::cout << std::left << std::setw(30) << "mesh" << std::setw(22) << "solver" << std::right
            << std::setw(10) << "analyse" << std::setw(10) << "factor" << std::setw(10) << "solve"
            << std::setw(12) << "residual\n";
  for (const auto& [path, levels] : cases) {
    const ricci::Mesh mesh = load(path, levels);
    const ricci::MeshTables t = ricci::build_mesh_tables(mesh);
    const ricci::CirclePackingMetric metric =
        ricci::initial_metric(t, ricci::mesh_edge_lengths(mesh), ricci::Geometry::euclidean,
                              ricci::Scheme::inversive_distance, ricci::RadiusInit::mean);
    ricci::FlowState state;
    ricci::evaluate_flow_state(t, metric.geometry, metric.eta,
                               ricci::u_from_radii(metric.geometry, metric.gamma), state);
    ricci::HessianAssembler assembler(t, 0);
    const Sparse H = assembler.assemble(metric.geometry, metric.eta, state);
    const Sparse full = H.selfadjointView<Eigen::Lower>();
    const Eigen::VectorXd rhs = Eigen::VectorXd::Random(H.rows());
    std::string name = path.substr(path.find_last_of('/') + 1) + " (" +
                       std::to_string(mesh.n_faces()) + " F)";
    for (auto kind :
         {ricci::LinearSolver::eigen_ldlt, ricci::LinearSolver::eigen_llt,
          ricci::LinearSolver::cholmod_simplicial, ricci::LinearSolver::cholmod_supernodal}) {
      double analyse = 1e300, factor = 1e300, solve = 1e300, residual = 0;
      for (int r = 0; r < 2; ++r) {
        ricci::SymmetricFactorization solver(kind);
        ricci::Stopwatch t0;
        solver.analyze(H);
        analyse = std::min(analyse, t0.seconds());
        t0.restart();
        const bool ok = solver.factorize(H);
        factor = std::min(factor, t0.seconds());
        t0.restart();
        const Eigen::VectorXd x = solver.solve(rhs);
        solve = std::min(solve, t0.seconds());
        residual = ok ? (full * x - rhs).norm() / rhs.norm() : -1;
      }
      std::cout << std::left << std::setw(30) << name << std::setw(22) << ricci::to_string(kind)
                << std::right << std::fixed << std::setprecision(3) << std::setw(10) << analyse
                << std::setw(10) << factor << std::setw(10) << solve << std::scientific
                << std::setprecision(1) << std::setw(11) << residual << std::defaultfloat << std::endl;
    }
  }
  return 0;
}

}  // namespace msp::bench
