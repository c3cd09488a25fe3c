// STL reader, ascii ("solid ... facet ... vertex x y z ... endsolid") and binary (80-byte header,
// triangle count, 50 bytes per triangle). STL repeats every corner, so identical positions are
// merged into one vertex; without that no two triangles would share an edge.
#include <cstdint>
#include <cstring>
#include <unordered_map>

#include "ricci/mesh/parse_util.h"
#include "ricci/mesh/soup_formats.h"

namespace ricci::detail {
namespace {

struct PositionHash {
  size_t operator()(const Eigen::Vector3d& p) const {
    size_t seed = 0;
    for (int k = 0; k < 3; ++k) {
      // -0.0 and 0.0 are the same point: hash them alike (operator== already agrees).
      const double value = p[k] == 0.0 ? 0.0 : p[k];
      uint64_t bits;
      std::memcpy(&bits, &value, sizeof bits);
      seed ^= std::hash<uint64_t>()(bits) + 0x9e3779b97f4a7c15ULL + (seed << 6) + (seed >> 2);
    }
    return seed;
  }
};

/// Collects triangle corners and gives each distinct position one vertex index.
class Welder {
 public:
  explicit Welder(PolygonSoup& soup) : soup_(soup) {}
  /// Index of the vertex at `p`, made on first sight; `line` (0 = none) is where it appeared.
  int vertex(const Eigen::Vector3d& p, long line = 0) {
    // NaN never equals itself: give such corners their own vertex so diagnose() can name it.
    if (!p.allFinite()) return add(p, line);
    const auto [it, inserted] = index_.try_emplace(p, static_cast<int>(soup_.positions.size()));
    if (inserted) add(p, line);
    return it->second;
  }
  void reserve(size_t triangles) { index_.reserve(triangles / 2 + 3); }

 private:
  int add(const Eigen::Vector3d& p, long line) {
    soup_.positions.push_back(p);
    if (line > 0) soup_.vertex_lines.push_back(static_cast<int>(line));
    return static_cast<int>(soup_.positions.size() - 1);
  }

  PolygonSoup& soup_;
  std::unordered_map<Eigen::Vector3d, int, PositionHash> index_;
};

PolygonSoup parse_binary(std::string_view data, uint32_t count) {
  PolygonSoup soup;
  Welder welder(soup);
  welder.reserve(count);
  soup.faces.reserve(count);
  for (uint32_t t = 0; t < count; ++t) {
    const char* record = data.data() + 84 + 50 * static_cast<size_t>(t);
    std::vector<int> face(3);
    for (int corner = 0; corner < 3; ++corner) {
      float xyz[3];
      std::memcpy(xyz, record + 12 + 12 * corner, sizeof xyz);  // STL is little-endian
      face[corner] = welder.vertex(Eigen::Vector3d(xyz[0], xyz[1], xyz[2]));
    }
    soup.faces.push_back(std::move(face));
  }
  return soup;
}

PolygonSoup parse_ascii(std::string_view data, const std::string& name) {
  PolygonSoup soup;
  Welder welder(soup);
  LineCursor cursor(data);
  std::string_view line, token;
  std::vector<int> face;
  long facet_line = 0;
  bool saw_solid = false;
  while (cursor.next(line)) {
    std::string_view text = line;
    if (!next_token(text, token)) continue;
    const long n = cursor.line_number();
    if (token == "solid") {
      saw_solid = true;
    } else if (!saw_solid) {
      fail(name, n, "not an STL file: it starts with " + quote_token(token) + ", not 'solid'");
    } else if (token == "facet") {
      if (!face.empty()) fail(name, n, "facet starts before the previous one has 3 vertices");
      facet_line = n;
    } else if (token == "vertex") {
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        if (!next_token(text, token))
          fail(name, n, "vertex has " + std::to_string(k) + " coordinates; 3 are needed");
        if (!parse_double(token, p[k]))
          fail(name, n, "vertex: expected a number, found " + quote_token(token));
      }
      face.push_back(welder.vertex(p, n));
      if (face.size() > 3) fail(name, n, "facet has more than 3 vertices");
    } else if (token == "endfacet") {
      if (face.size() != 3)
        fail(name, n, "facet has " + std::to_string(face.size()) + " vertices instead of 3");
      soup.faces.push_back(std::move(face));
      soup.face_lines.push_back(static_cast<int>(facet_line));
      face.clear();
    }
  }
  if (!face.empty()) fail(name, cursor.line_number(), "file ends inside a facet");
  return soup;
}

}  // namespace

PolygonSoup parse_stl(std::string_view data, const std::string& name) {
  // Binary files may also begin with "solid", so the size formula decides first.
  if (data.size() >= 84) {
    uint32_t count = 0;
    std::memcpy(&count, data.data() + 80, sizeof count);
    if (84 + 50 * static_cast<uint64_t>(count) == data.size()) return parse_binary(data, count);
  }
  std::string_view probe = data, token;
  if (!next_token(probe, token) || token != "solid") {
    if (data.size() >= 84) {
      uint32_t count = 0;
      std::memcpy(&count, data.data() + 80, sizeof count);
      fail(name, 0,
           "binary STL says " + std::to_string(count) + " triangles (" +
               std::to_string(84 + 50 * static_cast<uint64_t>(count)) +
               " bytes) but the file has " + std::to_string(data.size()) +
               " bytes: truncated or not an STL file");
    }
    fail(name, 0, "not an STL file: too short for binary STL and no 'solid' header");
  }
  return parse_ascii(data, name);
}

}  // namespace ricci::detail
