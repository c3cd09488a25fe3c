// The strict readers: every format and variant gives the same soup; malformed files throw an
// IOError naming the file and the line.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <random>

#include "ricci/mesh/diagnose.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/soup_io.h"
#include "test_paths.h"

namespace {

namespace fs = std::filesystem;
using ricci::PolygonSoup;

/// A scratch folder removed at the end of each test.
class SoupIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ricci_soup_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& bytes) {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path.string();
  }
  std::string write_gz(const std::string& name, const std::string& bytes) {
    const fs::path path = dir_ / name;
    gzFile file = gzopen(path.string().c_str(), "wb");
    gzwrite(file, bytes.data(), static_cast<unsigned>(bytes.size()));
    gzclose(file);
    return path.string();
  }
  fs::path dir_;
};

// The unit square split into two triangles (0 1 2) and (0 2 3), the shape every format encodes.
const std::vector<Eigen::Vector3d> kSquare = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, -2.25}};
const std::vector<std::vector<int>> kSquareFaces = {{0, 1, 2}, {0, 2, 3}};

void expect_square(const PolygonSoup& soup) {
  ASSERT_EQ(soup.positions.size(), 4u);
  for (size_t v = 0; v < 4; ++v) EXPECT_EQ(soup.positions[v], kSquare[v]) << "vertex " << v;
  EXPECT_EQ(soup.faces, kSquareFaces);
}

std::string expect_io_error(const std::string& path) {
  try {
    (void)ricci::read_soup(path);
  } catch (const ricci::IOError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind(path, 0), 0u) << message;  // starts with the file name
    return message;
  }
  ADD_FAILURE() << "no IOError for " << path;
  return "";
}

TEST_F(SoupIo, OffWithCommentsColoursAndHeaderVariants) {
  expect_square(ricci::read_soup(write(
      "a.off",
      "OFF\n# comment\n4 2 0\n0 0 0\n1 0 0\n1 1 0.5 # trailing\n0 1 -2.25\n3 0 1 2\n3 0 2 3\n")));
  expect_square(ricci::read_soup(write(
      "b.off",
      "COFF 4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 .5 0 0 0 0\n0 1 -2.25e0 1 1 1 1\n"
      "3 0 1 2 0.5 0.5 0.5\n3 0 2 3 0.5 0.5 0.5\n")));
  expect_square(ricci::read_soup(
      write("c.off",
            "NOFF\r\n4 2 5\r\n0 0 0 0 0 1\r\n1 0 0 0 0 1\r\n1 1 0.5 0 0 1\r\n+0 1 -2.25 0 0 1\r\n"
            "3 0 1 2\r\n3 0 2 3")));
}

TEST_F(SoupIo, OffFaceLinesAreRecorded) {
  const auto soup = ricci::read_soup(write(
      "lines.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0.5\n0 1 -2.25\n\n# gap\n3 0 1 2\n3 0 2 3\n"));
  EXPECT_EQ(soup.face_lines, (std::vector<int>{9, 10}));
  EXPECT_EQ(soup.vertex_lines, (std::vector<int>{3, 4, 5, 6}));
  EXPECT_EQ(soup.vertex_where(2), "vertex 2 (line 5)");
  EXPECT_EQ(soup.face_where(1), "face 1 (line 10)");
}

TEST_F(SoupIo, ObjIndexFormsAndNegativeIndices) {
  expect_square(ricci::read_soup(
      write("a.obj",
            "# square\nmtllib x.mtl\no square\nv 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 -2.25 1.0\n"
            "vt 0 0\nvn 0 0 1\ng group\ns off\nusemtl m\nf 1/1/1 2/1/1 3/1/1\nf 1//1 -2//1 -1\n")));
  expect_square(ricci::read_soup(write(
      "b.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nf -3 -2 -1\nv 0 1 -2.25\nf 1/2 3/2 4/2 # comment\n")));
}

TEST_F(SoupIo, ObjPolygonsKeepTheirCorners) {
  const auto soup =
      ricci::read_soup(write("q.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
  ASSERT_EQ(soup.faces.size(), 1u);
  EXPECT_EQ(soup.faces[0], (std::vector<int>{0, 1, 2, 3}));
}

std::string ply_header(const std::string& format, const std::string& vertex_type,
                       const std::string& index_type) {
  return "ply\nformat " + format +
         " 1.0\ncomment made by a test\nelement vertex 4\n"
         "property " +
         vertex_type + " x\nproperty uchar red\nproperty " + vertex_type +
         " y\n"
         "property " +
         vertex_type +
         " z\nproperty list uchar int extra\n"
         "element face 2\nproperty list uchar " +
         index_type +
         " vertex_indices\nproperty float quality\n"
         "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
}

template <typename T>
void put(std::string& out, T value, bool big_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian) std::reverse(bytes, bytes + sizeof(T));  // the test machine is little-endian
  out.append(bytes, sizeof(T));
}

template <typename Real, typename Index>
std::string binary_ply(const std::string& vertex_type, const std::string& index_type, bool big) {
  std::string out =
      ply_header(big ? "binary_big_endian" : "binary_little_endian", vertex_type, index_type);
  for (const auto& p : kSquare) {
    put<Real>(out, static_cast<Real>(p.x()), big);
    put<uint8_t>(out, 200, big);
    put<Real>(out, static_cast<Real>(p.y()), big);
    put<Real>(out, static_cast<Real>(p.z()), big);
    put<uint8_t>(out, 2, big);
    put<int32_t>(out, 7, big);
    put<int32_t>(out, -7, big);
  }
  for (const auto& face : kSquareFaces) {
    put<uint8_t>(out, 3, big);
    for (int v : face) put<Index>(out, static_cast<Index>(v), big);
    put<float>(out, 0.25f, big);
  }
  put<int32_t>(out, 0, big);
  put<int32_t>(out, 1, big);
  return out;
}

TEST_F(SoupIo, PlyAsciiAndBinaryOfEveryEndiannessAndType) {
  expect_square(ricci::read_soup(write("a.ply", ply_header("ascii", "float", "int") +
                                                    "0 7 0 0 0\n1 200 0 0 1 5\n1 1 1 0.5 0\n0 1 1 "
                                                    "-2.25 2 1 2\n3 0 1 2 0.5\n3 0 2 3 1\n0 1\n")));
  expect_square(
      ricci::read_soup(write("le.ply", binary_ply<float, int32_t>("float", "int", false))));
  expect_square(
      ricci::read_soup(write("be.ply", binary_ply<float, int32_t>("float", "int", true))));
  expect_square(
      ricci::read_soup(write("d.ply", binary_ply<double, uint32_t>("double", "uint", true))));
  expect_square(
      ricci::read_soup(write("s.ply", binary_ply<double, uint16_t>("float64", "ushort", false))));
}

TEST_F(SoupIo, PlyTristripsBecomeTriangles) {
  const auto soup = ricci::read_soup(
      write("strip.ply",
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty "
            "float z\n"
            "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n1 1 0.5\n0 1 -2.25\n5 1 2 0 3 -1\n"));
  ASSERT_EQ(soup.faces.size(), 2u);
  EXPECT_EQ(soup.faces[0], (std::vector<int>{1, 2, 0}));
  EXPECT_EQ(soup.faces[1], (std::vector<int>{0, 2, 3}));  // odd triangles flipped to keep winding
}

std::string binary_stl(bool solid_prefix) {
  std::string out(80, ' ');
  if (solid_prefix) out.replace(0, 9, "solid bin");  // some exporters do this; size decides
  put<uint32_t>(out, 2, false);
  for (const auto& face : kSquareFaces) {
    for (int k = 0; k < 3; ++k) put<float>(out, 0.0f, false);
    for (int v : face)
      for (int k = 0; k < 3; ++k) put<float>(out, static_cast<float>(kSquare[v][k]), false);
    put<uint16_t>(out, 0, false);
  }
  return out;
}

TEST_F(SoupIo, StlAsciiAndBinaryWeldCornersByPosition) {
  std::string ascii = "solid square\n";
  for (const auto& face : kSquareFaces) {
    ascii += "  facet normal 0 0 1\n    outer loop\n";
    for (int v : face)
      ascii += "      vertex " + std::to_string(kSquare[v].x()) + " " +
               std::to_string(kSquare[v].y()) + " " + std::to_string(kSquare[v].z()) + "\n";
    ascii += "    endloop\n  endfacet\n";
  }
  ascii += "endsolid square\n";
  expect_square(ricci::read_soup(write("a.stl", ascii)));
  expect_square(ricci::read_soup(write("b.stl", binary_stl(false))));
  expect_square(ricci::read_soup(write("c.stl", binary_stl(true))));
}

TEST_F(SoupIo, GzipOfAnyFormatAndCaseInsensitiveExtensions) {
  expect_square(ricci::read_soup(
      write_gz("a.off.gz", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0.5\n0 1 -2.25\n3 0 1 2\n3 0 2 3\n")));
  expect_square(
      ricci::read_soup(write_gz("b.PLY.GZ", binary_ply<float, int32_t>("float", "int", true))));
  expect_square(ricci::read_soup(write_gz("c.stl.gz", binary_stl(false))));
  expect_square(ricci::read_soup(
      write("D.OBJ", "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 -2.25\nf 1 2 3\nf 1 3 4\n")));
}

TEST_F(SoupIo, DragonIsGzippedBinaryPly) {
  const auto soup =
      ricci::read_soup(msp_test::test_mesh("nonmanifold/dragon_vrip_res4.ply.gz"));
  EXPECT_EQ(soup.positions.size(), 5205u);
  EXPECT_EQ(soup.faces.size(), 11102u);
}

TEST_F(SoupIo, ErrorsNameTheFileAndLine) {
  EXPECT_NE(expect_io_error(write("e.off", "")).find("file is empty"), std::string::npos);
  EXPECT_NE(expect_io_error(write("t.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n"))
                .find(":4: file ends after 2 of 4 vertices"),
            std::string::npos);
  EXPECT_NE(expect_io_error(write("r.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"))
                .find(":6: face 0 has vertex index 3 but the file has 3 vertices"),
            std::string::npos);
  EXPECT_NE(expect_io_error(write("n.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"))
                .find(":4: vertex 1: expected a number, found 'x'"),
            std::string::npos);
  EXPECT_NE(expect_io_error(write("s.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n"))
                .find(":6: face 0 lists 3 of 4 vertex indices"),
            std::string::npos);
  EXPECT_NE(expect_io_error(write("o.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n"))
                .find(":3: face 0 has vertex index 2 but"),
            std::string::npos);
  EXPECT_NE(
      expect_io_error(write("m.obj", "v 0 0 0\nf -2 1 1\n")).find(":2: face 0 has vertex index -2"),
      std::string::npos);
  EXPECT_NE(expect_io_error(write("x.mesh", "OFF")).find("unknown mesh format '.mesh'"),
            std::string::npos);
  EXPECT_NE(expect_io_error(write("noext", "OFF")).find("no file extension"), std::string::npos);
  EXPECT_NE(expect_io_error((dir_ / "missing.off").string()).find("cannot open"),
            std::string::npos);
  std::string cut = binary_ply<float, int32_t>("float", "int", false);
  cut.resize(cut.size() - 12);
  EXPECT_NE(expect_io_error(write("cut.ply", cut))
                .find("file ends inside element 'face' (record 1 of 2)"),
            std::string::npos);
  std::string stl = binary_stl(false);
  stl.pop_back();
  EXPECT_NE(expect_io_error(write("cut.stl", stl)).find("binary STL says 2 triangles"),
            std::string::npos);
  EXPECT_NE(
      expect_io_error(write("big.ply",
                            "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\n"
                            "property float y\nproperty float z\nend_header\n0 0 0\n"))
          .find(":3: element 'vertex' claims 1000000000 records"),
      std::string::npos);
  std::string gz_bytes;
  {
    const std::string gz = write_gz("whole.off.gz", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    std::ifstream in(gz, std::ios::binary);
    gz_bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  gz_bytes.resize(gz_bytes.size() / 2);
  EXPECT_NE(expect_io_error(write("half.off.gz", gz_bytes)).find("gzip"), std::string::npos);
}

TEST_F(SoupIo, NonFiniteCoordinatesAreReadForDiagnosis) {
  const auto soup =
      ricci::read_soup(write("nan.obj", "v nan 0 0\nv 1 inf 0\nv 0 1 -inf\nf 1 2 3\n"));
  EXPECT_TRUE(std::isnan(soup.positions[0].x()));
  EXPECT_TRUE(std::isinf(soup.positions[1].y()));
  EXPECT_LT(soup.positions[2].z(), 0);
}

/// Parses `data`; only success or an IOError is acceptable (no crash, hang or other exception),
/// and whatever parses must be diagnosable.
void expect_parsed_or_io_error(std::string_view data, ricci::MeshFormat format) {
  try {
    const auto soup = ricci::parse_soup(data, format, "fuzz");
    (void)ricci::diagnose(soup);
  } catch (const ricci::IOError&) {
  } catch (const std::exception& e) {
    ADD_FAILURE() << "unexpected " << e.what();
  }
}

TEST_F(SoupIo, TruncatedAndCorruptedFilesOnlyEverThrowIOError) {
  const std::pair<std::string, ricci::MeshFormat> samples[] = {
      {"OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0.5\n0 1 -2.25\n3 0 1 2\n3 0 2 3\n", ricci::MeshFormat::off},
      {"v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 -2.25\nf 1/1 2/2 3/3\nf -4 -2 -1\n",
       ricci::MeshFormat::obj},
      {ply_header("ascii", "float", "int") +
           "0 7 0 0 0\n1 200 0 0 1 5\n1 1 1 0.5 0\n0 1 1 -2.25 2 1 2\n"
           "3 0 1 2 0.5\n3 0 2 3 1\n0 1\n",
       ricci::MeshFormat::ply},
      {binary_ply<float, int32_t>("float", "int", false), ricci::MeshFormat::ply},
      {binary_ply<double, uint16_t>("double", "ushort", true), ricci::MeshFormat::ply},
      {binary_stl(false), ricci::MeshFormat::stl},
      {"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 "
       "0\nendloop\n"
       "endfacet\nendsolid s\n",
       ricci::MeshFormat::stl}};
  std::mt19937 random(12345);
  for (const auto& [data, format] : samples) {
    for (size_t length = 0; length <= data.size(); ++length)
      expect_parsed_or_io_error(std::string_view(data).substr(0, length), format);
    for (int trial = 0; trial < 300; ++trial) {
      std::string corrupt = data;
      for (int k = 0; k < 3; ++k)
        corrupt[random() % corrupt.size()] = static_cast<char>(random() % 256);
      expect_parsed_or_io_error(corrupt, format);
    }
  }
}

TEST_F(SoupIo, HugeCountsInTinyFilesAreRefusedQuickly) {
  EXPECT_NE(expect_io_error(write("h.off", "OFF\n2000000000 2000000000 0\n")).find("cannot fit"),
            std::string::npos);
  const std::string empty_elements =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement nothing 4000000000\nelement face 1\nproperty list uchar int "
      "vertex_indices\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(ricci::read_soup(write("e.ply", empty_elements)).faces.size(), 1u);
}

}  // namespace
