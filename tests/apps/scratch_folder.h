#pragma once
// A test fixture with a fresh folder of its own under the system's temporary directory, named
// by the fixture and the process id (parallel ctest runs do not meet) and removed after the test.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>

#include <unistd.h>

#include <ricci/mesh/io.h>

namespace msp_test {

class ScratchFolderTest : public ::testing::Test {
 protected:
  explicit ScratchFolderTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    folder_ = std::filesystem::temp_directory_path() / (prefix_ + std::to_string(::getpid()));
    std::filesystem::create_directories(folder_);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }
  /// The path of `name` in the folder (the file need not exist).
  std::string path(const std::string& name) const { return (folder_ / name).string(); }
  /// Writes `mesh` to `name` in the folder (the format from its extension); returns the path.
  std::string file(const std::string& name, const ricci::Mesh& mesh) const {
    const std::string written = path(name);
    ricci::write_mesh(mesh, written);
    return written;
  }
  std::filesystem::path folder_;

 private:
  std::string prefix_;
};

}  // namespace msp_test
