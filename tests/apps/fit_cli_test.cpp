// `msp fit`, run as a user runs it (the real binary): the .glb validates clean and is
// watertight when read back, the report holds the keys, and bad input leaves nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

#include "msp/io/gltf_reader.h"
#include <ricci/mesh/arrays.h>
#include <ricci/mesh/io.h>
#include <ricci/mesh/primitives.h>
#include <spline/tessellate/dihedral.h>
#include <spline/tessellate/scan_distance.h>
#include <spline/tessellate/tessellate.h>
#include <tiny_gltf.h>

#include "apps/gltf_test_util.h"
#include "apps/info_subprocess.h"
#include "test_paths.h"

namespace {

namespace fs = std::filesystem;
using msp_test::run_msp;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("msp_fit_tests_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string model(const std::string& name) {
  return msp_test::bundled_model(name);
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

template <typename T>
std::vector<T> read_accessor(const tinygltf::Model& m, int index, int components) {
  const auto& a = m.accessors[static_cast<size_t>(index)];
  const auto& view = m.bufferViews[static_cast<size_t>(a.bufferView)];
  const auto& data = m.buffers[static_cast<size_t>(view.buffer)].data;
  std::vector<T> out(a.count * static_cast<size_t>(components));
  std::memcpy(out.data(), data.data() + view.byteOffset + a.byteOffset, out.size() * sizeof(T));
  return out;
}

// The surface of a .glb welded the way a user's tool would: vertices with bit-identical float
// positions are one vertex (uv seams split render vertices only).
spline::WatertightReport glb_surface_topology(const fs::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, path.string())) << err;
  const auto& surface = m.meshes.at(0).primitives.at(0);
  EXPECT_EQ(m.meshes[0].name, "surface");
  EXPECT_EQ(m.accessors[static_cast<size_t>(surface.indices)].componentType,
            TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  const auto xyz = read_accessor<float>(m, surface.attributes.at("POSITION"), 3);
  const auto indices = read_accessor<std::uint32_t>(m, surface.indices, 1);
  std::map<std::tuple<float, float, float>, int> weld;
  std::vector<int> welded(xyz.size() / 3);
  for (size_t v = 0; v < welded.size(); ++v) {
    const auto key = std::make_tuple(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    welded[v] = weld.emplace(key, static_cast<int>(weld.size())).first->second;
  }
  Eigen::MatrixX3d positions(static_cast<Eigen::Index>(weld.size()), 3);
  for (const auto& [key, i] : weld)
    positions.row(i) << std::get<0>(key), std::get<1>(key), std::get<2>(key);
  std::vector<std::array<int, 3>> triangles;
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    triangles.push_back({welded[indices[t]], welded[indices[t + 1]], welded[indices[t + 2]]});
  return spline::check_watertight(triangles, positions);
}

void expect_validator_clean(const fs::path& glb) {
  const auto report = msp_test::run_gltf_validator(glb.string());
  if (!report) GTEST_SKIP() << "node or tools/node_modules missing (scripts/install-deps.sh)";
  EXPECT_EQ(report->value("errors", -1), 0) << report->dump(1);
  EXPECT_EQ(report->value("warnings", -1), 0) << report->dump(1);
}

// Every key of the report, seconds per stage and in total.
void expect_report_keys(const nlohmann::json& r) {
  for (const char* key :
       {"genus", "singularities", "domain_faces", "control_points", "degree", "fairness", "fit_rms",
        "fit_max", "bbox_diagonal", "seam_normal_jump_max_deg", "watertight", "seconds"}) {
    EXPECT_TRUE(r.contains(key)) << key;
  }
  for (const char* stage : {"read", "simplify", "atlas", "fit", "tessellate", "total"})
    EXPECT_TRUE(r["seconds"].contains(stage)) << stage;
  double sum = 0.0;
  for (const auto& [name, s] : r["seconds"].items())
    if (name != "total") sum += s.get<double>();
  EXPECT_LE(sum, r["seconds"]["total"].get<double>() * 1.001);
}

const std::vector<std::string> kSmall = {"--domain-faces", "400", "--density", "3", "--quiet"};

std::vector<std::string> args(std::vector<std::string> head,
                              const std::vector<std::string>& tail = kSmall) {
  head.insert(head.end(), tail.begin(), tail.end());
  return head;
}

TEST(FitCli, TorusGivesAWatertightValidGlbAndReport) {
  const fs::path dir = fresh_dir("torus");
  const auto r = run_msp(args({"fit", model("genus1.off"), "-o", (dir / "t.glb").string(), "--json",
                               (dir / "t.json").string(), "--checkerboard", "--control-net",
                               "--domain", "--cut-loops", "--ply", (dir / "t.ply").string()}));
  ASSERT_EQ(r.exit_status, 0) << r.err;
  EXPECT_EQ(r.err, "");  // --quiet
  const nlohmann::json report = read_json(dir / "t.json");
  expect_report_keys(report);
  EXPECT_EQ(report["genus"], 1);
  EXPECT_EQ(report["degree"], 3);
  EXPECT_EQ(report["fairness"], 1);
  EXPECT_TRUE(report["singularities"].empty());
  EXPECT_EQ(report["control_points"].get<int>(), 10 * report["domain_faces"].get<int>());
  EXPECT_TRUE(report["watertight"].get<bool>());
  EXPECT_LT(report["seam_normal_jump_max_deg"].get<double>(), 1.0);
  EXPECT_LE(report["fit_rms"].get<double>(), report["fit_max"].get<double>());
  EXPECT_LT(report["fit_rms"].get<double>(), 0.01 * report["bbox_diagonal"].get<double>());

  // Read back: the surface is closed with the torus' Euler characteristic.
  const auto topology = glb_surface_topology(dir / "t.glb");
  EXPECT_TRUE(topology.closed(1)) << topology.boundary_edges << " boundary edges, chi "
                                  << topology.euler_characteristic;
  EXPECT_EQ(topology.faces, report["tessellation"]["triangles"].get<int>());
  // The PLY is the welded tessellation: the mesh reader sees a closed torus.
  const ricci::Mesh ply = ricci::read_mesh((dir / "t.ply").string());
  const auto t = ricci::surface_topology(ply);
  EXPECT_EQ(t.genus, 1);
  EXPECT_EQ(t.boundary_loops, 0);
  EXPECT_EQ(t.faces, topology.faces);
  expect_validator_clean(dir / "t.glb");
}

// Metadata in the scene's extras and the optional nodes.
TEST(FitCli, GlbCarriesExtrasAndExtraNodes) {
  const fs::path dir = fresh_dir("extras");
  const auto r = run_msp(args({"fit", model("genus2.off"), "-o", (dir / "g.glb").string(),
                               "--control-net", "--domain", "--cut-loops", "--obj",
                               (dir / "g.obj").string(), "--json", (dir / "g.json").string()}));
  ASSERT_EQ(r.exit_status, 0) << r.err;
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, (dir / "g.glb").string())) << err;
  std::vector<std::string> names;
  for (const auto& mesh : m.meshes) names.push_back(mesh.name);
  EXPECT_EQ(names.front(), "surface");
  EXPECT_NE(std::find(names.begin(), names.end(), "control net"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "domain mesh"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "extraordinary point"), names.end());
  EXPECT_EQ(std::count_if(names.begin(), names.end(),
                          [](const std::string& n) { return n.rfind("cut loop", 0) == 0; }),
            4);  // 2g loops
  const auto& extras = m.scenes[0].extras;
  EXPECT_EQ(extras.Get("genus").GetNumberAsInt(), 2);
  EXPECT_EQ(extras.Get("degree").GetNumberAsInt(), 3);
  EXPECT_EQ(extras.Get("r").GetNumberAsInt(), 1);
  EXPECT_EQ(extras.Get("singularities").ArrayLen(), 1u);
  EXPECT_GT(extras.Get("fit_error").Get("rms").GetNumberAsDouble(), 0.0);
  // The OBJ holds the welded surface of genus 2. The report's `watertight` is what a user's
  // tool sees: the .glb's surface welded by float position is a closed genus-2 surface exactly
  // when the report says so (the fill patch of main's first hole-filling version collapses
  // parts of itself to a point, which only the float weld shows).
  const ricci::Mesh obj = ricci::read_mesh((dir / "g.obj").string());
  EXPECT_EQ(ricci::surface_topology(obj).genus, 2);
  const auto report = read_json(dir / "g.json");
  const auto topology = glb_surface_topology(dir / "g.glb");
  EXPECT_EQ(topology.closed(2), report["watertight"].get<bool>())
      << "loops " << topology.boundary_loops << " chi " << topology.euler_characteristic
      << " nonmanifold edges " << topology.nonmanifold_edges << " degenerate "
      << topology.degenerate_triangles;
  EXPECT_EQ(report["filled_rims"], 1);
  EXPECT_EQ(report["open_rims"], 0);
  // The one patch is the cone hole's: a disk of domain faces, a part of the surface, whose
  // seam is the report's fill seam.
  const auto& patches = report["fill_patches"];
  ASSERT_EQ(patches.size(), 1u);
  EXPECT_EQ(patches[0]["kind"], "cone_hole");
  EXPECT_GT(patches[0]["covered_faces"].get<int>(), 0);
  EXPECT_GE(patches[0]["rim_edges"].get<int>(), 3);
  EXPECT_GT(patches[0]["area_fraction"].get<double>(), 0.0);
  EXPECT_LT(patches[0]["area_fraction"].get<double>(), 0.5);
  EXPECT_GT(patches[0]["extent_relative"].get<double>(), 0.0);
  EXPECT_LE(patches[0]["extent_relative"].get<double>(), 1.0 + 1e-9);
  EXPECT_GE(patches[0]["normal_spread_deg"].get<double>(), 0.0);
  EXPECT_LE(patches[0]["normal_spread_deg"].get<double>(), 180.0);
  EXPECT_TRUE(patches[0]["g1"].get<bool>());
  EXPECT_EQ(patches[0]["max_normal_jump_deg"].get<double>(),
            report["fill_normal_jump_max_deg"].get<double>());
  // genus2's patch meets its rim within a few degrees: no rim edge where it folds back.
  EXPECT_EQ(patches[0]["rim_edges_over_90_deg"], 0);
  ASSERT_EQ(patches[0]["worst_rim_point"].size(), 3u);
  for (const auto& x : patches[0]["worst_rim_point"]) EXPECT_TRUE(std::isfinite(x.get<double>()));
  // A smooth model gives a smooth surface: no tessellation edge where it folds back (measured
  // at 400 faces and density 3: between neighbouring triangles 2.6 degrees median, 15.5 at the
  // 99th percentile, 24 at most).
  const auto& dihedral = report["surface_dihedral"];
  EXPECT_GT(dihedral["edges"].get<int>(), 0);
  EXPECT_EQ(dihedral["edges_over_60_deg"], 0);
  EXPECT_LT(dihedral["p99_deg"].get<double>(), 20.0);
  expect_validator_clean(dir / "g.glb");
}

// --smoothing sets the thin-plate weight: a much stiffer surface misses the points by more.
TEST(FitCli, SmoothingWeightsTheThinPlate) {
  const fs::path dir = fresh_dir("smoothing");
  double rms[2];
  const char* weights[2] = {"1e-4", "1"};
  for (int i = 0; i < 2; ++i) {
    const auto json = dir / (std::string("s") + weights[i] + ".json");
    const auto r = run_msp(args({"fit", model("genus1.off"), "--smoothing", weights[i], "--json",
                                 json.string()}));
    ASSERT_EQ(r.exit_status, 0) << r.err;
    rms[i] = read_json(json)["fit_rms"].get<double>();
  }
  EXPECT_GT(rms[1], 2.0 * rms[0]);
}

// A given singular vertex becomes the domain vertex nearest to it.
TEST(FitCli, SingularVertexIsHonoured) {
  const fs::path dir = fresh_dir("singular");
  const ricci::Mesh mesh = ricci::read_mesh(model("genus2.off"));
  const int v = 123;
  const auto r = run_msp(args({"fit", model("genus2.off"), "--singularity", std::to_string(v),
                               "--json", (dir / "s.json").string()}));
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto report = read_json(dir / "s.json");
  ASSERT_EQ(report["singularities"].size(), 1u);
  const auto& s = report["singularities"][0];
  EXPECT_EQ(s["input_vertex"], v);
  const auto p = ricci::to_eigen(mesh.point(mesh.vertex_handle(v)));
  const Eigen::Vector3d q(s["position"][0].get<double>(), s["position"][1].get<double>(),
                          s["position"][2].get<double>());
  // Within a domain edge or so (400 faces on a diagonal-4 model: edges ~0.15).
  EXPECT_LT((p - q).norm(), 0.05 * report["bbox_diagonal"].get<double>());
  EXPECT_NEAR(s["curvature"].get<double>(), -4 * M_PI, 1e-6);
  // The domain is refined around the cone by default (--cone-refinement 2).
  EXPECT_EQ(report["cone_refinement"]["levels"], 2);
  EXPECT_EQ(report["cone_refinement"]["rings"], 6);
  EXPECT_GT(report["cone_refinement"]["added_faces"].get<int>(), 0);
}

// Below degree 3 the fairing order defaults to 0 (spline::default_fairness): at degree 2, r = 1
// (= n - 1) held the fit so close to its neighbours' polynomials that genus2's surface left the
// input (a spike 7% of the diagonal out, refused after 27 rounds).
TEST(FitCli, DegreeTwoTakesFairnessZero) {
  const fs::path dir = fresh_dir("degree2");
  const auto r = run_msp(
      args({"fit", model("genus2.off"), "--degree", "2", "--json", (dir / "d.json").string()}));
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto report = read_json(dir / "d.json");
  EXPECT_EQ(report["degree"], 2);
  EXPECT_EQ(report["fairness"], 0);
  EXPECT_TRUE(report["watertight"].get<bool>());
  EXPECT_EQ(report["folds"]["count"], 0);
  EXPECT_LT(report["fit_rms_relative"].get<double>(), 2e-3);
}

// --cone-refinement 0: the simplified mesh is the domain as it is (after the valence
// modification), and the report says so.
TEST(FitCli, ConeRefinementCanBeTurnedOff) {
  const fs::path dir = fresh_dir("unrefined");
  const auto r = run_msp(args({"fit", model("genus2.off"), "--cone-refinement", "0", "--json",
                               (dir / "u.json").string()}));
  ASSERT_EQ(r.exit_status, 0) << r.err;
  const auto report = read_json(dir / "u.json");
  EXPECT_EQ(report["cone_refinement"]["levels"], 0);
  EXPECT_EQ(report["cone_refinement"]["added_faces"], 0);
  EXPECT_TRUE(report["watertight"].get<bool>());
}

// Progress: one line per stage on stderr, each with its seconds.
TEST(FitCli, ProgressLinesPerStage) {
  const fs::path dir = fresh_dir("progress");
  const auto r = run_msp({"fit", model("genus1.off"), "--domain-faces", "400", "--density", "2",
                          "--json", (dir / "p.json").string()});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  // No "fair" line: the default fit is constrained to the fairing constraints, so fit_scan
  // skips the separate fairing (it would change nothing).
  for (const char* stage : {"read", "simplify", "atlas", "space", "parameters", "fit", "fill",
                            "tessellate", "measure", "export", "write"}) {
    const std::string line = std::string("msp fit: ") + stage + "... ";
    const auto at = r.err.find(line);
    ASSERT_NE(at, std::string::npos) << stage << "\n" << r.err;
    EXPECT_NE(r.err.find(" s\n", at), std::string::npos);
  }
}

// The report's figures are those of the written .glb measured from outside (read back by
// libio's reader, every scan vertex to it and its points back to the scan): a real open scan
// (boundary figures) and a closed genus-2 model with a cone.
TEST(FitCli, ReportMeasuresTheWrittenGlb) {
  for (const std::string& input : {msp_test::test_mesh("open/eight_open.off"), model("genus2.off")}) {
    const fs::path dir = fresh_dir("outside");
    const auto r = run_msp(args({"fit", input, "-o", (dir / "s.glb").string(), "--json",
                                 (dir / "s.json").string()}));
    ASSERT_EQ(r.exit_status, 0) << r.err;
    const nlohmann::json report = read_json(dir / "s.json");
    const auto glb = msp::gltf::read_glb_triangles((dir / "s.glb").string());
    const auto scan = ricci::to_arrays(ricci::read_mesh(input));
    std::vector<std::array<int, 3>> scan_triangles;
    for (Eigen::Index f = 0; f < scan.F.rows(); ++f)
      scan_triangles.push_back({scan.F(f, 0), scan.F(f, 1), scan.F(f, 2)});
    const auto d =
        spline::measure_against_scan(glb.positions, glb.triangles, scan.V, scan_triangles);
    const double diag = d.bbox_diagonal;
    const auto near = [](double reported, double measured) {
      return std::abs(reported - measured) <= 0.01 * std::abs(measured) + 1e-12;
    };
    EXPECT_EQ(report["fit_points"].get<int>(), scan.V.rows()) << input;  // every vertex
    EXPECT_TRUE(near(report["fit_rms"].get<double>(), d.fit_rms)) << input;
    EXPECT_TRUE(near(report["fit_max"].get<double>(), d.fit_max)) << input;
    const auto& s2s = report["surface_to_scan"];
    EXPECT_TRUE(near(s2s["p99_relative"].get<double>() * diag, d.surface_to_scan_p99)) << input;
    EXPECT_TRUE(near(s2s["max_relative"].get<double>() * diag, d.surface_to_scan_max)) << input;
    EXPECT_TRUE(near(report["coverage"]["fraction"].get<double>(), d.coverage)) << input;
    const double hausdorff = report["boundary"]["hausdorff_relative"].get<double>();
    if (d.boundary_hausdorff < 0) {
      EXPECT_EQ(hausdorff, -1.0) << input;  // closed: no boundary to compare
    } else {
      EXPECT_TRUE(near(hausdorff * diag, d.boundary_hausdorff)) << input;
    }
    EXPECT_EQ(report["folds"]["count"].get<int>(),
              spline::dihedral_angles(glb.triangles, glb.positions).over_90_deg)
        << input;
    // Every fold has one place; "next to the cone" is measured from a cone patch, if any.
    const auto& folds = report["folds"];
    EXPECT_EQ(folds["on_patches"].get<int>() + folds["on_spline_near_cone"].get<int>() +
                  folds["on_spline_elsewhere"].get<int>(),
              folds["count"].get<int>())
        << input;
    bool cone_patch = false;
    for (const auto& patch : report["fill_patches"])
      cone_patch = cone_patch || patch["kind"] == "cone_hole";
    EXPECT_EQ(folds["near_cone_radius_relative"].get<double>() > 0.0, cone_patch) << input;
    // And they are good: the surface reaches the scan, its boundary too, nothing sticks out.
    EXPECT_LT(d.fit_rms, 0.005 * diag) << input;
    EXPECT_LT(d.surface_to_scan_max, 0.02 * diag) << input;
    EXPECT_GT(d.coverage, 0.99) << input;
    if (d.scan_boundary_edges > 0) {
      EXPECT_LT(d.boundary_hausdorff, 0.005 * diag) << input;
    }
  }
}

struct BadCase {
  std::vector<std::string> arguments;  // after "fit"; {OUT} is the output folder
  std::string message;                 // part of the one stderr line
  int status;
};

void expect_refused(const std::string& name, const BadCase& c) {
  const fs::path dir = fresh_dir("bad_" + name);
  std::vector<std::string> a = {"fit"};
  for (auto s : c.arguments) {
    const auto at = s.find("{OUT}");
    if (at != std::string::npos) s.replace(at, 5, dir.string());
    a.push_back(s);
  }
  const auto r = run_msp(a);
  EXPECT_EQ(r.exit_status, c.status) << name << ": " << r.err;
  EXPECT_EQ(msp_test::line_count(r.err), 1) << name << ": " << r.err;
  EXPECT_NE(r.err.find(c.message), std::string::npos) << name << ": " << r.err;
  EXPECT_TRUE(fs::is_empty(dir)) << name << ": an output was left behind";
}

TEST(FitCli, RefusesNonManifoldInput) {
  for (const char* file : {"bowtie.off", "fin_edge.off", "mobius.obj"}) {
    expect_refused(file, {{std::string(MSP_TEST_DATA) + "/bad/" + file, "-o", "{OUT}/x.glb",
                           "--json", "{OUT}/x.json", "--quiet"},
                          file,
                          1});
  }
}

TEST(FitCli, RefusesTooFewDomainFaces) {
  expect_refused("few", {{model("genus2.off"), "--domain-faces", "10", "-o", "{OUT}/x.glb",
                          "--json", "{OUT}/x.json", "--quiet"},
                         "too few domain faces: 10",
                         1});
  // Without --quiet the progress line is closed before the error line.
  const fs::path dir = fresh_dir("few_loud");
  const auto r =
      run_msp({"fit", model("genus2.off"), "--domain-faces", "10", "-o", (dir / "x.glb").string()});
  EXPECT_EQ(r.exit_status, 1);
  EXPECT_NE(r.err.find("\nmsp fit: error: too few domain faces: 10"), std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(FitCli, RefusesSingularVertexOnTheBoundary) {
  const ricci::Mesh open = ricci::read_mesh(model("genus1_hole.off"));
  int boundary = -1;
  for (auto v : open.vertices())
    if (open.is_boundary(v)) boundary = v.idx();
  ASSERT_GE(boundary, 0);
  expect_refused("boundary",
                 {{model("genus1_hole.off"), "--singularity", std::to_string(boundary), "-o",
                   "{OUT}/x.glb", "--quiet"},
                  "singular vertex " + std::to_string(boundary) + " lies on the boundary",
                  1});
  expect_refused("range",
                 {{model("genus2.off"), "--singularity", "999999", "-o", "{OUT}/x.glb", "--quiet"},
                  "out of range",
                  1});
}

// The guard against points of the surface far from the scan: with a limit no surface meets,
// the run fails loudly and writes nothing.
TEST(FitCli, SurfaceFarFromTheScanFailsTheRun) {
  expect_refused("deviation", {{model("genus1.off"), "--max-deviation", "1e-7", "--domain-faces",
                                "400", "--density", "2", "-o", "{OUT}/x.glb", "--json",
                                "{OUT}/x.json", "--quiet"},
                               "of the bounding-box diagonal from the input (limit",
                               1});
  expect_refused("deviation-arg",
                 {{model("genus1.off"), "-o", "{OUT}/x.glb", "--max-deviation", "-1"},
                  "--max-deviation",
                  2});
  expect_refused("small-holes-arg",
                 {{model("genus1.off"), "-o", "{OUT}/x.glb", "--small-holes", "-0.1"},
                  "--small-holes must be in [0, 1)",
                  2});
}

TEST(FitCli, RefusesUnreadableFiles) {
  expect_refused("missing",
                 {{"/nonexistent/none.off", "-o", "{OUT}/x.glb", "--quiet"}, "none.off", 1});
  expect_refused("garbage", {{std::string(MSP_TEST_DATA) + "/bad/garbage.off", "-o", "{OUT}/x.glb",
                              "--json", "{OUT}/x.json", "--quiet"},
                             "garbage.off",
                             1});
}

TEST(FitCli, RefusesBadCommandLines) {
  expect_refused("folder", {{model("genus1.off"), "-o", "{OUT}/x.glb", "--json", "{OUT}/no/x.json"},
                            "does not exist",
                            1});
  expect_refused("ext", {{model("genus1.off"), "-o", "{OUT}/x.gltf"}, "-o must name a .glb", 2});
  expect_refused("none", {{model("genus1.off")}, "nothing to write", 2});
  expect_refused("degree",
                 {{model("genus1.off"), "-o", "{OUT}/x.glb", "--degree", "9"}, "--degree", 2});
  expect_refused("fair",
                 {{model("genus1.off"), "-o", "{OUT}/x.glb", "--fairness", "3"}, "--fairness", 2});
  expect_refused(
      "sing",
      {{model("genus1.off"), "-o", "{OUT}/x.glb", "--singularity", "x"}, "--singularity", 2});
  expect_refused("cone", {{model("genus1.off"), "-o", "{OUT}/x.glb", "--cone-refinement", "9"},
                          "--cone-refinement",
                          2});
  expect_refused("grading",
                 {{model("genus1.off"), "-o", "{OUT}/x.glb", "--cone-grading", "7"},
                  "--cone-grading must be in [0, 4]",
                  2});
  expect_refused("grading-number",
                 {{model("genus1.off"), "-o", "{OUT}/x.glb", "--cone-grading", "two"},
                  "option --cone-grading expects an integer, got 'two'",
                  2});
  expect_refused("turns",
                 {{model("genus1.off"), "-o", "{OUT}/x.glb", "--turn-refinement", "7"},
                  "--turn-refinement",
                  2});
  expect_refused("smooth",
                 {{model("genus1.off"), "-o", "{OUT}/x.glb", "--smoothing", "-1"},
                  "--smoothing",
                  2});
  expect_refused("unknown",
                 {{model("genus1.off"), "-o", "{OUT}/x.glb", "--colour", "red"}, "--colour", 2});
}

}  // namespace
