// Reading files into polygon soups: format dispatch, gzip, shared checks and message helpers.
#include "ricci/mesh/soup_io.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>

#include "ricci/mesh/errors.h"
#include "ricci/mesh/parse_util.h"
#include "ricci/mesh/soup_formats.h"

namespace ricci {
namespace detail {

void fail(const std::string& file, long line, const std::string& problem) {
  if (line > 0) throw IOError(file + ":" + std::to_string(line) + ": " + problem);
  throw IOError(file + ": " + problem);
}

std::string quote_token(std::string_view token) {
  constexpr size_t kMaxShown = 24;
  std::string out = "'";
  for (size_t i = 0; i < token.size() && i < kMaxShown; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (std::isprint(c)) {
      out += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      out += hex;
    }
  }
  if (token.size() > kMaxShown) out += "...";
  return out + "'";
}

namespace {

std::string read_plain(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, std::string("cannot open: ") + std::strerror(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) fail(path, 0, "cannot read (not a regular file?)");
  std::string bytes(static_cast<size_t>(size), '\0');
  in.seekg(0);
  if (size > 0 && !in.read(bytes.data(), size)) fail(path, 0, "read error");
  return bytes;
}

std::string read_gzip(const std::string& path) {
  gzFile file = gzopen(path.c_str(), "rb");
  if (!file) fail(path, 0, std::string("cannot open: ") + std::strerror(errno));
  std::unique_ptr<gzFile_s, int (*)(gzFile)> closer(file, gzclose);
  std::string bytes;
  std::vector<char> chunk(1 << 16);
  for (;;) {
    const int got = gzread(file, chunk.data(), static_cast<unsigned>(chunk.size()));
    if (got < 0) {
      int code = 0;
      const char* message = gzerror(file, &code);
      fail(path, 0, std::string("corrupt gzip data: ") + (message ? message : "unknown error"));
    }
    if (got == 0) break;
    bytes.append(chunk.data(), static_cast<size_t>(got));
  }
  // gzread stops quietly at a truncated stream; gzerror still says so (Z_BUF_ERROR).
  int code = Z_OK;
  gzerror(file, &code);
  if (code != Z_OK && code != Z_STREAM_END) fail(path, 0, "corrupt or truncated gzip data");
  return bytes;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::string read_file_bytes(const std::string& path) {
  return ends_with(lower(path), ".gz") ? read_gzip(path) : read_plain(path);
}

void check_soup_indices(const PolygonSoup& soup, const std::string& name) {
  const long long vertex_count = static_cast<long long>(soup.positions.size());
  for (size_t f = 0; f < soup.faces.size(); ++f) {
    const long line = f < soup.face_lines.size() ? soup.face_lines[f] : 0;
    const std::string where = line > 0 ? "face " + std::to_string(f) : soup.face_where(f);
    const auto& face = soup.faces[f];
    if (face.size() < 3)
      fail(name, line,
           where + " has " + std::to_string(face.size()) + " vertices; a face needs at least 3");
    for (int index : face) {
      if (index < 0 || index >= vertex_count)
        fail(name, line,
             where + " has vertex index " + std::to_string(index) + " but the file has " +
                 std::to_string(vertex_count) + " vertices");
    }
  }
  if (soup.faces.empty()) {
    fail(name, 0,
         soup.positions.empty() ? "no vertices and no faces"
                                : "no faces (" + std::to_string(vertex_count) +
                                      " vertices only: a point cloud is not a mesh)");
  }
}

}  // namespace detail

MeshFormat format_from_extension(const std::string& path) {
  std::string name = detail::lower(path);
  if (detail::ends_with(name, ".gz")) name.resize(name.size() - 3);
  if (detail::ends_with(name, ".off")) return MeshFormat::off;
  if (detail::ends_with(name, ".obj")) return MeshFormat::obj;
  if (detail::ends_with(name, ".ply")) return MeshFormat::ply;
  if (detail::ends_with(name, ".stl")) return MeshFormat::stl;
  const size_t slash = name.find_last_of('/');
  const size_t dot = name.find_last_of('.');
  const bool has_extension =
      dot != std::string::npos && (slash == std::string::npos || dot > slash);
  detail::fail(path, 0,
               has_extension ? "unknown mesh format '" + name.substr(dot) +
                                   "' (expected .off, .obj, .ply or .stl, optionally .gz)"
                             : "no file extension to tell the mesh format (expected .off, .obj, "
                               ".ply or .stl, optionally .gz)");
}

PolygonSoup parse_soup(std::string_view data, MeshFormat format, const std::string& name) {
  if (data.empty()) detail::fail(name, 0, "file is empty");
  PolygonSoup soup;
  switch (format) {
    case MeshFormat::off:
      soup = detail::parse_off(data, name);
      break;
    case MeshFormat::obj:
      soup = detail::parse_obj(data, name);
      break;
    case MeshFormat::ply:
      soup = detail::parse_ply(data, name);
      break;
    case MeshFormat::stl:
      soup = detail::parse_stl(data, name);
      break;
  }
  soup.source = name;
  detail::check_soup_indices(soup, name);
  return soup;
}

PolygonSoup read_soup(const std::string& path) {
  const MeshFormat format = format_from_extension(path);  // before opening: cheaper error first
  const std::string bytes = detail::read_file_bytes(path);
  return parse_soup(bytes, format, path);
}

}  // namespace ricci
