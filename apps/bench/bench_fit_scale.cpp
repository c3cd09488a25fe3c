// msp-bench fit-scale: `msp fit`'s job (spline::fit_surface with the default options) on one scan
// made larger by midpoint subdivision (the surface kept) and a seeded displacement along the
// normals (scanner noise, so the fit has something to smooth), at 1, 4 and 16 times the faces:
// seconds and CPU seconds by stage, the same per million input faces (near-linear scaling shows as
// a flat column), peak memory, and the ratio to one CHOLMOD solve of the same mesh (issue 19).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <ricci/mesh/arrays.h>
#include <ricci/mesh/io.h>
#include <ricci/metric/subdivide.h>

#include "bench/benchmarks.h"
#include "bench/child_run.h"
#include "msp/cli.h"
#include "ricci/util/memory.h"
#include "ricci/util/stopwatch.h"
#include "spline/surface/fit_surface.h"

namespace msp::bench {
namespace {

// Every vertex moved along its area-weighted normal by a normal deviate of `sigma` bounding-box
// diagonals (seeded: the same mesh every run).
void displace_along_normals(ricci::Mesh& mesh, double sigma) {
  if (sigma <= 0.0) return;
  const ricci::VertexFaceArrays arrays = ricci::to_arrays(mesh);
  const double diagonal =
      (arrays.V.colwise().maxCoeff() - arrays.V.colwise().minCoeff()).norm();
  Eigen::MatrixX3d normals = Eigen::MatrixX3d::Zero(arrays.V.rows(), 3);
  for (Eigen::Index f = 0; f < arrays.F.rows(); ++f) {
    const Eigen::Vector3d a = arrays.V.row(arrays.F(f, 0)), b = arrays.V.row(arrays.F(f, 1)),
                          c = arrays.V.row(arrays.F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k) normals.row(arrays.F(f, k)) += n;
  }
  std::mt19937_64 random(1);
  std::normal_distribution<double> deviate(0.0, sigma * diagonal);
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d n = normals.row(v.idx()).transpose();
    if (!(n.norm() > 0.0)) continue;
    const Eigen::Vector3d p = ricci::to_eigen(mesh.point(v)) + deviate(random) * n.normalized();
    mesh.set_point(v, ricci::to_openmesh(p));
  }
}

nlohmann::json stages_json(const spline::StageSeconds& stages) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, s] : stages) j[name] = s;
  return j;
}

const std::vector<std::string> kStages = {"simplify", "atlas",      "parameters", "fit",
                                          "correction", "fill",     "tessellate", "measure"};

}  // namespace

ricci::Mesh refined_scan(const std::string& path, int levels, double sigma) {
  ricci::Mesh mesh = ricci::read_mesh(path);
  for (int i = 0; i < levels; ++i) mesh = ricci::subdivide_midpoint(mesh);
  displace_along_normals(mesh, sigma);
  return mesh;
}

int run_fit_scale_case(int argc, char** argv) {
  Args args(argc, argv, {});
  args.require_known({"levels", "displace"});
  args.require_positionals(1, "msp-bench fit-scale-one MESH [--levels L] [--displace SIGMA]");
  nlohmann::json j;
  const ricci::Stopwatch read;
  const ricci::Mesh mesh = refined_scan(args.positionals()[0], args.get_int("levels", 0),
                                        args.get_double("displace", 2e-4));
  j["read_seconds"] = read.seconds();
  j["faces"] = mesh.n_faces();
  try {
    ricci::keep_freed_memory(mesh.n_vertices());  // as msp fit
    const spline::FittedSurface fitted = spline::fit_surface(mesh);
    j["status"] = "ok";
    j["seconds"] = stages_json(fitted.seconds);
    j["cpu_seconds"] = stages_json(fitted.cpu_seconds);
    j["fit_rms"] = fitted.delivered.fit_rms / fitted.bbox_diagonal;
    j["folds"] = fitted.surface_dihedral.over_90_deg;
    j["watertight"] = fitted.watertight;
  } catch (const std::exception& e) {
    j["status"] = std::string("failed: ") + e.what();
  }
  print_child_row(j, mesh);
  return 0;
}

int run_fit_scale_benchmark(int argc, char** argv) {
  Args args(argc, argv, {});
  args.require_known({"levels", "displace"});
  const std::string path =
      args.positionals().empty() ? shared_models() + "/closed_g0/venus.off" : args.positionals()[0];
  const std::vector<int> levels = parse_int_list(args.get_or("levels", "0,1,2"), "option --levels");
  const std::string displace = args.get_or("displace", "2e-4");
  std::cout << "msp fit (spline::fit_surface, default options) on " << path
            << " refined by midpoint subdivision L times and displaced along the normals by a "
               "normal deviate of "
            << displace
            << " diagonals (seeded), each in its own process.\nwall: seconds by stage; cpu: CPU "
               "seconds (both threads); '/M': per million input faces (flat = linear); chol: "
               "one CHOLMOD analyse + factorise + solve of the mesh's cotangent Laplacian (best "
               "of 3); ratio = wall total / chol; MB: peak RSS (the input mesh included).\n\n";
  std::cout << std::left << std::setw(14) << "mesh" << std::right << std::setw(9) << "faces";
  for (const std::string& s : kStages) std::cout << std::setw(11) << s;
  std::cout << std::setw(8) << "total" << std::setw(8) << "cpu" << std::setw(7) << "chol"
            << std::setw(7) << "ratio" << std::setw(7) << "MB" << std::setw(8) << "rms%"
            << std::setw(6) << "folds" << "\n";
  for (int level : levels) {
    const ChildResult child =
        run_child("'" + self_executable() + "' fit-scale-one '" + path + "' --levels " +
                  std::to_string(level) + " --displace " + displace);
    const std::string name = case_label(path, level);
    if (!child.parsed) {
      std::cout << std::left << std::setw(14) << name << " child failed: " << child.output << "\n";
      continue;
    }
    const nlohmann::json& j = child.json;
    const double faces = j["faces"].get<double>();
    std::cout << std::left << std::setw(14) << name << std::right << std::setw(9)
              << j["faces"].get<long>();
    if (j["status"] != "ok") {
      std::cout << "  " << j["status"].get<std::string>() << "\n";
      continue;
    }
    std::cout << std::fixed << std::setprecision(1);
    for (const std::string& s : kStages) {
      const double wall = j["seconds"].value(s, 0.0), cpu = j["cpu_seconds"].value(s, 0.0);
      std::ostringstream cell;
      cell << std::fixed << std::setprecision(1) << wall << "/" << cpu;
      std::cout << std::setw(11) << cell.str();
    }
    const double total = j["seconds"]["total"].get<double>();
    const double chol = j["cholesky"].get<double>();
    std::cout << std::setw(8) << total << std::setw(8) << j["cpu_seconds"]["total"].get<double>()
              << std::setprecision(2) << std::setw(7) << chol << std::setprecision(1)
              << std::setw(7) << total / chol << std::setprecision(0) << std::setw(7)
              << j["peak_mb"].get<double>() << std::setprecision(3) << std::setw(8)
              << 100.0 * j["fit_rms"].get<double>() << std::setw(6) << j["folds"].get<int>()
              << "\n";
    std::cout << std::left << std::setw(14) << "  cpu /M" << std::right << std::setw(9) << "";
    for (const std::string& s : kStages)
      std::cout << std::setprecision(1) << std::setw(11)
                << j["cpu_seconds"].value(s, 0.0) / (faces / 1e6);
    std::cout << std::setw(8) << "" << std::setw(8)
              << j["cpu_seconds"]["total"].get<double>() / (faces / 1e6) << "\n";
  }
  return 0;
}

}  // namespace msp::bench
