// read_mesh()/write_mesh() round trips (exact doubles, every writable format, atomic output) and
// the (V, F) adapters.
#include <gtest/gtest.h>

#include <filesystem>

#include "procedural_soups.h"
#include "ricci/mesh/arrays.h"
#include "ricci/mesh/build_mesh.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"

namespace {

namespace fs = std::filesystem;

class MeshIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ricci_mesh_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

/// A torus whose coordinates need all 17 digits (thirds, sevenths, large magnitudes).
ricci::Mesh awkward_torus() {
  auto soup = ricci_test::torus(7, 5);
  for (size_t v = 0; v < soup.positions.size(); ++v)
    soup.positions[v] = soup.positions[v].cwiseProduct(Eigen::Vector3d(1.0 / 3.0, 0.1, 1e5 / 7.0)) +
                        Eigen::Vector3d(1e-3 * v / 7.0, 0, 0);
  return ricci::build_mesh(soup);
}

TEST_F(MeshIo, WriteThenReadIsExactInEveryFormat) {
  const ricci::Mesh mesh = awkward_torus();
  for (const char* name : {"m.obj", "m.off", "m.ply"}) {
    SCOPED_TRACE(name);
    const std::string path = (dir_ / name).string();
    ricci::write_mesh(mesh, path);
    const ricci::Mesh back = ricci::read_mesh(path);
    ASSERT_EQ(back.n_vertices(), mesh.n_vertices());
    ASSERT_EQ(back.n_faces(), mesh.n_faces());
    for (const auto v : mesh.vertices()) EXPECT_EQ(back.point(v), mesh.point(v));  // bitwise
    const auto a = ricci::to_arrays(mesh), b = ricci::to_arrays(back);
    EXPECT_EQ(a.F, b.F);
  }
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) files += entry.is_regular_file();
  EXPECT_EQ(files, 3u) << "a temporary file was left behind";
}

TEST_F(MeshIo, WriteRefusesUnsupportedTargetsAndLeavesNothing) {
  const ricci::Mesh mesh = ricci::build_mesh(ricci_test::tetrahedron());
  EXPECT_THROW(ricci::write_mesh(mesh, (dir_ / "m.stl").string()), ricci::IOError);
  EXPECT_THROW(ricci::write_mesh(mesh, (dir_ / "m.xyz").string()), ricci::IOError);
  EXPECT_THROW(ricci::write_mesh(mesh, (dir_ / "no" / "such" / "dir.obj").string()),
               ricci::IOError);
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(MeshIo, ReadMeshRefusesBadCorpusFilesWithTypedErrors) {
  const std::string bad = std::string(MSP_TEST_DATA) + "/bad/";
  EXPECT_THROW((void)ricci::read_mesh(bad + "truncated_vertices.off"), ricci::IOError);
  EXPECT_THROW((void)ricci::read_mesh(bad + "fin_edge.off"), ricci::TopologyError);
  EXPECT_THROW((void)ricci::read_mesh(bad + "bowtie.off"), ricci::TopologyError);
  EXPECT_THROW((void)ricci::read_mesh(bad + "mobius.obj"), ricci::TopologyError);
  EXPECT_THROW((void)ricci::read_mesh(bad + "two_components.off"), ricci::TopologyError);
  EXPECT_THROW((void)ricci::read_mesh(bad + "zero_area_face.off"), ricci::InvalidInputError);
  EXPECT_THROW((void)ricci::read_mesh(bad + "nan_coordinate.obj"), ricci::InvalidInputError);
}

TEST_F(MeshIo, ArraysRoundTrip) {
  const ricci::Mesh mesh = awkward_torus();
  const auto arrays = ricci::to_arrays(mesh);
  EXPECT_EQ(arrays.V.rows(), 35);
  EXPECT_EQ(arrays.F.rows(), 70);
  const ricci::Mesh back = ricci::from_arrays(arrays.V, arrays.F);
  const auto again = ricci::to_arrays(back);
  EXPECT_EQ(again.V, arrays.V);
  EXPECT_EQ(again.F, arrays.F);
  Eigen::MatrixX3i bad = arrays.F;
  bad(3, 1) = 99;
  EXPECT_THROW((void)ricci::from_arrays(arrays.V, bad), ricci::InvalidInputError);
}

TEST_F(MeshIo, SameOrderMeshInvertsToArrays) {
  const ricci::Mesh mesh = awkward_torus();
  const auto arrays = ricci::to_arrays(mesh);
  const ricci::Mesh back = ricci::same_order_mesh(arrays);
  const auto again = ricci::to_arrays(back);
  EXPECT_EQ(again.V, arrays.V);
  EXPECT_EQ(again.F, arrays.F);
  EXPECT_EQ(back.n_edges(), mesh.n_edges());
  ricci::VertexFaceArrays twice = arrays;  // one face twice: a non-manifold edge
  twice.F.conservativeResize(arrays.F.rows() + 1, 3);
  twice.F.row(arrays.F.rows()) = arrays.F.row(0);
  EXPECT_THROW((void)ricci::same_order_mesh(twice), ricci::TopologyError);
}

}  // namespace
