#pragma once
// Internal helpers of the mesh readers: a line cursor, a whitespace tokenizer and number parsing
// with std::from_chars (iostream >> is an order of magnitude slower on 100k-face files).
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>

#include "ricci/mesh/errors.h"

namespace ricci::detail {

/// Throws IOError "<file>:<line>: <problem>", or "<file>: <problem>" when line <= 0.
[[noreturn]] void fail(const std::string& file, long line, const std::string& problem);

/// Walks a buffer line by line ("\n", "\r\n" or "\r\n"-less last line).
class LineCursor {
 public:
  explicit LineCursor(std::string_view data) : data_(data) {}
  /// Next line without its terminator; false at the end of the data.
  bool next(std::string_view& line) {
    if (pos_ >= data_.size()) return false;
    size_t end = data_.find('\n', pos_);
    if (end == std::string_view::npos) end = data_.size();
    line = data_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end + 1;
    ++line_number_;
    return true;
  }
  /// 1-based number of the line last returned.
  long line_number() const { return line_number_; }
  /// Bytes not yet returned (the binary body after a PLY header).
  std::string_view rest() const {
    return pos_ >= data_.size() ? std::string_view{} : data_.substr(pos_);
  }

 private:
  std::string_view data_;
  size_t pos_ = 0;
  long line_number_ = 0;
};

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// Splits the next whitespace-separated token off the front of `text`; false when none is left.
inline bool next_token(std::string_view& text, std::string_view& token) {
  size_t i = 0;
  while (i < text.size() && (is_space(text[i]) || text[i] == '\n')) ++i;
  if (i == text.size()) {
    text = {};
    return false;
  }
  size_t j = i;
  while (j < text.size() && !is_space(text[j]) && text[j] != '\n') ++j;
  token = text.substr(i, j - i);
  text.remove_prefix(j);
  return true;
}

/// Drops a '#' comment and everything after it.
inline std::string_view strip_comment(std::string_view line) {
  const size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

/// Parses a whole token as a double ("1e-3", "+2", "nan", "inf" included).
inline bool parse_double(std::string_view token, double& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return error == std::errc() && end == token.data() + token.size();
}

/// Parses a whole token as a signed integer.
inline bool parse_int(std::string_view token, long long& value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return error == std::errc() && end == token.data() + token.size();
}

/// A token quoted for a message, shortened and with control bytes escaped (garbage files).
std::string quote_token(std::string_view token);

/// Contents of a file, decompressed when the name ends in ".gz". \throw IOError.
std::string read_file_bytes(const std::string& path);

}  // namespace ricci::detail
