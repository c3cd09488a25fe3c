#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <ricci/mesh/errors.h>

#include "msp/cli.h"

namespace {

TEST(Args, ParsesPositionalsOptionsAndFlags) {
  const char* raw[] = {"mesh.obj", "--degree", "3", "--json", "--tol=1e-9", "-o", "out.glb"};
  msp::Args args(7, const_cast<char**>(raw), {"json"});
  ASSERT_EQ(args.positionals().size(), 1u);
  EXPECT_EQ(args.get_int("degree", 0), 3);
  EXPECT_TRUE(args.has("json"));
  EXPECT_DOUBLE_EQ(args.get_double("tol", 0), 1e-9);
  EXPECT_EQ(args.get_or("output", ""), "out.glb");
}

TEST(Args, RejectsUnknownOptionsAndBadNumbers) {
  const char* raw[] = {"--degre", "x"};
  msp::Args args(2, const_cast<char**>(raw), {});
  EXPECT_THROW(args.require_known({"degree"}), msp::UsageError);
  EXPECT_THROW(args.get_int("degre", 0), msp::UsageError);
}

TEST(AtomicWrite, FailureLeavesNoFile) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / "msp_atomic_test";
  fs::create_directories(dir);
  fs::path target = dir / "out.txt";
  fs::remove(target);
  EXPECT_THROW(msp::write_file_atomically(target.string(),
                                          [](const std::string&) { throw ricci::IOError("boom"); }),
               ricci::IOError);
  EXPECT_FALSE(fs::exists(target));
  EXPECT_TRUE(fs::is_empty(dir));
  msp::write_text_atomically(target.string(), "hello");
  std::ifstream in(target);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "hello");
  fs::remove_all(dir);
}

}  // namespace
