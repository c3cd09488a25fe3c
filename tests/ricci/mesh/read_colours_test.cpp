// read_mesh_with_colours(): vertex colours of COFF (0-255 and 0-1, after a normal in CNOFF) and
// PLY (uchar red/green/blue), carried past an unreferenced vertex; none from a plain OFF.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/io.h"

namespace {

namespace fs = std::filesystem;

class ReadColours : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ricci_read_colours_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  fs::path dir_;
};

// Two triangles over four vertices and an unreferenced one (index 2), which the mesh drops.
const char* kFaces = "3 0 1 3\n3 1 4 3\n";

TEST_F(ReadColours, OffWithColours) {
  const std::string coff =
      file("a.off", std::string("COFF\n5 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n"
                                "9 9 9 1 1 1 255\n0 1 0 0 0 255 255\n"
                                "1 1 0 51 102 153 255\n") +
                        kFaces);
  const ricci::ColouredMesh m = ricci::read_mesh_with_colours(coff);
  ASSERT_EQ(m.mesh.n_vertices(), 4u);
  ASSERT_EQ(m.colours.rows(), 4);
  EXPECT_EQ(m.colours.row(0), Eigen::RowVector3d(1, 0, 0));
  EXPECT_EQ(m.colours.row(2), Eigen::RowVector3d(0, 0, 1));  // soup vertex 3
  EXPECT_NEAR(m.colours(3, 1), 0.4, 1e-15);
  const std::string cnoff = file("b.off", std::string("CNOFF\n5 2 0\n0 0 0 0 0 1 0.5 0.25 0\n"
                                                      "1 0 0 0 0 1 0 1 0\n9 9 9 0 0 1 1 1 1\n"
                                                      "0 1 0 0 0 1 0 0 1\n1 1 0 0 0 1 1 1 1\n") +
                                              kFaces);
  EXPECT_EQ(ricci::read_mesh_with_colours(cnoff).colours.row(0), Eigen::RowVector3d(0.5, 0.25, 0));
  const std::string plain =
      file("c.off", std::string("OFF\n5 2 0\n0 0 0\n1 0 0\n9 9 9\n0 1 0\n1 1 0\n") + kFaces);
  EXPECT_EQ(ricci::read_mesh_with_colours(plain).colours.rows(), 0);
}

// A COFF whose vertex line lacks its colour (or has a word there) still reads as a mesh, with no
// colours: one missing colour makes the file's colours untrustworthy, not the geometry.
TEST_F(ReadColours, CoffWithAMissingColourHasNone) {
  for (const char* third : {"9 9 9\n", "9 9 9 red green blue 255\n"}) {
    const std::string coff = file("d.off", std::string("COFF\n5 2 0\n0 0 0 255 0 0 255\n"
                                                       "1 0 0 0 255 0 255\n") +
                                               third + "0 1 0 0 0 255 255\n1 1 0 1 2 3 255\n" +
                                               kFaces);
    const ricci::ColouredMesh m = ricci::read_mesh_with_colours(coff);
    EXPECT_EQ(m.mesh.n_vertices(), 4u) << third;
    EXPECT_EQ(m.colours.rows(), 0) << third;
  }
}

// Colours that are not numbers of the range are refused with the file and the vertex named.
TEST_F(ReadColours, NonFiniteOrOutOfRangeColoursAreRefused) {
  for (const char* third : {"9 9 9 nan 0 0 255\n", "9 9 9 -1 0 0 255\n", "9 9 9 0 300 0 255\n",
                            "9 9 9 inf 0 0 255\n"}) {
    const std::string coff = file("e.off", std::string("COFF\n5 2 0\n0 0 0 255 0 0 255\n"
                                                       "1 0 0 0 255 0 255\n") +
                                               third + "0 1 0 0 0 255 255\n1 1 0 1 2 3 255\n" +
                                               kFaces);
    try {
      (void)ricci::read_mesh_with_colours(coff);
      ADD_FAILURE() << "accepted " << third;
    } catch (const ricci::IOError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("e.off: vertex 2 (line 5) has the colour"), std::string::npos) << what;
    }
  }
}

TEST_F(ReadColours, PlyWithColours) {
  const std::string ply =
      file("a.ply", std::string("ply\nformat ascii 1.0\nelement vertex 5\n"
                                "property float x\nproperty float y\nproperty float z\n"
                                "property uchar red\nproperty uchar green\n"
                                "property uchar blue\nelement face 2\n"
                                "property list uchar int vertex_indices\nend_header\n"
                                "0 0 0 255 0 0\n1 0 0 0 255 0\n9 9 9 1 1 1\n"
                                "0 1 0 0 0 255\n1 1 0 51 102 153\n") +
                        kFaces);
  const ricci::ColouredMesh m = ricci::read_mesh_with_colours(ply);
  ASSERT_EQ(m.colours.rows(), 4);
  EXPECT_EQ(m.colours.row(1), Eigen::RowVector3d(0, 1, 0));
  EXPECT_NEAR(m.colours(3, 2), 0.6, 1e-15);
}

}  // namespace
