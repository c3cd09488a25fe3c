// OBJ reader: "v x y z [w]" and "f a b c ..." with a, a/t, a//n, a/t/n and negative (relative)
// indices; every other record (vt, vn, g, o, s, usemtl, l, ...) is skipped.
#include <algorithm>
#include <cstdint>
#include <cstring>

#include "ricci/mesh/parse_util.h"
#include "ricci/mesh/soup_formats.h"

namespace ricci::detail {
namespace {

/// A file with NUL bytes is binary, not OBJ text; reading it as lines would find nothing useful.
void refuse_binary(std::string_view data, const std::string& name) {
  const size_t probe = std::min<size_t>(data.size(), 4096);
  if (std::memchr(data.data(), '\0', probe))
    fail(name, 0,
         "not an OBJ file: binary data (NUL bytes) in the first " + std::to_string(probe) +
             " bytes");
}

}  // namespace

PolygonSoup parse_obj(std::string_view data, const std::string& name) {
  refuse_binary(data, name);
  PolygonSoup soup;
  LineCursor cursor(data);
  std::string_view line, token;
  while (cursor.next(line)) {
    std::string_view text = line;
    if (!next_token(text, token)) continue;
    const long line_number = cursor.line_number();
    if (token == "v") {
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        if (!next_token(text, token))
          fail(name, line_number,
               "vertex " + std::to_string(soup.positions.size()) + " has " + std::to_string(k) +
                   " coordinates; 3 are needed");
        if (!parse_double(token, p[k]))
          fail(name, line_number,
               "vertex " + std::to_string(soup.positions.size()) + ": expected a number, found " +
                   quote_token(token));
      }
      soup.positions.push_back(p);
      soup.vertex_lines.push_back(static_cast<int>(line_number));
    } else if (token == "f") {
      const size_t f = soup.faces.size();
      std::vector<int> face;
      text = strip_comment(text);
      while (next_token(text, token)) {
        const std::string_view index_text = token.substr(0, token.find('/'));
        long long index = 0;
        if (!parse_int(index_text, index))
          fail(name, line_number,
               "face " + std::to_string(f) + ": expected a vertex index, found " +
                   quote_token(token));
        // OBJ counts from 1; negative indices count back from the last vertex read so far.
        const long long vertex_count = static_cast<long long>(soup.positions.size());
        const long long resolved = index > 0 ? index - 1 : vertex_count + index;
        if (index == 0 || resolved < 0 || resolved > INT32_MAX)
          fail(name, line_number,
               "face " + std::to_string(f) + " has vertex index " + std::to_string(index) +
                   " but " + std::to_string(vertex_count) + " vertices are defined before it");
        face.push_back(static_cast<int>(resolved));
      }
      soup.faces.push_back(std::move(face));
      soup.face_lines.push_back(static_cast<int>(line_number));
    }
  }
  return soup;
}

}  // namespace ricci::detail
