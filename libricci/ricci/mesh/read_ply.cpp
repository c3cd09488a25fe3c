// PLY reader: ascii, binary_little_endian and binary_big_endian; vertex x, y, z of any numeric
// type among other properties; face lists "vertex_indices"/"vertex_index" of any integer type;
// "tristrips" (Stanford scans); every other element or property is read past and dropped.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "ricci/mesh/parse_util.h"
#include "ricci/mesh/soup_formats.h"

namespace ricci::detail {
namespace {

enum class PlyType { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool type_from_name(std::string_view name, PlyType& type) {
  struct Entry {
    const char* name;
    PlyType type;
  };
  static const Entry kTypes[] = {
      {"char", PlyType::int8},      {"int8", PlyType::int8},       {"uchar", PlyType::uint8},
      {"uint8", PlyType::uint8},    {"short", PlyType::int16},     {"int16", PlyType::int16},
      {"ushort", PlyType::uint16},  {"uint16", PlyType::uint16},   {"int", PlyType::int32},
      {"int32", PlyType::int32},    {"uint", PlyType::uint32},     {"uint32", PlyType::uint32},
      {"float", PlyType::float32},  {"float32", PlyType::float32}, {"double", PlyType::float64},
      {"float64", PlyType::float64}};
  for (const auto& entry : kTypes) {
    if (name == entry.name) {
      type = entry.type;
      return true;
    }
  }
  return false;
}

size_t type_size(PlyType type) {
  switch (type) {
    case PlyType::int8:
    case PlyType::uint8:
      return 1;
    case PlyType::int16:
    case PlyType::uint16:
      return 2;
    case PlyType::int32:
    case PlyType::uint32:
    case PlyType::float32:
      return 4;
    case PlyType::float64:
      return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  bool is_list = false;
  PlyType count_type = PlyType::uint8;  // lists only
  PlyType type = PlyType::float32;      // the scalar, or the list's items
};

struct Element {
  std::string name;
  long long count = 0;
  long header_line = 0;
  std::vector<Property> properties;
};

enum class Encoding { ascii, little_endian, big_endian };

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  long body_line = 0;  // line number of the last header line
};

Header parse_header(LineCursor& cursor, const std::string& name) {
  std::string_view line, token;
  if (!cursor.next(line) || line.substr(0, 3) != "ply")
    fail(name, 1, "not a PLY file: it does not start with 'ply'");
  Header header;
  bool has_format = false;
  for (;;) {
    if (!cursor.next(line)) fail(name, cursor.line_number(), "header has no end_header line");
    const long n = cursor.line_number();
    std::string_view text = line;
    if (!next_token(text, token)) continue;
    if (token == "end_header") break;
    if (token == "comment" || token == "obj_info") continue;
    std::string_view words[5];
    int count = 0;
    while (count < 5 && next_token(text, words[count])) ++count;
    if (token == "format") {
      if (count < 1) fail(name, n, "format line names no format");
      if (words[0] == "ascii")
        header.encoding = Encoding::ascii;
      else if (words[0] == "binary_little_endian")
        header.encoding = Encoding::little_endian;
      else if (words[0] == "binary_big_endian")
        header.encoding = Encoding::big_endian;
      else
        fail(name, n, "unknown PLY format " + quote_token(words[0]));
      has_format = true;
    } else if (token == "element") {
      Element element;
      long long element_count = 0;
      if (count < 2 || !parse_int(words[1], element_count) || element_count < 0)
        fail(name, n, "element line needs a name and a count");
      element.name = std::string(words[0]);
      element.count = element_count;
      element.header_line = n;
      header.elements.push_back(std::move(element));
    } else if (token == "property") {
      if (header.elements.empty()) fail(name, n, "property before any element");
      Property property;
      if (count >= 4 && words[0] == "list") {
        if (!type_from_name(words[1], property.count_type) ||
            !type_from_name(words[2], property.type))
          fail(name, n, "unknown type in list property " + quote_token(words[3]));
        if (property.count_type == PlyType::float32 || property.count_type == PlyType::float64)
          fail(name, n, "list property " + quote_token(words[3]) + " has a floating-point count");
        property.is_list = true;
        property.name = std::string(words[3]);
      } else if (count == 2) {
        if (!type_from_name(words[0], property.type))
          fail(name, n, "unknown property type " + quote_token(words[0]));
        property.name = std::string(words[1]);
      } else {
        fail(name, n, "malformed property line");
      }
      header.elements.back().properties.push_back(std::move(property));
    } else {
      fail(name, n, "unknown header keyword " + quote_token(token));
    }
  }
  if (!has_format) fail(name, cursor.line_number(), "header has no format line");
  header.body_line = cursor.line_number();
  return header;
}

/// Reads PLY values from the body, in text or binary; counts lines (ascii) or bytes (binary).
class BodyReader {
 public:
  BodyReader(std::string_view body, Encoding encoding, long first_line)
      : body_(body), encoding_(encoding), line_(first_line) {
    const uint16_t one = 1;
    unsigned char first_byte = 0;
    std::memcpy(&first_byte, &one, 1);
    const bool host_little = first_byte == 1;
    swap_ = encoding == Encoding::big_endian
                ? host_little
                : (encoding == Encoding::little_endian && !host_little);
  }

  /// One value as a double; false at the end of the data. Sets `bad_token` on malformed text.
  bool read(PlyType type, double& value, std::string_view& bad_token) {
    return encoding_ == Encoding::ascii ? read_text(value, bad_token) : read_binary(type, value);
  }
  long line() const { return line_; }
  bool is_ascii() const { return encoding_ == Encoding::ascii; }
  size_t remaining() const { return body_.size() - pos_; }

 private:
  bool read_text(double& value, std::string_view& bad_token) {
    while (pos_ < body_.size() && (is_space(body_[pos_]) || body_[pos_] == '\n')) {
      if (body_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ == body_.size()) return false;
    size_t end = pos_;
    while (end < body_.size() && !is_space(body_[end]) && body_[end] != '\n') ++end;
    const std::string_view token = body_.substr(pos_, end - pos_);
    pos_ = end;
    if (!parse_double(token, value)) bad_token = token;
    return true;
  }

  bool read_binary(PlyType type, double& value) {
    const size_t size = type_size(type);
    if (body_.size() - pos_ < size) return false;
    unsigned char bytes[8];
    std::memcpy(bytes, body_.data() + pos_, size);
    pos_ += size;
    if (swap_)
      for (size_t i = 0; i < size / 2; ++i) std::swap(bytes[i], bytes[size - 1 - i]);
    switch (type) {
      case PlyType::int8:
        value = as<int8_t>(bytes);
        break;
      case PlyType::uint8:
        value = as<uint8_t>(bytes);
        break;
      case PlyType::int16:
        value = as<int16_t>(bytes);
        break;
      case PlyType::uint16:
        value = as<uint16_t>(bytes);
        break;
      case PlyType::int32:
        value = as<int32_t>(bytes);
        break;
      case PlyType::uint32:
        value = as<uint32_t>(bytes);
        break;
      case PlyType::float32:
        value = as<float>(bytes);
        break;
      case PlyType::float64:
        value = as<double>(bytes);
        break;
    }
    return true;
  }

  template <typename T>
  static double as(const unsigned char* bytes) {
    T typed;
    std::memcpy(&typed, bytes, sizeof(T));
    return static_cast<double>(typed);
  }

  std::string_view body_;
  size_t pos_ = 0;
  Encoding encoding_;
  bool swap_ = false;
  long line_;
};

/// Reads one element's records, handing scalar values and lists to the callbacks.
class ElementReader {
 public:
  ElementReader(BodyReader& body, const Element& element, const std::string& name)
      : body_(body), element_(element), name_(name) {}

  /// Reads record `record`; `values[p]` gets scalar property p, `lists[p]` list property p.
  void read_record(long long record, std::vector<double>& values,
                   std::vector<std::vector<long long>>& lists) {
    record_line_ = body_.line() + 1;
    for (size_t p = 0; p < element_.properties.size(); ++p) {
      const Property& property = element_.properties[p];
      if (!property.is_list) {
        values[p] = value(property.type, record, property.name);
        continue;
      }
      const double size = value(property.count_type, record, property.name);
      if (size < 0 || size != std::floor(size) || size > static_cast<double>(body_.remaining()))
        where_fail(record, "list " + quote_token(property.name) + " has a bad length " +
                               std::to_string(size));
      auto& list = lists[p];
      list.resize(static_cast<size_t>(size));
      for (auto& item : list) {
        const double v = value(property.type, record, property.name);
        if (v != std::floor(v) || std::fabs(v) > 9e15)
          where_fail(record, "list " + quote_token(property.name) + " holds a non-integer " +
                                 std::to_string(v));
        item = static_cast<long long>(v);
      }
    }
  }
  /// Line on which the last record started (ascii only, else 0).
  long record_line() const { return body_.is_ascii() ? record_line_ : 0; }

 private:
  double value(PlyType type, long long record, const std::string& property) {
    double v = 0;
    std::string_view bad;
    if (!body_.read(type, v, bad))
      fail(name_, body_.is_ascii() ? body_.line() : 0,
           "file ends inside element " + quote_token(element_.name) + " (record " +
               std::to_string(record) + " of " + std::to_string(element_.count) + ")");
    if (!bad.empty())
      where_fail(record, "property " + quote_token(property) + ": expected a number, found " +
                             quote_token(bad));
    return v;
  }

  [[noreturn]] void where_fail(long long record, const std::string& problem) {
    fail(name_, body_.is_ascii() ? body_.line() : 0,
         "element " + quote_token(element_.name) + " record " + std::to_string(record) + ": " +
             problem);
  }

  BodyReader& body_;
  const Element& element_;
  const std::string& name_;
  long record_line_ = 0;
};

int find_property(const Element& element, std::string_view property, bool want_list) {
  for (size_t p = 0; p < element.properties.size(); ++p)
    if (element.properties[p].name == property && element.properties[p].is_list == want_list)
      return static_cast<int>(p);
  return -1;
}

int face_list_property(const Element& element, const std::string& name) {
  int p = find_property(element, "vertex_indices", true);
  if (p < 0) p = find_property(element, "vertex_index", true);
  if (p < 0)
    fail(name, element.header_line,
         "element " + quote_token(element.name) + " has no vertex_indices list");
  return p;
}

/// Triangles of a strip list where -1 restarts a strip; every other triangle is flipped to keep
/// one winding, and the zero-area stitching triangles strips use are dropped.
void append_strip_triangles(const std::vector<long long>& strip_list, PolygonSoup& soup,
                            long line) {
  std::vector<long long> strip;
  auto flush = [&]() {
    for (size_t k = 0; k + 2 < strip.size(); ++k) {
      long long a = strip[k], b = strip[k + 1];
      const long long c = strip[k + 2];
      if (k % 2) std::swap(a, b);
      if (a == b || b == c || a == c) continue;
      soup.faces.push_back({static_cast<int>(a), static_cast<int>(b), static_cast<int>(c)});
      soup.face_lines.push_back(static_cast<int>(line));
    }
    strip.clear();
  };
  for (long long index : strip_list) {
    if (index < 0)
      flush();
    else
      strip.push_back(index);
  }
  flush();
}

int checked_index(long long index) {
  // Out-of-range values become -1 here and are reported with the face by check_soup_indices().
  return index < 0 || index > INT32_MAX ? -1 : static_cast<int>(index);
}

}  // namespace

PolygonSoup parse_ply(std::string_view data, const std::string& name) {
  LineCursor cursor(data);
  const Header header = parse_header(cursor, name);
  BodyReader body(cursor.rest(), header.encoding, header.body_line);
  PolygonSoup soup;
  bool has_vertices = false;
  for (const Element& element : header.elements) {
    // A record takes at least one byte per property (binary) or two (ascii text).
    if (element.count > 0 &&
        static_cast<double>(element.count) * static_cast<double>(element.properties.size()) >
            static_cast<double>(body.remaining()))
      fail(name, element.header_line,
           "element " + quote_token(element.name) + " claims " + std::to_string(element.count) +
               " records but only " + std::to_string(body.remaining()) +
               " bytes follow the header");
    const bool is_vertex = element.name == "vertex";
    const bool is_face = element.name == "face";
    const bool is_strips = element.name == "tristrips";
    int px = -1, py = -1, pz = -1, plist = -1;
    int pr = -1, pg = -1, pb = -1;  // colours, kept when all three are there
    double colour_scale = 1;
    if (is_vertex) {
      px = find_property(element, "x", false);
      py = find_property(element, "y", false);
      pz = find_property(element, "z", false);
      if (px < 0 || py < 0 || pz < 0)
        fail(name, element.header_line, "element 'vertex' lacks an x, y or z property");
      soup.positions.reserve(static_cast<size_t>(element.count));
      has_vertices = true;
      pr = find_property(element, "red", false);
      pg = find_property(element, "green", false);
      pb = find_property(element, "blue", false);
      if (pr >= 0 && pg >= 0 && pb >= 0) {
        const PlyType t = element.properties[pr].type;
        colour_scale = t == PlyType::float32 || t == PlyType::float64 ? 1.0 : 1.0 / 255;
      } else {
        pr = -1;
      }
    } else if (is_face || is_strips) {
      plist = face_list_property(element, name);
      if (is_face) soup.faces.reserve(static_cast<size_t>(element.count));
    }
    if (element.properties.empty()) continue;  // records without data: nothing to read
    std::vector<double> values(element.properties.size());
    std::vector<std::vector<long long>> lists(element.properties.size());
    ElementReader reader(body, element, name);
    for (long long record = 0; record < element.count; ++record) {
      reader.read_record(record, values, lists);
      if (is_vertex) {
        soup.positions.emplace_back(values[px], values[py], values[pz]);
        if (pr >= 0) {
          soup.colours.emplace_back(colour_scale *
                                    Eigen::Vector3d(values[pr], values[pg], values[pb]));
        }
        soup.vertex_lines.push_back(static_cast<int>(reader.record_line()));
      } else if (is_face) {
        std::vector<int> face(lists[plist].size());
        for (size_t k = 0; k < face.size(); ++k) face[k] = checked_index(lists[plist][k]);
        soup.faces.push_back(std::move(face));
        soup.face_lines.push_back(static_cast<int>(reader.record_line()));
      } else if (is_strips) {
        append_strip_triangles(lists[plist], soup, reader.record_line());
      }
    }
  }
  if (!has_vertices) fail(name, 0, "PLY header declares no 'vertex' element");
  if (header.encoding != Encoding::ascii) {  // binary: no lines to name
    soup.face_lines.clear();
    soup.vertex_lines.clear();
  }
  return soup;
}

}  // namespace ricci::detail
