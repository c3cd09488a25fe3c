// msp-bench intrinsic [--faces N,...] [--genera G,...] [--track]: issue 20, the one-cone atlas
// by the intrinsic Delaunay flow on smoothed genus-g slabs (make_genus_slab) of about N faces:
// seconds of the flow and of the whole atlas, Newton iterations, factorisations, Ptolemy flips,
// the transition residual, and the flow's time as a multiple of one CHOLMOD analyse + factorise
// + solve of the same mesh's cotangent Laplacian. --track also runs the intrinsic flow alone on
// the slab (cone at the atlas's vertex) and carries every vertex and face centroid through its
// flips and back (point_tracking.h): seconds and the largest 3D round-trip error over the
// bounding-box diagonal.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <ricci/intrinsic/point_tracking.h>
#include <ricci/mesh/arrays.h>
#include <ricci/mesh/primitives.h>
#include <ricci/metric/mesh_tables.h>
#include <ricci/pipeline/one_cone_atlas.h>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "ricci/util/stopwatch.h"

namespace msp::bench {
namespace {

// The slab of `genus` whose face count is closest to `faces` (faces grow like resolution^2).
ricci::Mesh slab_of_size(int genus, int faces) {
  const double base = static_cast<double>(ricci::make_genus_slab(genus, 1).n_faces());
  const int resolution = std::max(1, static_cast<int>(std::lround(std::sqrt(faces / base))));
  return ricci::make_genus_slab(genus, resolution, 10);
}

// The intrinsic flow alone to one cone at `cone`, then every vertex and face centroid carried to
// its final triangulation and back: prints seconds of the flow, of the tracking, and the largest
// 3D round-trip error over the bounding-box diagonal.
void print_tracking(const ricci::Mesh& mesh, int cone) {
  const ricci::IntrinsicTriangulation initial =
      ricci::make_intrinsic_triangulation(mesh, ricci::mesh_edge_lengths(mesh));
  const ricci::Stopwatch flow_clock;
  const ricci::IntrinsicFlowResult r =
      ricci::intrinsic_conformal_flow(initial, ricci::single_cone_target(mesh, cone).curvature);
  const double flow_seconds = flow_clock.seconds();
  const ricci::Stopwatch clock;
  const ricci::IntrinsicCorrespondence map(initial, r.flip_log);
  std::vector<ricci::TriangulationPoint> points = ricci::vertex_points(initial);
  for (int f = 0; f < initial.face_count(); ++f)
    points.push_back({f, Eigen::Vector3d::Constant(1.0 / 3.0)});
  const std::vector<ricci::TriangulationPoint> back = map.to_initial(map.to_final(points));
  const double seconds = clock.seconds();
  const Eigen::MatrixX3d V = ricci::to_arrays(mesh).V;
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  double worst = 0;
  for (size_t n = 0; n < points.size(); ++n) {
    worst = std::max(worst, (ricci::point_position(initial, V, back[n]) -
                             ricci::point_position(initial, V, points[n]))
                                    .norm() /
                                diagonal);
  }
  std::cout << "      tracking: flow " << std::fixed << std::setprecision(2) << flow_seconds
            << " s (" << ricci::to_string(r.status) << ", " << r.flips << " flips), "
            << points.size() << " points to the final triangulation and back " << seconds
            << " s, round trip " << std::scientific << std::setprecision(1) << worst << "\n";
}

}  // namespace

int run_intrinsic_benchmark(int argc, char** argv) {
  Args args(argc, argv, {"track"});
  args.require_known({"faces", "genera", "track"});
  args.require_positionals(0, "msp-bench intrinsic [--faces N,...] [--genera G,...] [--track]");
  const bool track = args.has("track");
  const std::vector<int> sizes =
      parse_int_list(args.get_or("faces", "10000,100000"), "option --faces");
  const std::vector<int> genera =
      parse_int_list(args.get_or("genera", "4,6,8,10"), "option --genera");
  std::cout << "genus  faces  flow_s  atlas_s  newton  factor    flips  residual  flipped  "
               "cholmod_s  flow/cholmod\n";
  for (int faces : sizes) {
    for (int genus : genera) {
      const ricci::Mesh mesh = slab_of_size(genus, faces);
      const double cholesky = one_cholesky_seconds(regularised_cotangent_laplacian(mesh));
      ricci::OneConeAtlasOptions options;
      options.route = ricci::FlowRoute::intrinsic_delaunay;
      const ricci::Stopwatch t;
      std::cout << std::setw(5) << genus << std::setw(7) << mesh.n_faces() << std::flush;
      try {
        const ricci::OneConeAtlasResult r = ricci::build_one_cone_atlas(mesh, options);
        std::cout << std::fixed << std::setprecision(2) << std::setw(8) << r.timings.flow
                  << std::setw(9) << t.seconds() << std::setw(8) << r.flow.iterations
                  << std::setw(8) << r.flow.factorizations << std::setw(9) << r.intrinsic_flips
                  << std::scientific << std::setprecision(1) << std::setw(10)
                  << r.relative_transition_residual() << std::setw(8)
                  << r.atlas.layout.flipped_faces << std::fixed << std::setprecision(3)
                  << std::setw(10) << cholesky << std::setprecision(0) << std::setw(12)
                  << r.timings.flow / cholesky << "\n";
        if (track) print_tracking(mesh, std::max(0, r.chosen_vertex));
      } catch (const std::exception& e) {
        std::cout << "  failed after " << t.seconds() << " s: " << e.what() << "\n";
      }
    }
  }
  return 0;
}

}  // namespace msp::bench
