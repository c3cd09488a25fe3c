// msp-bench intrinsic [--faces N,...] [--genera G,...]: issue 20, the one-cone atlas by the
// intrinsic Delaunay flow on smoothed genus-g slabs (make_genus_slab) of about N faces: seconds
// of the flow and of the whole atlas, Newton iterations, Ptolemy flips, the transition residual,
// and the flow's time as a multiple of one CHOLMOD analyse + factorise + solve of the same
// mesh's cotangent Laplacian.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <ricci/mesh/primitives.h>
#include <ricci/pipeline/one_cone_atlas.h>

#include "bench/benchmarks.h"
#include "msp/cli.h"
#include "ricci/util/stopwatch.h"

namespace msp::bench {
namespace {

std::vector<int> int_list(const std::string& text) {
  std::vector<int> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) values.push_back(std::stoi(item));
  return values;
}

// The slab of `genus` whose face count is closest to `faces` (faces grow like resolution^2).
ricci::Mesh slab_of_size(int genus, int faces) {
  const double base = static_cast<double>(ricci::make_genus_slab(genus, 1).n_faces());
  const int resolution = std::max(1, static_cast<int>(std::lround(std::sqrt(faces / base))));
  return ricci::make_genus_slab(genus, resolution, 10);
}

}  // namespace

int run_intrinsic_benchmark(int argc, char** argv) {
  Args args(argc, argv, {});
  args.require_known({"faces", "genera"});
  args.require_positionals(0, "msp-bench intrinsic [--faces N,...] [--genera G,...]");
  const std::vector<int> sizes = int_list(args.get_or("faces", "10000,100000"));
  const std::vector<int> genera = int_list(args.get_or("genera", "4,6,8,10"));
  std::cout << "genus  faces  flow_s  atlas_s  newton  flips  residual  flipped  cholmod_s  "
               "flow/cholmod\n";
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
                  << std::setw(8) << r.intrinsic_flips << std::scientific << std::setprecision(1)
                  << std::setw(10) << r.relative_transition_residual() << std::setw(8)
                  << r.atlas.layout.flipped_faces << std::fixed << std::setprecision(3)
                  << std::setw(10) << cholesky << std::setprecision(0) << std::setw(12)
                  << r.timings.flow / cholesky << "\n";
      } catch (const std::exception& e) {
        std::cout << "  failed after " << t.seconds() << " s: " << e.what() << "\n";
      }
    }
  }
  return 0;
}

}  // namespace msp::bench
