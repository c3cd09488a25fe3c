// read_mesh() on the strict soup readers; write_mesh() with exact round-trip coordinates.
#include "ricci/mesh/io.h"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <random>
#include <sstream>

#include "ricci/mesh/build_mesh.h"
#include "ricci/mesh/errors.h"
#include "ricci/mesh/soup_io.h"

namespace ricci {
namespace {

/// Appends the shortest representation that parses back to exactly `value`.
void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void append_vertex(std::string& out, const char* prefix, const Mesh::Point& p) {
  out += prefix;
  for (int k = 0; k < 3; ++k) {
    if (k) out += ' ';
    append_number(out, p[k]);
  }
  out += '\n';
}

std::string format_mesh(const Mesh& mesh, MeshFormat format) {
  std::string out;
  out.reserve(mesh.n_vertices() * 60 + mesh.n_faces() * 24 + 256);
  const std::string counts =
      std::to_string(mesh.n_vertices()) + " " + std::to_string(mesh.n_faces());
  if (format == MeshFormat::off) out += "OFF\n" + counts + " 0\n";
  if (format == MeshFormat::ply)
    out += "ply\nformat ascii 1.0\ncomment written by libricci\nelement vertex " +
           std::to_string(mesh.n_vertices()) +
           "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
           std::to_string(mesh.n_faces()) +
           "\nproperty list uchar int vertex_indices\nend_header\n";
  if (format == MeshFormat::obj) out += "# written by libricci: " + counts + " (vertices faces)\n";
  for (const auto v : mesh.vertices())
    append_vertex(out, format == MeshFormat::obj ? "v " : "", mesh.point(v));
  const int base = format == MeshFormat::obj ? 1 : 0;
  for (const auto f : mesh.faces()) {
    out += format == MeshFormat::obj ? "f" : std::to_string(mesh.valence(f));
    for (const auto v : mesh.fv_range(f)) {
      out += ' ';
      out += std::to_string(v.idx() + base);
    }
    out += '\n';
  }
  return out;
}

}  // namespace

Mesh read_mesh(const std::string& path) { return build_mesh(read_soup(path)); }

ColouredMesh read_mesh_with_colours(const std::string& path) {
  const PolygonSoup soup = read_soup(path);
  for (std::size_t v = 0; v < soup.colours.size(); ++v) {
    const Eigen::Vector3d& c = soup.colours[v];
    if (c.allFinite() && c.minCoeff() >= 0.0 && c.maxCoeff() <= 1.0) continue;
    std::ostringstream what;
    what << path << ": " << soup.vertex_where(v) << " has the colour (" << c.x() << ", " << c.y()
         << ", " << c.z() << "), outside 0-1 (0-255 for integers)";
    throw IOError(what.str());
  }
  MeshBuildResult built = build_mesh_with_report(soup);
  ColouredMesh out;
  out.mesh = std::move(built.mesh);
  if (soup.colours.size() == soup.positions.size() && !soup.colours.empty()) {
    out.colours.resize(static_cast<Eigen::Index>(built.input_vertex.size()), 3);
    for (size_t v = 0; v < built.input_vertex.size(); ++v) {
      out.colours.row(static_cast<Eigen::Index>(v)) =
          soup.colours[static_cast<size_t>(built.input_vertex[v])].transpose();
    }
  }
  return out;
}

void write_mesh(const Mesh& mesh, const std::string& path) {
  const MeshFormat format = format_from_extension(path);
  if (format == MeshFormat::stl)
    throw IOError(path + ": writing STL is not supported (use .obj, .off or .ply)");
  if (path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0)
    throw IOError(path + ": writing .gz is not supported");
  write_file_atomically(path, format_mesh(mesh, format));
}

void write_file_atomically(const std::string& path, std::string_view bytes) {
  std::random_device entropy;
  const std::string temp = path + ".tmp" + std::to_string(entropy());
  std::FILE* file = std::fopen(temp.c_str(), "wb");
  if (!file) throw IOError(path + ": cannot create " + temp);
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
  const bool closed = std::fclose(file) == 0;
  std::error_code error;
  if (written && closed) std::filesystem::rename(temp, path, error);
  if (!written || !closed || error) {
    std::filesystem::remove(temp, error);
    throw IOError(path + ": write failed (disk full or no permission?)");
  }
}

}  // namespace ricci
