#include "msp/io/atomic_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include <ricci/mesh/errors.h>

namespace msp {

void write_file_atomically(const std::string& path,
                           const std::function<void(const std::string& temp_path)>& write) {
  namespace fs = std::filesystem;
  fs::path target(path);
  fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(folder)) {
    throw ricci::IOError("cannot write " + path + ": folder " + folder.string() +
                         " does not exist");
  }
  std::random_device rd;
  fs::path temp = folder / ("." + target.filename().string() + ".tmp" + std::to_string(rd()));
  try {
    write(temp.string());
    fs::rename(temp, target);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

void write_text_atomically(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw ricci::IOError("cannot write " + path);
  });
}

void write_bytes_atomically(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  write_file_atomically(path, [&](const std::string& temp) {
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (!f) throw ricci::IOError("cannot write " + path);
    const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), f);
    if (std::fclose(f) != 0 || written != bytes.size())
      throw ricci::IOError("cannot write " + path);
  });
}

}  // namespace msp
