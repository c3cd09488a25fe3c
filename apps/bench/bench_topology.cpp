// msp-bench topology [models folder]: times of the cut graph, slicing, layout and atlas.
// Closed bench meshes have no flat metric of their own, so on them only the cut graph and the
// slicing are timed; the layout and atlas are timed on flat torus grids (exact flat lengths).
#include <cstdio>
#include <ctime>
#include <string>

#include "bench/benchmarks.h"
#include "ricci/atlas/atlas.h"
#include "ricci/layout/layout_e2.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "ricci/topology/cut_graph.h"
#include "ricci/topology/polygon_word.h"
#include "ricci/topology/slice.h"

namespace msp::bench {
namespace {

// CPU time of this thread: the machine is shared and these stages are single-threaded, so
// wall time would mostly measure the other processes.
struct Clock {
  using time_point = double;
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
};

double seconds_since(double t) { return Clock::now() - t; }

void cut_and_slice_row(const std::string& path) {
  const ricci::Mesh mesh = ricci::read_mesh(path);
  const Eigen::VectorXd lengths = ricci::checked_edge_lengths(mesh, {});
  auto t = Clock::now();
  const ricci::CutGraph cut = ricci::compute_cut_graph(mesh, ricci::VertexHandle(0), lengths);
  const double cut_time = seconds_since(t);
  if (cut.genus == 0 && cut.boundary_loop_count == 0) {
    std::printf(
        "%-28s %7zu %2d %2d %6d %9.3f   (closed genus 0: no cut; the pipeline punctures it)\n",
        path.substr(path.find_last_of('/') + 1).c_str(), mesh.n_faces(), 0, 0, 0, cut_time);
    return;
  }
  t = Clock::now();
  const ricci::SlicedMesh sliced = ricci::slice_along(mesh, cut.is_cut_edge);
  ricci::check_disk(sliced);
  const double slice_time = seconds_since(t);
  t = Clock::now();
  const ricci::FundamentalPolygon polygon = ricci::fundamental_polygon_word(mesh, cut, sliced);
  const double word_time = seconds_since(t);
  int cut_edges = 0;
  for (char c : cut.is_cut_edge) cut_edges += c;
  std::printf("%-28s %7zu %2d %2d %6d %9.3f %9.3f %9.3f %s\n",
              path.substr(path.find_last_of('/') + 1).c_str(), mesh.n_faces(), cut.genus,
              cut.boundary_loop_count, cut_edges, cut_time, slice_time, word_time,
              polygon.canonical ? "yes" : "no");
}

void flat_torus_row(int nx, int ny) {
  const ricci::Mesh torus = ricci::make_flat_torus_grid(nx, ny, 1.0 * nx / ny, 1.0);
  const Eigen::VectorXd lengths = ricci::flat_torus_edge_lengths(torus, nx, ny, 1.0 * nx / ny, 1.0);
  auto t = Clock::now();
  const ricci::CutGraph cut = ricci::compute_cut_graph(torus, ricci::VertexHandle(0), lengths);
  const ricci::SlicedMesh sliced = ricci::slice_along(torus, cut.is_cut_edge);
  ricci::check_disk(sliced);
  const double cut_time = seconds_since(t);
  t = Clock::now();
  const ricci::LayoutE2Result layout =
      ricci::layout_e2(sliced.mesh, ricci::sliced_edge_lengths(sliced, lengths));
  const double layout_time = seconds_since(t);
  t = Clock::now();
  const ricci::AffineAtlas atlas =
      ricci::build_affine_atlas(torus, lengths, ricci::VertexHandle(0));
  const double atlas_time = seconds_since(t);
  std::printf("flat torus %4d x %-4d        %7zu %9.3f %9.3f %9.3f %9.1e %9.1e %3zu\n", nx, ny,
              torus.n_faces(), cut_time, layout_time, atlas_time, layout.max_relative_length_error,
              atlas.max_transition_residual / atlas.domain_diameter, atlas.charts.size());
}

}  // namespace

int run_topology_benchmark(int argc, char** argv) {
  const std::string folder = argc > 0 ? argv[0] : shared_models() + "/bench";
  std::printf(
      "cut graph (tree-cotree from vertex 0, 3D lengths) + slicing + polygon word,\n"
      "thread CPU seconds\n");
  std::printf("%-28s %7s %2s %2s %6s %9s %9s %9s %s\n", "mesh", "faces", "g", "b", "cuts", "cut",
              "slice", "word", "canonical");
  for (const char* name : {"sphere_10k.obj", "torus_10k.obj", "genus2_10k.obj", "genus3_10k.obj",
                           "cap_10k.obj", "sphere_100k.obj", "torus_100k.obj", "genus2_100k.obj",
                           "genus3_100k.obj", "cap_100k.obj"}) {
    try {
      cut_and_slice_row(folder + "/" + name);
    } catch (const std::exception& e) {
      std::printf("%-28s %s\n", name, e.what());
    }
  }
  std::printf("\nflat torus grids (exact flat lengths), thread CPU seconds; errors relative\n");
  std::printf("%-28s %7s %9s %9s %9s %9s %9s %3s\n", "mesh", "faces", "cut+slice", "layout",
              "atlas", "len err", "trans res", "charts");
  for (auto [nx, ny] : {std::pair{71, 70}, std::pair{224, 224}, std::pair{708, 707}}) {
    flat_torus_row(nx, ny);
  }
  return 0;
}

}  // namespace msp::bench
