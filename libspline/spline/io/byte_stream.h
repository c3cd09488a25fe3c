#pragma once
// Internal to the spline file: little-endian binary writing and bounds-checked reading.
// Doubles are stored as their IEEE-754 bit patterns, so they read back exactly.
#include <Eigen/Core>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "ricci/mesh/errors.h"

namespace spline::io_detail {

class ByteWriter {
 public:
  void u8(std::uint8_t value) { bytes_.push_back(value); }
  void u32(std::uint32_t value) {
    for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
  }
  void i32(int value) { u32(static_cast<std::uint32_t>(value)); }
  void u64(std::uint64_t value) {
    for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
  }
  void count(std::size_t value) { u64(static_cast<std::uint64_t>(value)); }
  void f64(double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    u64(bits);
  }
  void vec2(const Eigen::Vector2d& v) {
    f64(v.x());
    f64(v.y());
  }
  void vec3(const Eigen::Vector3d& v) {
    for (int k = 0; k < 3; ++k) f64(v[k]);
  }
  void text(const std::string& s) {
    count(s.size());
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  void raw(const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  /// Starts a section: its 4-byte tag and a length patched by end_section().
  void begin_section(const char* tag) {
    raw(tag, 4);
    section_start_ = bytes_.size();
    u64(0);
  }
  void end_section() {
    const std::uint64_t length = bytes_.size() - section_start_ - 8;
    for (int i = 0; i < 8; ++i)
      bytes_[section_start_ + i] = static_cast<std::uint8_t>(length >> (8 * i));
  }
  [[nodiscard]] std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
  std::size_t section_start_ = 0;
};

/// Reads a byte range; every read is checked against its end. Errors name the source (the file)
/// and the section being read.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size, std::string source, std::string where)
      : data_(data), size_(size), source_(std::move(source)), where_(std::move(where)) {}

  [[nodiscard]] std::size_t remaining() const { return size_ - pos_; }
  [[nodiscard]] std::size_t offset() const { return pos_; }
  [[nodiscard]] const std::string& source() const { return source_; }

  std::uint8_t u8() { return take(1)[0]; }
  std::uint32_t u32() {
    const std::uint8_t* p = take(4);
    std::uint32_t value = 0;
    for (int i = 0; i < 4; ++i) value |= static_cast<std::uint32_t>(p[i]) << (8 * i);
    return value;
  }
  int i32() {
    const std::uint32_t bits = u32();
    int value = 0;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  std::uint64_t u64() {
    const std::uint8_t* p = take(8);
    std::uint64_t value = 0;
    for (int i = 0; i < 8; ++i) value |= static_cast<std::uint64_t>(p[i]) << (8 * i);
    return value;
  }
  double f64() {
    const std::uint64_t bits = u64();
    double value = 0.0;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  Eigen::Vector2d vec2() {
    const double x = f64();
    return {x, f64()};
  }
  Eigen::Vector3d vec3() {
    const double x = f64();
    const double y = f64();
    return {x, y, f64()};
  }
  /// A stored element count, refused when `min_bytes` per element do not fit in what is left
  /// (so no count allocates more than the data holds).
  std::size_t count(std::size_t min_bytes, const std::string& what) {
    const std::uint64_t n = u64();
    if (n > remaining() / (min_bytes > 0 ? min_bytes : 1)) {
      fail("inconsistent counts: " + std::to_string(n) + " " + what + " do not fit in the " +
           std::to_string(remaining()) + " bytes left of " + where_);
    }
    return static_cast<std::size_t>(n);
  }
  std::string text(const std::string& what) {
    const std::size_t n = count(1, what);
    const std::uint8_t* p = take(n);
    return std::string(reinterpret_cast<const char*>(p), n);
  }
  /// The next section, which must carry `tag`: a reader over its bytes (this one moves past it).
  ByteReader section(const char* tag) {
    std::string name(tag, 4);
    while (name.back() == ' ') name.pop_back();
    if (remaining() < 12) fail("file ends before section " + name + " (truncated)");
    const std::uint8_t* p = take(4);
    if (std::memcmp(p, tag, 4) != 0) {
      fail("expected section " + name + " at byte " + std::to_string(pos_ - 4) + ", found another");
    }
    const std::uint64_t length = u64();
    if (length > remaining()) {
      fail("file ends inside section " + name + " (" + std::to_string(remaining()) + " of its " +
           std::to_string(length) + " bytes; truncated)");
    }
    ByteReader inner(data_ + pos_, static_cast<std::size_t>(length), source_, "section " + name);
    pos_ += static_cast<std::size_t>(length);
    return inner;
  }
  /// Refuses bytes left over (a section longer than its contents).
  void expect_end() const {
    if (remaining() != 0) {
      fail("inconsistent counts: " + std::to_string(remaining()) +
           " bytes left over at the end of " + where_);
    }
  }
  [[noreturn]] void fail(const std::string& problem) const {
    throw ricci::IOError(source_ + ": " + problem);
  }
  [[noreturn]] void invalid(const std::string& problem) const {
    throw ricci::InvalidInputError(source_ + ": " + where_ + ": " + problem);
  }

 private:
  const std::uint8_t* take(std::size_t n) {
    if (n > remaining()) {
      fail("inconsistent counts: " + where_ + " ends inside its contents (" +
           std::to_string(remaining()) + " bytes left, " + std::to_string(n) + " needed)");
    }
    const std::uint8_t* p = data_ + pos_;
    pos_ += n;
    return p;
  }

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  std::string source_;
  std::string where_;
};

}  // namespace spline::io_detail
