#pragma once
// Byte surgery on spline files for the bad-file tests: where a section starts, fields read and
// written in place, the JSON header replaced (docs/spline-file.md: 16-byte preamble, header,
// then sections of a 4-byte tag, a u64 length and the payload).
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace spline::testing {

inline std::uint64_t read_u64(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  std::uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value |= static_cast<std::uint64_t>(bytes.at(at + i)) << (8 * i);
  return value;
}

inline std::uint32_t read_u32(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (int i = 0; i < 4; ++i) value |= static_cast<std::uint32_t>(bytes.at(at + i)) << (8 * i);
  return value;
}

inline void write_u64(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint64_t value) {
  for (int i = 0; i < 8; ++i) bytes.at(at + i) = static_cast<std::uint8_t>(value >> (8 * i));
}

inline void write_u32(std::vector<std::uint8_t>& bytes, std::size_t at, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes.at(at + i) = static_cast<std::uint8_t>(value >> (8 * i));
}

/// Offset of the section with this 4-byte tag (its tag's first byte).
inline std::size_t section_offset(const std::vector<std::uint8_t>& bytes, const char* tag) {
  std::size_t at = 16 + read_u32(bytes, 12);
  while (at + 12 <= bytes.size()) {
    if (std::memcmp(bytes.data() + at, tag, 4) == 0) return at;
    at += 12 + read_u64(bytes, at + 4);
  }
  throw std::logic_error(std::string("no section ") + tag);
}

/// The file with its JSON header replaced by `text`.
inline std::vector<std::uint8_t> with_header_text(const std::vector<std::uint8_t>& bytes,
                                                  const std::string& text) {
  const std::size_t old_end = 16 + read_u32(bytes, 12);
  std::vector<std::uint8_t> out(16 + text.size() + (bytes.size() - old_end));
  std::memcpy(out.data(), bytes.data(), 16);
  write_u32(out, 12, static_cast<std::uint32_t>(text.size()));
  std::memcpy(out.data() + 16, text.data(), text.size());
  std::memcpy(out.data() + 16 + text.size(), bytes.data() + old_end, bytes.size() - old_end);
  return out;
}

/// The file with one integer of its JSON header changed.
inline std::vector<std::uint8_t> with_header_value(const std::vector<std::uint8_t>& bytes,
                                                   const std::string& key, long long value) {
  const std::size_t length = read_u32(bytes, 12);
  nlohmann::ordered_json header = nlohmann::ordered_json::parse(
      std::string(bytes.begin() + 16, bytes.begin() + 16 + static_cast<std::ptrdiff_t>(length)));
  header[key] = value;
  return with_header_text(bytes, header.dump());
}

}  // namespace spline::testing
