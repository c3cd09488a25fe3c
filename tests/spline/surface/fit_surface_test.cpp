// fit_surface, the whole scan-to-surface job: holes capped or left open as asked (the
// tessellation's topology agrees with the rims), seams below a degree at the defaults, the
// figures `msp fit --json` reports, and tessellate_surface reproducing the tessellation from
// the SplineSurface alone.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_paths.h"
#include "apps/info_subprocess.h"
#include "ricci/mesh/arrays.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/primitives.h"
#include "spline/surface/fit_surface.h"
#include "spline/surface/tessellate_surface.h"

namespace spline {
namespace {

namespace fs = std::filesystem;

std::string bundled(const std::string& name) {
  return std::string(MSP_SOURCE_DIR) + "/models/" + name;
}

// The small, fast setting of the hole tests: 400 domain faces, density 3.
FitSurfaceOptions small_options(bool fill_boundaries = false) {
  FitSurfaceOptions options;
  options.domain_faces = 400;
  options.density = 3;
  options.fill_boundaries = fill_boundaries;
  return options;
}

// Fitted once per process and setting (ctest runs each test in a process of its own).
const FittedSurface& two_holes_fit(bool fill_boundaries) {
  const auto fit = [](bool fill) {
    return fit_surface(ricci::read_mesh(bundled("genus2_two_holes.off")), small_options(fill));
  };
  if (fill_boundaries) {
    static const FittedSurface filled = fit(true);
    return filled;
  }
  static const FittedSurface open = fit(false);
  return open;
}

// Without fill_boundaries the boundary rims stay open, one per input loop: the surface keeps
// the input's genus and boundary loops.
TEST(FitSurface, OpenModelKeepsOneLoopPerOpenRim) {
  const FittedSurface& r = two_holes_fit(false);
  EXPECT_TRUE(r.watertight);
  EXPECT_EQ(r.input.boundary_loops, 2);
  EXPECT_EQ(r.boundary_rims, 2);
  EXPECT_EQ(r.surface.open_rims.size(), 2u);
  EXPECT_TRUE(r.fill_failures.empty());
  EXPECT_TRUE(r.topology.matches(2, 2));
  EXPECT_TRUE(r.float_topology.matches(2, 2));
  for (const Rim& rim : r.surface.open_rims) EXPECT_EQ(rim.kind, Rim::Kind::boundary);
}

// With fill_boundaries every rim is capped (a positions-only patch where no height field fits,
// counted in fallback_fills; nearby loops may share a rim): a closed surface of the input's
// genus.
TEST(FitSurface, FillBoundariesClosesTheSurface) {
  const FittedSurface& r = two_holes_fit(true);
  EXPECT_TRUE(r.watertight);
  EXPECT_TRUE(r.surface.open_rims.empty());
  EXPECT_GE(r.boundary_rims, 1);
  EXPECT_LE(r.boundary_rims, 2);
  EXPECT_GE(static_cast<int>(r.surface.fills.size()), r.boundary_rims);
  EXPECT_LE(r.fallback_fills, static_cast<int>(r.surface.fills.size()));
  EXPECT_TRUE(r.topology.closed(2));
  EXPECT_TRUE(r.float_topology.closed(2));
}

// Every fill's covered faces and every face outside the spline's domain are skipped, and the
// singular vertex is the atlas' cone.
TEST(FitSurface, SkippedFacesAreThePatchesAndTheHole) {
  const FittedSurface& r = two_holes_fit(true);
  const auto& space = *r.surface.spline.space;
  ASSERT_EQ(r.surface.skipped_faces.size(), r.surface.domain.n_faces());
  for (int f = 0; f < static_cast<int>(r.surface.domain.n_faces()); ++f) {
    if (!space.in_domain(f)) {
      EXPECT_TRUE(r.surface.skipped_faces[static_cast<std::size_t>(f)]);
    }
  }
  for (const HoleFill& fill : r.surface.fills) {
    for (int f : fill.rim.covered_faces) {
      EXPECT_TRUE(r.surface.skipped_faces[static_cast<std::size_t>(f)]);
    }
  }
  EXPECT_EQ(r.surface.singular_vertex, r.atlas.problem.cone);
  EXPECT_EQ(r.surface.domain.n_faces(), r.atlas.problem.mesh.n_faces());
}

// The saved surface re-tessellated: the very same positions, triangles and normals.
TEST(FitSurface, TessellateSurfaceReproducesTheTessellation) {
  for (bool filled : {false, true}) {
    const FittedSurface& r = two_holes_fit(filled);
    TessellationOptions options;
    options.density = r.tessellation.density;
    const Tessellation t = tessellate_surface(r.surface, options);
    ASSERT_EQ(t.positions.rows(), r.tessellation.positions.rows());
    EXPECT_TRUE(t.positions == r.tessellation.positions);
    EXPECT_TRUE(t.normals == r.tessellation.normals);
    EXPECT_EQ(t.triangles, r.tessellation.triangles);
    EXPECT_EQ(t.triangle_face, r.tessellation.triangle_face);
  }
}

// A patch welds to its rim's samples: a rim on a face the surface skips is refused.
TEST(FitSurface, TessellateSurfaceRefusesARimOnASkippedFace) {
  SplineSurface surface = two_holes_fit(true).surface;
  ASSERT_FALSE(surface.fills.empty());
  const int face = surface.fills.front().rim.edges.front().face;
  surface.skipped_faces[static_cast<std::size_t>(face)] = 1;
  TessellationOptions options;
  options.density = 2;
  EXPECT_THROW((void)tessellate_surface(surface, options), ricci::InvalidInputError);
}

TEST(FitSurface, RefusesBadSingularVertexAndTooFewFaces) {
  const ricci::Mesh open = ricci::read_mesh(bundled("genus1_hole.off"));
  FitSurfaceOptions options = small_options();
  for (auto v : open.vertices()) {
    if (!open.is_boundary(v)) continue;
    options.singular_vertex = v.idx();
    break;
  }
  EXPECT_THROW((void)fit_surface(open, options), ricci::InvalidInputError);
  options.singular_vertex = static_cast<int>(open.n_vertices());
  EXPECT_THROW((void)fit_surface(open, options), ricci::InvalidInputError);
  options.singular_vertex = -1;
  options.domain_faces = minimum_domain_faces(1) - 1;
  EXPECT_THROW((void)fit_surface(open, options), ricci::InvalidInputError);
}

// The library call is what `msp fit` reports: the same figures, to the last bit.
TEST(FitSurface, FiguresAreThoseMspFitReports) {
  const std::string model = bundled("genus2.off");
  const fs::path dir = fs::temp_directory_path() /
                       ("msp_fit_surface_tests_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto run = msp_test::run_msp({"fit", model, "--json", (dir / "x.json").string(),
                                      "--domain-faces", "400", "--density", "3", "--quiet"});
  ASSERT_EQ(run.exit_status, 0) << run.err;
  std::ifstream in(dir / "x.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  fs::remove_all(dir);

  const FittedSurface r = fit_surface(ricci::read_mesh(model), small_options());
  EXPECT_EQ(report["fit_rms"].get<double>(), r.fit_rms);
  EXPECT_EQ(report["fit_max"].get<double>(), r.fit_max);
  EXPECT_EQ(report["fit_points"].get<int>(), r.fit_points);
  EXPECT_EQ(report["fit_points_on_fills"].get<int>(), r.fit_points_on_fills);
  EXPECT_EQ(report["bbox_diagonal"].get<double>(), r.bbox_diagonal);
  EXPECT_EQ(report["edge_normal_jump_max_deg"].get<double>(), r.edge_normal_jump_deg);
  EXPECT_EQ(report["fill_normal_jump_max_deg"].get<double>(), r.fill_normal_jump_deg);
  EXPECT_EQ(report["fill_position_gap_relative"].get<double>(), r.fill_position_gap);
  EXPECT_EQ(report["filled_rims"].get<std::size_t>(), r.surface.fills.size());
  EXPECT_EQ(report["open_rims"].get<std::size_t>(), r.surface.open_rims.size());
  EXPECT_EQ(report["fallback_fills"].get<int>(), r.fallback_fills);
  EXPECT_EQ(report["watertight"].get<bool>(), r.watertight);
  EXPECT_EQ(report["control_points"].get<int>(), r.surface.spline.space->function_count());
  EXPECT_EQ(report["fit_constraint_residual"].get<double>(), r.fit_constraint_residual);
  EXPECT_EQ(report["singularities"][0]["domain_vertex"].get<int>(), r.atlas.chosen_vertex);
  const auto& t = report["tessellation"];
  EXPECT_EQ(t["vertices"].get<int>(), r.topology.vertices);
  EXPECT_EQ(t["triangles"].get<int>(), r.topology.faces);
  EXPECT_EQ(t["density"].get<int>(), r.tessellation.density);
  EXPECT_EQ(report["surface_dihedral"]["max_deg"].get<double>(), r.surface_dihedral.max_deg);
  EXPECT_TRUE(r.watertight);
  EXPECT_EQ(r.surface.fills.size(), 1u);
}

// The seams at the defaults (2000 domain faces) on shared scans: below one degree, and the fit
// RMS below the bound, with G1 patches only. These were the hard cases: the cone patch flipped
// (block: retried on a bigger hole), the spline folded next to large cones (elephant_cgal,
// helmet, joint: the domain refined around the cone), the surface turned fast next to the rim
// (bunny_npm_closed, femur: meet_patches and the corner-refined patch). joint is a 446-face CAD
// mesh whose creases the spline rounds: a looser RMS bound. femur's scan folds itself (497 of
// its edges turn by more than 90 degrees): the fold rounds round the surface there instead of
// folding it, up to crease_fold_rms_growth times the RMS: a looser bound too.
struct SeamCase {
  const char* model;
  double max_rms_relative;
};

void PrintTo(const SeamCase& c, std::ostream* os) { *os << c.model; }

class FitSurfaceSeams : public ::testing::TestWithParam<SeamCase> {};

TEST_P(FitSurfaceSeams, BelowOneDegreeAtTheDefaults) {
  const SeamCase& c = GetParam();
  FitSurfaceOptions options;
  options.density = 3;
  const FittedSurface r =
      fit_surface(ricci::read_mesh(msp_test::test_mesh(c.model)), options);
  EXPECT_TRUE(r.watertight) << c.model;
  EXPECT_LT(std::max(r.edge_normal_jump_deg, r.fill_normal_jump_deg), 1.0) << c.model;
  // The spline's own error (density 3 tessellates coarsely: the delivered RMS adds chords).
  EXPECT_LT(r.projection_rms / r.bbox_diagonal, c.max_rms_relative) << c.model;
  EXPECT_EQ(r.fallback_fills, 0) << c.model;
}

INSTANTIATE_TEST_SUITE_P(Scans, FitSurfaceSeams,
                         ::testing::Values(SeamCase{"closed_g0/bunny_npm_closed.off", 0.002},
                                           SeamCase{"closed_g2/femur.off.gz", 0.003},
                                           SeamCase{"closed_g2/joint.off", 0.004},
                                           SeamCase{"closed_g3/block.off", 0.002},
                                           SeamCase{"closed_g3/elephant_cgal.off", 0.002},
                                           SeamCase{"closed_g3/helmet.off", 0.002}),
                         [](const ::testing::TestParamInfo<SeamCase>& info) {
                           std::string name = info.param.model;
                           for (char& ch : name) {
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           }
                           return name;
                         });

// The delivered figures of a closed input are the measure of the delivered tessellation itself
// (welded as float, as a file holds it) against the input, whichever round was delivered:
// fit_surface measures every round it caps in full beside that round's own measures and keeps
// the figures of the one it delivers.
void expect_delivered_figures_of_the_tessellation(const FittedSurface& r,
                                                  const ricci::Mesh& input) {
  ASSERT_EQ(r.input.boundary_loops, 0);
  const ricci::VertexFaceArrays scan = ricci::to_arrays(input);
  std::vector<std::array<int, 3>> scan_triangles;
  for (Eigen::Index f = 0; f < scan.F.rows(); ++f)
    scan_triangles.push_back({scan.F(f, 0), scan.F(f, 1), scan.F(f, 2)});
  const TriangleSoup soup = float_welded(r.tessellation);
  ScanDistanceOptions measure;
  measure.unmeasured_surface_triangles.assign(r.tessellation.triangle_face.size(), 0);
  const ScanDistanceReport expected =
      measure_against_scan(soup.positions, soup.triangles, scan.V, scan_triangles, measure);
  EXPECT_EQ(r.fit_rms, expected.fit_rms);
  EXPECT_EQ(r.fit_max, expected.fit_max);
  EXPECT_EQ(r.fit_points, expected.scan_points);
  EXPECT_EQ(r.bbox_diagonal, expected.bbox_diagonal);
  EXPECT_EQ(r.delivered.surface_points, expected.surface_points);
  EXPECT_EQ(r.delivered.surface_to_scan_max, expected.surface_to_scan_max);
  EXPECT_EQ(r.delivered.surface_to_scan_p99, expected.surface_to_scan_p99);
  EXPECT_EQ(r.delivered.coverage, expected.coverage);
}

TEST(FitSurface, DeliveredFiguresMeasureTheDeliveredTessellation) {
  const ricci::Mesh input = ricci::read_mesh(bundled("genus2.off"));
  const FittedSurface r = fit_surface(input, small_options());
  expect_delivered_figures_of_the_tessellation(r, input);
  EXPECT_GT(r.fit_rms, 0.0);
  EXPECT_LE(r.fit_rms, r.fit_max);
}

// A closed genus-0 input is punctured by the one-cone pipeline; the puncture is one rim, always
// capped (without fill_boundaries too): a closed sphere. The knight's puncture is no height
// field (its rim normals span more than a hemisphere): the parametric patch caps it.
TEST(FitSurface, PuncturedSphereIsCapped) {
  FitSurfaceOptions options = small_options();
  const FittedSurface r = fit_surface(
      ricci::read_mesh(msp_test::test_mesh("closed_g0/knight_decimated.off")),
      options);
  EXPECT_TRUE(r.watertight);
  EXPECT_EQ(r.surface.fills.size(), 1u);
  EXPECT_TRUE(r.surface.open_rims.empty());
  EXPECT_EQ(r.boundary_rims, 0);
  EXPECT_TRUE(r.topology.closed(0));
}

}  // namespace
}  // namespace spline

namespace spline {
namespace {

// Shapes a spline folds on when its domain is too coarse or its parameters land on the wrong
// side: thin parts a few domain edges thick, and an open boundary that waves. Each fit at the
// default options must not fold (no tessellation edge over 90 degrees), must stay near the
// input both ways and, when open, reach the input's boundary.
struct ThinCase {
  std::string name;
  ricci::Mesh mesh;
};

// A sphere squashed into a plate `thickness` thick (its rim is the thin part).
ricci::Mesh plate(double thickness) {
  ricci::Mesh m = ricci::make_icosphere(5);
  for (auto v : m.vertices()) {
    auto p = m.point(v);
    m.set_point(v, ricci::Mesh::Point(p[0], p[1], 0.5 * thickness * p[2]));
  }
  return m;
}

// A fin: a plate bent into a quarter of a cylinder (thin and curved).
ricci::Mesh fin(double thickness) {
  ricci::Mesh m = plate(thickness);
  for (auto v : m.vertices()) {
    auto p = m.point(v);
    const double angle = 0.8 * p[0], radius = 1.5 + p[2];
    m.set_point(v, ricci::Mesh::Point(radius * std::sin(angle), p[1], radius * std::cos(angle)));
  }
  return m;
}

// A genus-1 body with a thin handle: a torus whose tube is 0.7 thick on one side and 0.1 on
// the other, narrowing smoothly.
ricci::Mesh thin_handle() {
  constexpr double kTube = 0.06;  // of make_torus below
  ricci::Mesh m = ricci::make_torus(160, 24, 1.0, kTube);
  for (auto v : m.vertices()) {
    auto p = m.point(v);
    const double angle = std::atan2(p[1], p[0]);
    const ricci::Mesh::Point centre(std::cos(angle), std::sin(angle), 0.0);
    const double c = 0.5 * (1.0 + std::cos(angle));
    const double tube = 0.05 + 0.3 * c * c;
    m.set_point(v, centre + (tube / kTube) * (p - centre));
  }
  return m;
}

// An annulus whose outer boundary waves in and out and up and down.
ricci::Mesh wavy_annulus() {
  ricci::Mesh m = ricci::make_annulus(24, 240, 0.4, 1.0);
  for (auto v : m.vertices()) {
    auto p = m.point(v);
    const double r = std::hypot(p[0], p[1]), angle = std::atan2(p[1], p[0]);
    const double s = 1.0 + 0.12 * r * std::sin(7 * angle);
    m.set_point(v, ricci::Mesh::Point(s * p[0], s * p[1], 0.15 * r * r * std::cos(5 * angle)));
  }
  return m;
}

class FitSurfaceThinParts : public ::testing::TestWithParam<int> {};

ThinCase thin_case(int k) {
  switch (k) {
    // About three domain edges thick (2000 faces over the plate's area 2 pi: edges ~0.085).
    case 0: return {"fin 0.25 thick", fin(0.25)};
    case 1: return {"torus with a thin tube", ricci::make_torus(160, 24, 1.0, 0.06)};
    case 2: return {"wavy annulus", wavy_annulus()};
    case 3: return {"plate 0.25 thick", plate(0.25)};
    default: return {"genus-1 body with a thin handle", thin_handle()};
  }
}

TEST_P(FitSurfaceThinParts, NoFoldAndNearTheInputBothWays) {
  const ThinCase c = thin_case(GetParam());
  const FittedSurface r = fit_surface(c.mesh);
  const double diag = r.bbox_diagonal;
  EXPECT_TRUE(r.watertight) << c.name;
  EXPECT_EQ(r.surface_dihedral.over_90_deg, 0) << c.name;
  EXPECT_EQ(r.fit_points, static_cast<int>(c.mesh.n_vertices())) << c.name;
  EXPECT_LT(r.fit_rms, 0.002 * diag) << c.name;
  EXPECT_LT(r.fit_max, 0.02 * diag) << c.name;
  EXPECT_LT(r.delivered.surface_to_scan_max, 0.02 * diag) << c.name;
  EXPECT_GT(r.delivered.coverage, 0.99) << c.name;
  if (r.input.boundary_loops > 0) {
    EXPECT_GE(r.delivered.boundary_hausdorff, 0.0) << c.name;
    EXPECT_LT(r.delivered.boundary_hausdorff, 0.005 * diag) << c.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, FitSurfaceThinParts, ::testing::Values(0, 1, 2, 3, 4));

// The first round folds; every round after it keeps its domain and control points (fold rounds
// on the same space), and the delivered surface is watertight without folds.
void expect_fold_rounds_on_the_first_space(const FittedSurface& r) {
  ASSERT_GE(r.refinement.size(), 2u);
  EXPECT_GT(r.refinement.front().folds, 0);
  for (const RefinementRound& round : r.refinement) {
    EXPECT_EQ(round.control_points, r.refinement.front().control_points);
    EXPECT_EQ(round.domain_faces, r.refinement.front().domain_faces);
  }
  EXPECT_EQ(r.surface_dihedral.over_90_deg, 0);
  EXPECT_TRUE(r.watertight);
}

// Without refinement the plate's first fit folds at its rim; the fold rounds refit the spline
// on the same space (same control points) with stronger fairing there until it does not, and
// only the delivered round is capped.
TEST(FitSurfaceFoldRounds, RefitOnTheSameSpaceUntilNoFold) {
  FitSurfaceOptions options;
  options.refinement_rounds = 0;
  const FittedSurface r = fit_surface(plate(0.25), options);
  expect_fold_rounds_on_the_first_space(r);
  EXPECT_EQ(r.surface.fills.size(), 1u);
  EXPECT_LT(r.projection_rms, 0.002 * r.bbox_diagonal);
  EXPECT_LT(r.fit_rms, 0.002 * r.bbox_diagonal);
}

// At the defaults (one refinement round) the fold rounds run first on the first fit: they
// leave the plate without folds, so the refinement round (a whole fit on a split domain) is
// never run: every round has the first one's domain and control points.
TEST(FitSurfaceFoldRounds, RunBeforeTheRefinementAndSkipIt) {
  const FittedSurface r = fit_surface(plate(0.25));
  expect_fold_rounds_on_the_first_space(r);
  EXPECT_LT(r.fit_rms, 0.002 * r.bbox_diagonal);
}

// A thinner plate with a small hole in its top (an open input): its first fit folds at the rim,
// away from the hole, so the fold rounds run first as on a closed input and refit on the first
// space (no refinement round) until no fold is left; the boundary still meets the scan's.
TEST(FitSurfaceFoldRounds, RunFirstOnAnOpenInputFoldedAwayFromItsBoundary) {
  ricci::Mesh m = plate(0.2);
  m.request_face_status();
  m.request_edge_status();
  m.request_vertex_status();
  for (auto f : m.faces()) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (auto v : m.fv_range(f)) c += ricci::to_eigen(m.point(v)) / 3.0;
    if (c.z() > 0.0 && (c.head<2>() - Eigen::Vector2d(0.3, 0.0)).norm() < 0.1) m.delete_face(f);
  }
  m.garbage_collection();
  ASSERT_EQ(ricci::surface_topology(m).boundary_loops, 1);
  const FittedSurface r = fit_surface(m);
  expect_fold_rounds_on_the_first_space(r);
  EXPECT_EQ(r.input.boundary_loops, 1);
  EXPECT_LT(r.fit_rms, 0.002 * r.bbox_diagonal);
  EXPECT_LT(r.delivered.boundary_hausdorff, 0.005 * r.bbox_diagonal);
}

// The delivery rule between folds and RMS (FitSurfaceOptions::fold_free_rms): with the fold
// rounds' RMS limits at their tightest (no growth, no goal) the plate's fold rounds, which raise
// the RMS, are refused, and without the rule its first fit, which folds at the rim, is
// delivered. With it, the refused round that leaves no fold within the acceptance RMS is
// delivered instead: no fold, RMS still within 0.2% of the diagonal.
TEST(FitSurfaceFoldRounds, AFoldFreeRoundWithinTheAcceptanceBeatsAFoldedOne) {
  FitSurfaceOptions options;
  options.refinement_rounds = 0;
  options.fold_rms_growth = 1.0;
  options.fold_rms_goal = 0.0;
  options.fold_free_rms = 0.0;
  const FittedSurface folded = fit_surface(plate(0.25), options);
  ASSERT_GE(folded.refinement.size(), 2u);
  EXPECT_GT(folded.surface_dihedral.over_90_deg, 0);
  options.fold_free_rms = FitSurfaceOptions{}.fold_free_rms;
  const FittedSurface r = fit_surface(plate(0.25), options);
  // The round delivered last (the fold-free one, capped after the folded one) is measured.
  expect_delivered_figures_of_the_tessellation(r, plate(0.25));
  EXPECT_NE(r.fit_rms, folded.fit_rms);
  EXPECT_EQ(r.surface_dihedral.over_90_deg, 0);
  EXPECT_TRUE(r.watertight);
  EXPECT_GT(r.projection_rms, folded.projection_rms);  // error traded for the folds
  EXPECT_LT(r.projection_rms, 0.002 * r.bbox_diagonal);
  EXPECT_LT(r.fit_rms, 0.002 * r.bbox_diagonal);
  // The same rounds were run; only the delivery differs.
  ASSERT_EQ(r.refinement.size(), folded.refinement.size());
  for (std::size_t k = 0; k < r.refinement.size(); ++k)
    EXPECT_EQ(r.refinement[k].folds, folded.refinement[k].folds);
}

}  // namespace
}  // namespace spline
