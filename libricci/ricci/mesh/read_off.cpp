// OFF reader: "OFF", "COFF", "NOFF", "CNOFF", "STOFF" headers, counts on the header line or the
// next one, '#' comments, and extra per-line data (colours, normals) after what we need.
#include <algorithm>

#include "ricci/mesh/parse_util.h"
#include "ricci/mesh/soup_formats.h"

namespace ricci::detail {
namespace {

/// Next line holding something other than whitespace and comments; false at the end.
bool next_content_line(LineCursor& cursor, std::string_view& content) {
  std::string_view line;
  while (cursor.next(line)) {
    content = strip_comment(line);
    std::string_view probe = content, token;
    if (next_token(probe, token)) return true;
  }
  return false;
}

long long read_count(std::string_view& text, const char* what, const std::string& name, long line) {
  std::string_view token;
  long long count = 0;
  if (!next_token(text, token)) fail(name, line, std::string("missing ") + what + " count");
  if (!parse_int(token, count) || count < 0)
    fail(name, line, std::string("bad ") + what + " count " + quote_token(token));
  return count;
}

/// The header keyword is [ST][C][N][4][n]OFF; the variants we read only add per-line data.
void check_header(std::string_view keyword, const std::string& name) {
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF")
    fail(name, 1, "not an OFF file: the first word is " + quote_token(keyword) + ", not OFF");
  const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  if (prefix.find('4') != std::string_view::npos || prefix.find('n') != std::string_view::npos)
    fail(name, 1, "unsupported OFF variant " + quote_token(keyword) + " (only 3-D is read)");
}

/// The vertex lines; with `colours`, the r g b after the coordinates (and the normal, with
/// `normals`) are kept, scaled to [0, 1] when any exceeds 1 (0-255 integers).
void read_vertices(LineCursor& cursor, long long count, const std::string& name, bool normals,
                   bool colours, PolygonSoup& soup) {
  std::string_view text, token;
  soup.positions.resize(static_cast<size_t>(count));
  soup.vertex_lines.resize(static_cast<size_t>(count));
  for (long long v = 0; v < count; ++v) {
    if (!next_content_line(cursor, text))
      fail(name, cursor.line_number(),
           "file ends after " + std::to_string(v) + " of " + std::to_string(count) + " vertices");
    soup.vertex_lines[static_cast<size_t>(v)] = static_cast<int>(cursor.line_number());
    auto& p = soup.positions[static_cast<size_t>(v)];
    for (int k = 0; k < 3; ++k) {
      if (!next_token(text, token))
        fail(name, cursor.line_number(),
             "vertex " + std::to_string(v) + " has " + std::to_string(k) +
                 " coordinates; 3 are needed");
      if (!parse_double(token, p[k]))
        fail(name, cursor.line_number(),
             "vertex " + std::to_string(v) + ": expected a number, found " + quote_token(token));
    }
    if (!colours) continue;
    for (int k = 0; k < 3 && normals; ++k) next_token(text, token);
    Eigen::Vector3d c;
    bool has_colour = true;
    for (int k = 0; k < 3 && has_colour; ++k) {
      has_colour = next_token(text, token) && parse_double(token, c[k]);
    }
    if (has_colour) {
      soup.colours.push_back(c);
    } else {
      colours = false;  // a vertex without a colour: the file has none to trust
      soup.colours.clear();
    }
  }
  double largest = 0;
  for (const Eigen::Vector3d& c : soup.colours) largest = std::max(largest, c.maxCoeff());
  if (largest > 1) {
    for (Eigen::Vector3d& c : soup.colours) c /= 255.0;
  }
}

/// One face line "n i1 ... in [colour]" into `face`.
void read_face(std::string_view text, long long f, long long vertex_count, const std::string& name,
               long line, std::vector<int>& face) {
  std::string_view token;
  long long size = 0;
  next_token(text, token);
  if (!parse_int(token, size) || size < 0)
    fail(name, line, "face " + std::to_string(f) + ": bad vertex count " + quote_token(token));
  if (size > static_cast<long long>(text.size()))
    fail(name, line,
         "face " + std::to_string(f) + " claims " + std::to_string(size) +
             " vertices but the line is too short");
  face.resize(static_cast<size_t>(size));
  for (long long k = 0; k < size; ++k) {
    long long index = 0;
    if (!next_token(text, token))
      fail(name, line,
           "face " + std::to_string(f) + " lists " + std::to_string(k) + " of " +
               std::to_string(size) + " vertex indices");
    if (!parse_int(token, index))
      fail(name, line,
           "face " + std::to_string(f) + ": expected a vertex index, found " + quote_token(token));
    if (index < 0 || index >= vertex_count)
      fail(name, line,
           "face " + std::to_string(f) + " has vertex index " + std::to_string(index) +
               " but the file has " + std::to_string(vertex_count) + " vertices");
    face[static_cast<size_t>(k)] = static_cast<int>(index);
  }
}

}  // namespace

PolygonSoup parse_off(std::string_view data, const std::string& name) {
  LineCursor cursor(data);
  std::string_view text, token;
  if (!next_content_line(cursor, text)) fail(name, 0, "file holds no data (comments only)");
  next_token(text, token);
  check_header(token, name);
  const std::string_view keyword = token;
  if (next_token(text, token)) {
    if (token == "BINARY") fail(name, cursor.line_number(), "binary OFF is not supported");
    text = std::string_view(token.data(), text.data() + text.size() - token.data());
  } else if (!next_content_line(cursor, text)) {
    fail(name, cursor.line_number(), "file ends before the vertex and face counts");
  }
  const long count_line = cursor.line_number();
  const long long vertex_count = read_count(text, "vertex", name, count_line);
  const long long face_count = read_count(text, "face", name, count_line);
  // A garbage count must not reserve gigabytes: each record needs at least 4 bytes.
  if (vertex_count > static_cast<long long>(data.size()) / 4 ||
      face_count > static_cast<long long>(data.size()) / 4)
    fail(name, count_line,
         "counts of " + std::to_string(vertex_count) + " vertices and " +
             std::to_string(face_count) + " faces cannot fit in a file of " +
             std::to_string(data.size()) + " bytes");

  PolygonSoup soup;
  const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  read_vertices(cursor, vertex_count, name, prefix.find('N') != std::string_view::npos,
                prefix.find('C') != std::string_view::npos, soup);
  soup.faces.resize(static_cast<size_t>(face_count));
  soup.face_lines.resize(static_cast<size_t>(face_count));
  for (long long f = 0; f < face_count; ++f) {
    if (!next_content_line(cursor, text))
      fail(name, cursor.line_number(),
           "file ends after " + std::to_string(f) + " of " + std::to_string(face_count) + " faces");
    soup.face_lines[static_cast<size_t>(f)] = static_cast<int>(cursor.line_number());
    read_face(text, f, vertex_count, name, cursor.line_number(),
              soup.faces[static_cast<size_t>(f)]);
  }
  return soup;
}

}  // namespace ricci::detail
