#pragma once
// Small command-line helpers shared by the msp subcommands: argument parsing, error reporting
// and atomic file output.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace msp {

/// Thrown for a bad command line; main() prints it as one line and exits with status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Parsed arguments: positionals in order, `--name value` options and `--flag` switches.
class Args {
 public:
  /// `flags` lists the switches that take no value; every other `--name` takes one.
  Args(int argc, char** argv, const std::vector<std::string>& flags);

  const std::vector<std::string>& positionals() const { return positionals_; }
  bool has(const std::string& name) const;
  std::optional<std::string> get(const std::string& name) const;
  std::string get_or(const std::string& name, const std::string& fallback) const;
  double get_double(const std::string& name, double fallback) const;
  int get_int(const std::string& name, int fallback) const;
  /// Throws UsageError naming the first option not in `known`.
  void require_known(const std::vector<std::string>& known) const;
  /// Throws UsageError unless there are exactly `count` positionals.
  void require_positionals(size_t count, const std::string& usage) const;

 private:
  std::vector<std::string> positionals_;
  std::map<std::string, std::string> options_;
};

/// Writes a file through a temporary in the same folder and renames it into place, so a reader
/// never sees a half-written file and a failure leaves nothing behind.
void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temp_path)>& write);
void write_text_atomically(const std::string& path, const std::string& text);
/// Binary bytes, the same way. \throw ricci::IOError.
void write_bytes_atomically(const std::string& path, const std::vector<std::uint8_t>& bytes);

}  // namespace msp
