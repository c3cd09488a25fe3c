// The spline file: a saved surface reads back evaluating bit for bit like the saved one (the
// spline's positions and derivatives at many domain points, the fills' patches), re-encodes to
// the same bytes; bad files (truncated anywhere, wrong magic or version, counts that disagree,
// indices out of range, non-finite numbers, knots out of bounds, random corruption) are refused
// with a one-line typed error naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"
#include "spline/io/bad_splines.h"
#include "spline/io/spline_file.h"
#include "spline/io/spline_file_bytes.h"
#include "spline/surface/fit_surface.h"
#include "spline/surface/surface_fixtures.h"
#include "spline/surface/tessellate_surface.h"

namespace spline {
namespace {

using testing::section_offset;
using testing::small_surface;

template <typename A, typename B>
bool same_bits(const A& a, const B& b) {
  if (a.size() != b.size()) return false;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    const double x = a.data()[i], y = b.data()[i];
    if (std::memcmp(&x, &y, sizeof x) != 0) return false;
  }
  return true;
}

bool same_jet(const SurfaceJet& a, const SurfaceJet& b) {
  return a.chart == b.chart && same_bits(a.position, b.position) && same_bits(a.du, b.du) &&
         same_bits(a.dv, b.dv) && same_bits(a.duu, b.duu) && same_bits(a.duv, b.duv) &&
         same_bits(a.dvv, b.dvv) && same_bits(a.normal, b.normal);
}

const Eigen::Vector3d kBarycentrics[] = {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0},
                                         {0.6, 0.3, 0.1},
                                         {0.05, 0.9, 0.05},
                                         {1.0, 0.0, 0.0},
                                         {0.5, 0.5, 0.0},
                                         {0.0, 0.25, 0.75}};

// Every domain face at kBarycentrics: the loaded spline's jets equal the saved one's bit for bit.
void expect_same_spline(const ManifoldSpline& saved, const ManifoldSpline& loaded) {
  int compared = 0;
  for (int face : saved.space->domain_faces()) {
    for (const Eigen::Vector3d& bary : kBarycentrics) {
      const SurfaceJet a = saved.evaluate({face, bary});
      const SurfaceJet b = loaded.evaluate({face, bary});
      ASSERT_TRUE(same_jet(a, b)) << "face " << face << " at " << bary.transpose();
      ++compared;
    }
  }
  EXPECT_GT(compared, 1000);
}

// Points on each rim edge and halfway to the patch's centre: equal jets (value, gradient,
// Hessian), bit for bit.
void expect_same_fill(const HoleFill& saved, const HoleFill& loaded) {
  ASSERT_TRUE(loaded.space);
  EXPECT_EQ(saved.rim.edges.size(), loaded.rim.edges.size());
  EXPECT_EQ(saved.rim.covered_faces, loaded.rim.covered_faces);
  EXPECT_EQ(saved.space->function_count(), loaded.space->function_count());
  for (std::size_t j = 0; j < saved.rim.edges.size(); ++j) {
    for (double t : {0.0, 0.37, 0.81}) {
      const Eigen::Vector2d on_rim = saved.parameter(static_cast<int>(j), t);
      ASSERT_TRUE(same_bits(on_rim, loaded.parameter(static_cast<int>(j), t)));
      for (double s : {1.0, 0.5, 0.1}) {
        const Eigen::Vector2d u = saved.center + s * (on_rim - saved.center);
        const SplineJet a = saved.jet(u), b = loaded.jet(u);
        ASSERT_TRUE(same_bits(a.value, b.value) && same_bits(a.gradient, b.gradient) &&
                    same_bits(a.hessian, b.hessian))
            << "rim edge " << j << " t " << t << " s " << s;
      }
    }
  }
  EXPECT_TRUE(same_bits(saved.control_points, loaded.control_points));
  EXPECT_EQ(saved.g1, loaded.g1);
  EXPECT_EQ(saved.fallback_reason, loaded.fallback_reason);
  EXPECT_EQ(saved.max_normal_jump_deg, loaded.max_normal_jump_deg);
}

void expect_round_trip(const SplineSurface& saved) {
  const std::vector<std::uint8_t> bytes = encode_spline_surface(saved, {{"tool", "test"}});
  const SplineFile file = decode_spline_file(bytes, "round-trip");
  const SplineSurface& loaded = file.surface;
  EXPECT_EQ(file.header.version, kSplineFileVersion);
  EXPECT_EQ(file.header.provenance.at("tool"), "test");
  ASSERT_EQ(loaded.domain.n_vertices(), saved.domain.n_vertices());
  ASSERT_EQ(loaded.domain.n_faces(), saved.domain.n_faces());
  for (auto v : saved.domain.vertices()) {
    EXPECT_EQ(loaded.domain.point(v), saved.domain.point(v));
  }
  EXPECT_EQ(loaded.singular_vertex, saved.singular_vertex);
  EXPECT_EQ(loaded.skipped_faces, saved.skipped_faces);
  EXPECT_EQ(loaded.spline.space->domain_faces(), saved.spline.space->domain_faces());
  EXPECT_TRUE(same_bits(loaded.spline.control_points, saved.spline.control_points));
  expect_same_spline(saved.spline, loaded.spline);
  ASSERT_EQ(loaded.fills.size(), saved.fills.size());
  for (std::size_t i = 0; i < saved.fills.size(); ++i) {
    expect_same_fill(saved.fills[i], loaded.fills[i]);
  }
  ASSERT_EQ(loaded.open_rims.size(), saved.open_rims.size());
  for (std::size_t i = 0; i < saved.open_rims.size(); ++i) {
    EXPECT_EQ(loaded.open_rims[i].edges.size(), saved.open_rims[i].edges.size());
    EXPECT_EQ(loaded.open_rims[i].covered_faces, saved.open_rims[i].covered_faces);
  }
  // Everything stored is read back: the loaded surface encodes to the same bytes.
  EXPECT_EQ(encode_spline_surface(loaded, {{"tool", "test"}}), bytes);
}

TEST(SplineFile, ClosedSurfaceWithConeFillEvaluatesBitForBit) {
  const SplineSurface& surface = small_surface("genus2.off");
  ASSERT_EQ(surface.fills.size(), 1u);
  ASSERT_GE(surface.singular_vertex, 0);
  expect_round_trip(surface);
}

TEST(SplineFile, OpenSurfaceWithOpenRimEvaluatesBitForBit) {
  const SplineSurface& surface = small_surface("genus2_hole.off");
  ASSERT_FALSE(surface.open_rims.empty());
  expect_round_trip(surface);
}

TEST(SplineFile, TorusWithoutFillsEvaluatesBitForBit) {
  const SplineSurface& surface = small_surface("genus1.off", 200);
  EXPECT_TRUE(surface.fills.empty());
  expect_round_trip(surface);
}

// fit_surface's surface (cone-refined domain, cone and boundary patches, surface moved to meet
// them): read back, it evaluates bit for bit and tessellates to the very same mesh.
TEST(SplineFile, FittedSurfaceReadBackTessellatesBitForBit) {
  FitSurfaceOptions options;
  options.domain_faces = 400;
  options.density = 3;
  options.fill_boundaries = true;
  const FittedSurface fitted = fit_surface(
      ricci::read_mesh(std::string(MSP_SOURCE_DIR) + "/models/genus2_two_holes.off"), options);
  ASSERT_GE(fitted.surface.fills.size(), 2u);
  expect_round_trip(fitted.surface);
  const SplineSurface loaded =
      decode_spline_file(encode_spline_surface(fitted.surface), "fitted").surface;
  TessellationOptions tessellation;
  tessellation.density = fitted.tessellation.density;
  const Tessellation t = tessellate_surface(loaded, tessellation);
  EXPECT_TRUE(same_bits(t.positions, fitted.tessellation.positions));
  EXPECT_TRUE(same_bits(t.normals, fitted.tessellation.normals));
  EXPECT_TRUE(same_bits(t.uvs, fitted.tessellation.uvs));
  EXPECT_EQ(t.triangles, fitted.tessellation.triangles);
}

TEST(SplineFile, SaveIsAtomicAndLoadReadsItBack) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("msp_spline_file_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const SplineSurface& surface = small_surface("genus1.off", 200);
  const std::string path = (dir / "torus.msp").string();
  save_spline_surface(surface, path);
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    (void)entry;
    ++entries;
  }
  EXPECT_EQ(entries, 1);  // no temporary left behind
  const SplineSurface loaded = load_spline_surface(path);
  expect_same_spline(surface.spline, loaded.spline);
  EXPECT_THROW(save_spline_surface(surface, (dir / "no" / "such" / "x.msp").string()),
               ricci::IOError);
  EXPECT_THROW((void)load_spline_surface((dir / "missing.msp").string()), ricci::IOError);
  fs::remove_all(dir);
}

// Decoding `bytes` throws a ricci::Error of type E whose message is one line, starts with the
// source and contains `keyword`.
template <typename E>
void expect_refused(const std::vector<std::uint8_t>& bytes, const std::string& keyword) {
  try {
    (void)decode_spline_file(bytes, "bad.msp");
    ADD_FAILURE() << "accepted; expected: " << keyword;
  } catch (const E& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("bad.msp: ", 0), 0u) << message;
    EXPECT_NE(message.find(keyword), std::string::npos) << message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what() << " (expected: " << keyword << ")";
  }
}

const std::vector<std::uint8_t>& torus_bytes() {
  static const std::vector<std::uint8_t> bytes =
      encode_spline_surface(small_surface("genus1.off", 200));
  return bytes;
}

const std::vector<std::uint8_t>& genus2_bytes() {
  static const std::vector<std::uint8_t> bytes = encode_spline_surface(small_surface("genus2.off"));
  return bytes;
}

TEST(SplineFileBad, TruncatedAnywhereIsRefused) {
  // Cuts past the FILL section decode the whole surface (the patch's space is the slow part):
  // fewer of them on the file with a fill.
  for (const auto* good : {&torus_bytes(), &genus2_bytes()}) {
    const std::size_t size = good->size();
    const bool filled = good == &genus2_bytes();
    std::vector<std::size_t> cuts;
    for (std::size_t n = 0; n < 400 && n < size; ++n) cuts.push_back(n);
    for (std::size_t n = 400; n < size; n += size / (filled ? 60 : 200)) cuts.push_back(n);
    for (std::size_t n = size - (filled ? 2 : 32); n < size; ++n) cuts.push_back(n);
    for (std::size_t n : cuts) {
      SCOPED_TRACE(n);
      const std::vector<std::uint8_t> cut(good->begin(), good->begin() + n);
      expect_refused<ricci::IOError>(cut, n < 16 && n > 0 ? "truncated" : "");
    }
  }
  expect_refused<ricci::IOError>(
      std::vector<std::uint8_t>(torus_bytes().begin(), torus_bytes().end() - 1),
      "file ends before section END (truncated)");
}

TEST(SplineFileBad, WrongMagicAndVersionAreRefused) {
  std::vector<std::uint8_t> bytes = torus_bytes();
  bytes[1] = 'X';
  expect_refused<ricci::IOError>(bytes, "not an msp spline file");
  const std::string text = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  expect_refused<ricci::IOError>(std::vector<std::uint8_t>(text.begin(), text.end()), "bad magic");
  bytes = torus_bytes();
  bytes[8] = 2;  // version 2
  expect_refused<ricci::IOError>(bytes, "format version 2 is not supported");
}

TEST(SplineFileBad, HeaderCountsThatDisagreeAreRefused) {
  for (const char* key : {"faces", "control_points", "fills", "charts", "degree"}) {
    SCOPED_TRACE(key);
    expect_refused<ricci::IOError>(testing::with_header_value(torus_bytes(), key, 7),
                                   std::string("inconsistent counts: the header says ") + key);
  }
  expect_refused<ricci::IOError>(testing::with_header_text(torus_bytes(), "{\"format\": 3"),
                                 "the header is not a JSON object");
}

TEST(SplineFileBad, SectionLengthsThatDisagreeAreRefused) {
  std::vector<std::uint8_t> bytes = torus_bytes();
  const std::size_t atlas = section_offset(bytes, "ATLS") + 4;
  // The section claims 8 more bytes than its contents.
  testing::write_u64(bytes, atlas, testing::read_u64(bytes, atlas) + 8);
  expect_refused<ricci::IOError>(bytes, "inconsistent counts: 8 bytes left over");
  bytes = torus_bytes();
  const std::size_t spline = section_offset(bytes, "SPLN") + 4;
  testing::write_u64(bytes, spline, testing::read_u64(bytes, spline) - 1);
  expect_refused<ricci::IOError>(bytes, "section SPLN");
  bytes = torus_bytes();
  std::memcpy(bytes.data() + section_offset(bytes, "FILL"), "XXXX", 4);
  expect_refused<ricci::IOError>(bytes, "expected section FILL");
}

TEST(SplineFileBad, IndicesOutOfRangeAreRefused) {
  std::vector<std::uint8_t> bytes = torus_bytes();
  const std::size_t mesh = section_offset(bytes, "MESH") + 12;
  const std::size_t vertices = testing::read_u64(bytes, mesh);
  const std::size_t first_face = mesh + 8 + 24 * vertices + 8;
  testing::write_u32(bytes, first_face + 4, 1000000);
  expect_refused<ricci::InvalidInputError>(bytes, "face 0 has vertex index 1000000 outside");
  bytes = torus_bytes();
  testing::write_u32(bytes, first_face + 4, testing::read_u32(bytes, first_face));
  expect_refused<ricci::InvalidInputError>(bytes, "domain mesh: face 0");
}

TEST(SplineFileBad, NonFiniteNumbersAreRefused) {
  SplineSurface surface;
  const SplineSurface& good = small_surface("genus1.off", 200);
  surface.domain = good.domain;
  surface.spline = good.spline;
  surface.skipped_faces = good.skipped_faces;
  surface.spline.control_points(17, 1) = std::numeric_limits<double>::quiet_NaN();
  expect_refused<ricci::InvalidInputError>(encode_spline_surface(surface),
                                           "control point 17 is not finite");
  surface.spline.control_points(17, 1) = 0.0;
  surface.domain.set_point(surface.domain.vertex_handle(3),
                           {0.0, std::numeric_limits<double>::infinity(), 0.0});
  expect_refused<ricci::InvalidInputError>(encode_spline_surface(surface),
                                           "vertex 3 is not finite");
}

TEST(SplineFileBad, KnotsOutsideTheirBoundAreRefused) {
  std::vector<std::uint8_t> bytes = torus_bytes();
  // SPLN: degree (4), cloud count (8), then vertex 0's knot count (4) and knots (16 each).
  const std::size_t second_knot = section_offset(bytes, "SPLN") + 12 + 4 + 8 + 4 + 16;
  double x = 0.0;
  std::memcpy(&x, bytes.data() + second_knot, sizeof x);
  x += 1.0;
  std::memcpy(bytes.data() + second_knot, &x, sizeof x);
  expect_refused<ricci::InvalidInputError>(
      bytes, "home cloud of vertex 0 has a knot farther than half the smallest inradius");
}

// Random corruption of single bytes: refused with a typed error or read as another valid
// surface, never a crash (run under ASan / UBSan too).
TEST(SplineFileBad, CorruptedBytesNeverCrash) {
  std::mt19937 random(7);
  for (const auto* good : {&torus_bytes(), &genus2_bytes()}) {
    std::uniform_int_distribution<std::size_t> position(0, good->size() - 1);
    for (int trial = 0; trial < (good == &torus_bytes() ? 150 : 20); ++trial) {
      std::vector<std::uint8_t> bytes = *good;
      const std::size_t at = position(random);
      bytes[at] = static_cast<std::uint8_t>(bytes[at] ^ (1u << (trial % 8)));
      try {
        (void)decode_spline_file(bytes, "corrupt.msp");
      } catch (const ricci::Error& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      }
    }
  }
}

// The bad files of the corpus, made from a small torus by one change each (bad_splines.h).
std::vector<std::uint8_t> make_bad_spline(const std::string& name) {
  SplineSurface surface = small_surface("genus1.off", 100);
  if (name == "nan_control_point.msp") {
    surface.spline.control_points(5, 2) = std::numeric_limits<double>::quiet_NaN();
  }
  std::vector<std::uint8_t> bytes = encode_spline_surface(surface, {{"corpus", name}});
  if (name == "truncated.msp") bytes.resize(section_offset(bytes, "ATLS") + 100);
  // The reader stops at the preamble of these two: their first 4 KB are enough.
  if (name == "wrong_magic.msp") {
    std::memcpy(bytes.data(), "OFF\n", 4);
    bytes.resize(4096);
  }
  if (name == "wrong_version.msp") {
    testing::write_u32(bytes, 8, 99);
    bytes.resize(4096);
  }
  if (name == "inconsistent_counts.msp") {
    const int faces = static_cast<int>(surface.domain.n_faces());
    bytes = testing::with_header_value(bytes, "faces", 101);
    EXPECT_NE(faces, 101);
  }
  if (name == "index_out_of_range.msp") {
    const std::size_t mesh = section_offset(bytes, "MESH") + 12;
    const std::size_t faces = mesh + 8 + 24 * testing::read_u64(bytes, mesh) + 8;
    testing::write_u32(bytes, faces + 2 * 12 + 4, 4096);
  }
  return bytes;
}

// Run by hand (--gtest_also_run_disabled_tests) to write the corpus into tests/data/bad.
TEST(SplineFileCorpus, DISABLED_WriteBadSplines) {
  for (const auto& bad : testing::kBadSplines) {
    const std::vector<std::uint8_t> bytes = make_bad_spline(bad.name);
    const std::string path = std::string(MSP_TEST_DATA) + "/bad/" + bad.name;
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_TRUE(file) << path;
    EXPECT_EQ(std::fwrite(bytes.data(), 1, bytes.size(), file), bytes.size());
    std::fclose(file);
  }
}

TEST(SplineFileCorpus, EveryBadSplineIsRefusedWithItsKeyword) {
  for (const auto& bad : testing::kBadSplines) {
    SCOPED_TRACE(bad.name);
    const std::string path = std::string(MSP_TEST_DATA) + "/bad/" + bad.name;
    try {
      (void)load_spline_surface(path);
      ADD_FAILURE() << "accepted";
    } catch (const ricci::Error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
      EXPECT_NE(message.find(bad.keyword), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace spline
