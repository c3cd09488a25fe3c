// The spline file: preamble, JSON header, and the sections in order (docs/spline-file.md).
#include "spline/io/spline_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "ricci/mesh/diagnose.h"
#include "ricci/mesh/io.h"
#include "ricci/mesh/parse_util.h"
#include "spline/io/spline_file_detail.h"

namespace spline {
namespace {

using io_detail::ByteReader;
using io_detail::ByteWriter;
using io_detail::FaceCorners;

// PNG-style: a non-ASCII first byte, then CR LF, ^Z and LF, which text-mode transfers mangle.
constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'S', 'P', '\r', '\n', 0x1a, '\n'};
constexpr std::size_t kPreamble = 16;  // magic, version (u32), header length (u32)
constexpr std::uint32_t kMaxHeader = 1u << 20;

std::string str(std::size_t value) { return std::to_string(value); }

nlohmann::ordered_json header_json(const SplineSurface& surface,
                                   const SplineFileProvenance& provenance) {
  const ManifoldSplineSpace& space = *surface.spline.space;
  const ricci::AffineAtlas& atlas = space.atlas();
  nlohmann::ordered_json json;
  json["format"] = "msp spline";
  json["version"] = kSplineFileVersion;
  json["degree"] = space.degree();
  json["vertices"] = surface.domain.n_vertices();
  json["faces"] = surface.domain.n_faces();
  json["charts"] = atlas.charts.size();
  json["transitions"] = atlas.transitions.size();
  json["control_points"] = surface.spline.control_points.rows();
  json["fills"] = surface.fills.size();
  json["open_rims"] = surface.open_rims.size();
  json["singular_vertex"] = surface.singular_vertex;
  json["provenance"] = nlohmann::ordered_json::object();
  for (const auto& [key, value] : provenance) json["provenance"][key] = value;
  return json;
}

void write_mesh(ByteWriter& out, const ricci::Mesh& mesh) {
  out.count(mesh.n_vertices());
  for (auto v : mesh.vertices()) out.vec3(ricci::to_eigen(mesh.point(v)));
  const FaceCorners corners = io_detail::face_corners(mesh);
  out.count(corners.size());
  for (const auto& face : corners) {
    for (int v : face) out.i32(v);
  }
}

// The domain mesh, with each face's corners in the stored order. Refuses non-finite positions,
// indices out of range and a soup that is no consistently oriented 2-manifold (diagnose()).
ricci::Mesh read_mesh(ByteReader& in) {
  ricci::PolygonSoup soup;
  soup.positions.resize(in.count(24, "vertices"));
  for (std::size_t v = 0; v < soup.positions.size(); ++v) {
    soup.positions[v] = in.vec3();
    if (!soup.positions[v].allFinite()) in.invalid("vertex " + str(v) + " is not finite");
  }
  soup.faces.resize(in.count(12, "faces"));
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    soup.faces[f] = {in.i32(), in.i32(), in.i32()};
    for (int v : soup.faces[f]) {
      if (v < 0 || static_cast<std::size_t>(v) >= soup.positions.size()) {
        in.invalid("face " + str(f) + " has vertex index " + std::to_string(v) + " outside [0, " +
                   str(soup.positions.size()) + ")");
      }
    }
  }
  const ricci::MeshDiagnosis diagnosis = ricci::diagnose(soup);
  for (const ricci::MeshProblem& problem : diagnosis.problems) {
    // Tiny faces do not break the data structures; the charts' checks cover the geometry.
    if (problem.kind == ricci::MeshProblemKind::kZeroArea) continue;
    throw ricci::TopologyError(in.source() + ": domain mesh: " + problem.message);
  }
  if (!diagnosis.consistently_oriented) {
    throw ricci::TopologyError(in.source() + ": domain mesh: faces not consistently oriented");
  }
  ricci::Mesh mesh;
  for (const Eigen::Vector3d& p : soup.positions) mesh.add_vertex(ricci::to_openmesh(p));
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const auto& c = soup.faces[f];
    // OpenMesh makes face_halfedges' corners (c0, c1, c2) of add_face(c0, c1, c2) (checked
    // below).
    const auto face = mesh.add_face(ricci::VertexHandle(c[0]), ricci::VertexHandle(c[1]),
                                    ricci::VertexHandle(c[2]));
    if (!face.is_valid()) in.invalid("face " + str(f) + " cannot be added to the mesh");
  }
  const FaceCorners corners = io_detail::face_corners(mesh);
  for (std::size_t f = 0; f < corners.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (corners[f][k] != soup.faces[f][k]) in.invalid("face " + str(f) + " changed its corners");
    }
  }
  return mesh;
}

// The space from the stored atlas and clouds; its own checks (stars glued in their charts,
// clouds starting at their vertices within the DMS bound) are reported as the file's.
std::shared_ptr<const ManifoldSplineSpace> make_space(const ByteReader& in, const ricci::Mesh& mesh,
                                                      const ricci::AffineAtlas& atlas, int degree,
                                                      std::vector<KnotCloud> clouds) {
  try {
    return std::make_shared<const ManifoldSplineSpace>(mesh, atlas, degree, std::move(clouds));
  } catch (const ricci::TopologyError& e) {
    throw ricci::TopologyError(in.source() + ": " + e.what());
  } catch (const ricci::InvalidInputError& e) {
    in.invalid(e.what());
  }
}

int header_int(const ByteReader& in, const nlohmann::json& json, const char* key) {
  const auto it = json.find(key);
  if (it == json.end() || !it->is_number_integer()) {
    in.fail(std::string("header has no integer \"") + key + "\"");
  }
  const auto value = it->get<long long>();
  if (value < -1 || value > std::numeric_limits<int>::max()) {
    in.fail(std::string("header \"") + key + "\" is out of range");
  }
  return static_cast<int>(value);
}

SplineFileHeader read_header(ByteReader& in, std::uint32_t length) {
  std::string text(length, '\0');
  for (char& c : text) c = static_cast<char>(in.u8());
  const nlohmann::json json = nlohmann::json::parse(text, nullptr, false);
  if (json.is_discarded() || !json.is_object()) in.fail("the header is not a JSON object");
  if (json.value("format", std::string()) != "msp spline") {
    in.fail("the header's format is not \"msp spline\"");
  }
  SplineFileHeader header;
  header.version = static_cast<std::uint32_t>(header_int(in, json, "version"));
  header.degree = header_int(in, json, "degree");
  header.vertices = header_int(in, json, "vertices");
  header.faces = header_int(in, json, "faces");
  header.charts = header_int(in, json, "charts");
  header.transitions = header_int(in, json, "transitions");
  header.control_points = header_int(in, json, "control_points");
  header.fills = header_int(in, json, "fills");
  header.open_rims = header_int(in, json, "open_rims");
  header.singular_vertex = header_int(in, json, "singular_vertex");
  const auto provenance = json.find("provenance");
  if (provenance != json.end() && provenance->is_object()) {
    for (const auto& [key, value] : provenance->items()) {
      if (value.is_string()) header.provenance[key] = value.get<std::string>();
    }
  }
  return header;
}

// The header's counts must be the sections' (a file edited by hand or cut and pasted).
void check_counts(const ByteReader& in, const SplineFileHeader& header,
                  const SplineSurface& surface) {
  const ManifoldSplineSpace& space = *surface.spline.space;
  const std::pair<const char*, std::pair<long long, long long>> counts[] = {
      {"degree", {header.degree, space.degree()}},
      {"vertices", {header.vertices, surface.domain.n_vertices()}},
      {"faces", {header.faces, surface.domain.n_faces()}},
      {"charts", {header.charts, space.atlas().charts.size()}},
      {"transitions", {header.transitions, space.atlas().transitions.size()}},
      {"control_points", {header.control_points, surface.spline.control_points.rows()}},
      {"fills", {header.fills, surface.fills.size()}},
      {"open_rims", {header.open_rims, surface.open_rims.size()}},
      {"singular_vertex", {header.singular_vertex, surface.singular_vertex}},
  };
  for (const auto& [key, values] : counts) {
    if (values.first != values.second) {
      in.fail(std::string("inconsistent counts: the header says ") + key + " " +
              std::to_string(values.first) + ", the sections hold " +
              std::to_string(values.second));
    }
  }
}

void read_surface_section(ByteReader& in, SplineSurface& surface) {
  surface.singular_vertex = in.i32();
  const int vertices = static_cast<int>(surface.domain.n_vertices());
  if (surface.singular_vertex < -1 || surface.singular_vertex >= vertices) {
    in.invalid("singular vertex " + std::to_string(surface.singular_vertex) + " is outside [-1, " +
               std::to_string(vertices) + ")");
  }
  surface.skipped_faces.resize(in.count(1, "skipped-face flags"));
  if (!surface.skipped_faces.empty() && surface.skipped_faces.size() != surface.domain.n_faces()) {
    in.fail("inconsistent counts: " + str(surface.skipped_faces.size()) +
            " skipped-face flags for " + str(surface.domain.n_faces()) + " faces");
  }
  for (char& c : surface.skipped_faces) {
    const std::uint8_t flag = in.u8();
    if (flag > 1) in.invalid("a skipped-face flag is " + std::to_string(flag));
    c = static_cast<char>(flag);
  }
}

}  // namespace

std::vector<std::uint8_t> encode_spline_surface(const SplineSurface& surface,
                                                const SplineFileProvenance& provenance) {
  if (!surface.spline.space) throw ricci::InvalidInputError("spline file: the spline has no space");
  const ManifoldSplineSpace& space = *surface.spline.space;
  if (surface.spline.control_points.rows() != space.function_count()) {
    throw ricci::InvalidInputError(
        "spline file: " + std::to_string(surface.spline.control_points.rows()) +
        " control points for " + std::to_string(space.function_count()) + " functions");
  }
  const ricci::Mesh& domain = surface.domain;
  const auto live_faces = std::distance(domain.faces_sbegin(), domain.faces_end());
  const auto live_vertices = std::distance(domain.vertices_sbegin(), domain.vertices_end());
  if (live_faces != static_cast<long>(domain.n_faces()) ||
      live_vertices != static_cast<long>(domain.n_vertices()) ||
      static_cast<int>(domain.n_faces()) != space.face_count()) {
    throw ricci::InvalidInputError(
        "spline file: the domain mesh is not the space's (deleted elements or another face count)");
  }
  ByteWriter out;
  out.raw(kMagic, sizeof kMagic);
  out.u32(kSplineFileVersion);
  const std::string header = header_json(surface, provenance).dump();
  out.u32(static_cast<std::uint32_t>(header.size()));
  out.raw(header.data(), header.size());

  out.begin_section("MESH");
  write_mesh(out, surface.domain);
  out.end_section();
  out.begin_section("ATLS");
  io_detail::write_atlas(out, space.atlas());
  out.end_section();
  out.begin_section("SPLN");
  out.i32(space.degree());
  std::vector<KnotCloud> clouds(surface.domain.n_vertices());
  for (std::size_t v = 0; v < clouds.size(); ++v) clouds[v] = space.home_cloud(static_cast<int>(v));
  io_detail::write_clouds(out, clouds);
  io_detail::write_points(out, surface.spline.control_points);
  out.end_section();
  out.begin_section("SURF");
  out.i32(surface.singular_vertex);
  out.count(surface.skipped_faces.size());
  for (char c : surface.skipped_faces) out.u8(c ? 1 : 0);
  out.end_section();
  out.begin_section("FILL");
  out.count(surface.fills.size());
  for (const HoleFill& fill : surface.fills) io_detail::write_fill(out, fill);
  out.end_section();
  out.begin_section("RIMS");
  out.count(surface.open_rims.size());
  for (const Rim& rim : surface.open_rims) io_detail::write_rim(out, rim);
  out.end_section();
  out.begin_section("END ");
  out.end_section();
  return std::move(out.bytes());
}

SplineFile decode_spline_file(const std::vector<std::uint8_t>& bytes, const std::string& source) {
  ByteReader file(bytes.data(), bytes.size(), source, "file");
  if (bytes.empty()) file.fail("the file is empty");
  if (std::memcmp(bytes.data(), kMagic, std::min(bytes.size(), sizeof kMagic)) != 0) {
    file.fail("not an msp spline file (bad magic bytes)");
  }
  if (bytes.size() < kPreamble) file.fail("file ends inside the preamble (truncated)");
  for (std::size_t i = 0; i < sizeof kMagic; ++i) (void)file.u8();
  const std::uint32_t version = file.u32();
  if (version != kSplineFileVersion) {
    file.fail("format version " + std::to_string(version) + " is not supported (this msp reads " +
              std::to_string(kSplineFileVersion) + ")");
  }
  const std::uint32_t header_length = file.u32();
  if (header_length > kMaxHeader || header_length > file.remaining()) {
    file.fail("file ends inside the header (" + std::to_string(header_length) +
              " bytes announced; truncated)");
  }
  SplineFile result;
  result.header = read_header(file, header_length);
  if (result.header.version != version) {
    file.fail("the header's version " + std::to_string(result.header.version) +
              " is not the preamble's " + std::to_string(version));
  }
  SplineSurface& surface = result.surface;
  ByteReader mesh = file.section("MESH");
  surface.domain = read_mesh(mesh);
  mesh.expect_end();
  const FaceCorners corners = io_detail::face_corners(surface.domain);
  ByteReader atlas_in = file.section("ATLS");
  const ricci::AffineAtlas atlas =
      io_detail::read_atlas(atlas_in, corners, static_cast<int>(surface.domain.n_vertices()));
  atlas_in.expect_end();
  ByteReader spline_in = file.section("SPLN");
  const int degree = spline_in.i32();
  if (degree < 1 || degree > kMaxDmsDegree) {
    spline_in.invalid("degree " + std::to_string(degree) + " is outside 1.." +
                      std::to_string(kMaxDmsDegree));
  }
  surface.spline.space =
      make_space(spline_in, surface.domain, atlas, degree, io_detail::read_clouds(spline_in));
  surface.spline.control_points =
      io_detail::read_points(spline_in, surface.spline.space->function_count(), "control point");
  spline_in.expect_end();
  ByteReader surface_in = file.section("SURF");
  read_surface_section(surface_in, surface);
  surface_in.expect_end();
  const ManifoldSplineSpace& space = *surface.spline.space;
  ByteReader fills = file.section("FILL");
  surface.fills.resize(fills.count(64, "fills"));
  for (std::size_t i = 0; i < surface.fills.size(); ++i) {
    surface.fills[i] = io_detail::read_fill(fills, corners, space, "fill " + str(i));
  }
  fills.expect_end();
  ByteReader rims = file.section("RIMS");
  surface.open_rims.resize(rims.count(17, "open rims"));
  for (std::size_t i = 0; i < surface.open_rims.size(); ++i) {
    surface.open_rims[i] = io_detail::read_rim(rims, corners, space, "open rim " + str(i));
  }
  rims.expect_end();
  file.section("END ").expect_end();
  if (file.remaining() != 0) {
    file.fail(str(file.remaining()) + " bytes follow the END section");
  }
  check_counts(file, result.header, surface);
  return result;
}

void save_spline_surface(const SplineSurface& surface, const std::string& path,
                         const SplineFileProvenance& provenance) {
  const std::vector<std::uint8_t> bytes = encode_spline_surface(surface, provenance);
  ricci::write_file_atomically(
      path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

SplineFile read_spline_file(const std::string& path) {
  const std::string text = ricci::detail::read_file_bytes(path);
  const std::vector<std::uint8_t> bytes(text.begin(), text.end());
  return decode_spline_file(bytes, path);
}

SplineSurface load_spline_surface(const std::string& path) {
  return std::move(read_spline_file(path).surface);
}

}  // namespace spline
