// msp-bench match: conformal modules and surface matching (issue 17) at ~20k and ~100k faces,
// against the shape-analysis paper's Table 1 (2010 desktop, 13-29k faces: euclidean Ricci flow
// 17-40 s, hyperbolic 3-8 s). Meshes of the model collection (MSP_SHARED_MODELS), midpoint
// subdivided and simplified to the size (preparation not timed): holes.off (genus 0, 7 loops:
// circle domain, its flows counted), ChineseDragon-10kv.off (2 loops: annulus) and
// mech-holes-shark.off (4 loops). B of the match is A stretched by 1.2 along x and bent (not
// an isometry), matched by both methods (hyperbolic from 3 loops), so the correspondence error
// measures how far the map is from the vertex correspondence under that deformation. chol = one
// CHOLMOD solve of the cotangent Laplacian.
#include <cmath>
#include <cstdio>
#include <string>

#include "bench/benchmarks.h"
#include "ricci/analysis/conformal_module.h"
#include "ricci/analysis/match.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/simplify.h"
#include "ricci/metric/subdivide.h"

namespace msp::bench {
namespace {

struct Case {
  const char* name;
  const char* file;  ///< under the models folder
  int target_faces;  ///< subdivide until above, then simplify to this many faces
};

ricci::Mesh prepared(const std::string& models, const Case& c) {
  ricci::Mesh mesh = ricci::read_mesh(models + "/" + c.file);
  while (static_cast<int>(mesh.n_faces()) < c.target_faces) mesh = ricci::subdivide_midpoint(mesh);
  ricci::SimplifyOptions options;
  options.target_faces = c.target_faces;
  return ricci::simplify_mesh(mesh, options).mesh;
}

/// x stretched by 1.2 and the surface bent by z += 0.3 y^2 / diagonal.
ricci::Mesh deformed(const ricci::Mesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (auto v : mesh.vertices()) {
    lo = lo.cwiseMin(ricci::to_eigen(mesh.point(v)));
    hi = hi.cwiseMax(ricci::to_eigen(mesh.point(v)));
  }
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const double diagonal = (hi - lo).norm();
  ricci::Mesh out = mesh;
  for (auto v : out.vertices()) {
    Eigen::Vector3d p = ricci::to_eigen(out.point(v)) - centre;
    p.x() *= 1.2;
    p.z() += 0.3 * p.y() * p.y() / diagonal;
    out.set_point(v, ricci::to_openmesh(p + centre));
  }
  return out;
}

void row(const std::string& models, const Case& c) {
  const ricci::Mesh a = prepared(models, c);
  const ricci::Mesh b = deformed(a);
  const double chol = cotangent_cholesky_seconds(a);
  ricci::ModuleOptions module_options;
  module_options.retry = false;
  const ricci::ModuleResult module = ricci::conformal_module(a, module_options);
  const auto match_text = [&](ricci::MatchMethod method) -> std::string {
    if (method == ricci::MatchMethod::hyperbolic && module.boundary_loops < 3) return "-";
    try {
      ricci::MatchOptions options;
      options.method = method;
      const ricci::MatchResult m = ricci::match_surfaces(a, b, options);
      char buffer[160];
      std::snprintf(buffer, sizeof buffer, "%7.2f %6.0fx %5d %4d %6.2f %6.2f", m.seconds,
                    m.seconds / chol, m.flipped_faces + m.flipped_faces_b, m.flattened_ears,
                    100 * m.shape_error, 100 * m.correspondence_error);
      return buffer;
    } catch (const std::exception& e) {
      return std::string("failed: ") + e.what();
    }
  };
  std::printf("%-12s %6zu %2d %-13s %7.2f %6.0fx %5d %s %6.3f  %s | %s\n", c.name, a.n_faces(),
              module.boundary_loops, ricci::to_string(module.kind).c_str(), module.seconds,
              module.seconds / chol, module.circle_iterations, module.converged ? "" : "(!)", chol,
              match_text(ricci::MatchMethod::euclidean).c_str(),
              match_text(ricci::MatchMethod::hyperbolic).c_str());
  std::fflush(stdout);
}

}  // namespace

int run_match_benchmark(int argc, char** argv) {
  const std::string models = argc > 0 ? argv[0] : shared_models();
  const Case cases[] = {
      {"dragon-20k", "open/ChineseDragon-10kv.off", 20000},
      {"holes-20k", "open/holes.off", 20000},
      {"shark-20k", "open/mech-holes-shark.off", 20000},
      {"dragon-100k", "open/ChineseDragon-10kv.off", 100000},
      {"holes-100k", "open/holes.off", 100000},
      {"shark-100k", "open/mech-holes-shark.off", 100000},
  };
  std::printf(
      "wall seconds of ricci::conformal_module (no retry) and ricci::match_surfaces (A against A "
      "stretched and bent), euclidean | hyperbolic;\nflows = circle-domain flows; chol = one "
      "CHOLMOD solve; x = ratio to it; flips = reversed faces of A and B; ears = flattened ears; "
      "d_g and corr in %% of the diagonal\n");
  std::printf("%-12s %6s %2s %-13s %7s %7s %5s %6s  %7s %7s %5s %4s %6s %6s | %s\n", "mesh",
              "faces", "b", "module", "s", "x", "flows", "chol", "match s", "x", "flips", "ears",
              "d_g", "corr", "the same, hyperbolic");
  // Further arguments keep only the cases of those names (e.g. holes-100k).
  for (const Case& c : cases) {
    bool wanted = argc <= 1;
    for (int i = 1; i < argc; ++i) wanted = wanted || std::string(argv[i]) == c.name;
    if (wanted) row(models, c);
  }
  return 0;
}

}  // namespace msp::bench
