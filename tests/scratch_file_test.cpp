// Scratch record files: records come back in order and intact, a file cut
// inside a record is an error naming it, and the file goes with the object.
#include <gtest/gtest.h>

#include <filesystem>

#include "errors.hpp"
#include "scratch_file.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using globe_test::TempDir;

TEST(ScratchFile, RecordsComeBackInOrderAndTheFileGoes) {
  TempDir dir;
  const fs::path path = dir / "s.scratch";
  {
    globe::ScratchFile f(path.string());
    const std::vector<uint8_t> a{1, 2, 3}, empty, b(70000, 7);
    f.append(a);
    f.append(empty);
    f.append(b);
    EXPECT_EQ(f.bytes_written(), 3 * 4 + 3 + 70000u);
    f.rewind();
    std::vector<uint8_t> r;
    ASSERT_TRUE(f.next(r));
    EXPECT_EQ(r, a);
    ASSERT_TRUE(f.next(r));
    EXPECT_TRUE(r.empty());
    ASSERT_TRUE(f.next(r));
    EXPECT_EQ(r, b);
    EXPECT_FALSE(f.next(r));
    EXPECT_TRUE(fs::exists(path));
  }
  EXPECT_FALSE(fs::exists(path));
}

TEST(ScratchFile, ATruncatedRecordIsAnErrorNamingTheFile) {
  TempDir dir;
  const fs::path path = dir / "t.scratch";
  globe::ScratchFile f(path.string());
  f.append(std::vector<uint8_t>(100, 1));
  f.rewind();
  fs::resize_file(path, 50);
  std::vector<uint8_t> r;
  try {
    f.next(r);
    FAIL() << "no error";
  } catch (const globe::OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

TEST(ScratchFile, AnUncreatableFileIsAnOutputError) {
  TempDir dir;
  EXPECT_THROW(globe::ScratchFile((dir / "missing" / "x").string()), globe::OutputError);
}
