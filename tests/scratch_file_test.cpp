// Scratch files: records come back in order and intact, a file cut inside a
// record is an error naming it, and the file goes with the object; arrays
// come back from their offsets, on disk and in memory.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "kit/scratch_array_file.hpp"
#include "kit/scratch_file.hpp"
#include "runtime/errors.hpp"
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

// Random-access scratch: arrays written at offsets come back from any order,
// on disk and in memory alike; a read past the end is an error naming the
// file; the file goes with the object.
TEST(ScratchArrayFile, ArraysComeBackFromTheirOffsetsOnDiskAndInMemory) {
  TempDir dir;
  for (const uint64_t in_memory : {uint64_t{0}, uint64_t{1 << 20}}) {
    const fs::path path = dir / (in_memory ? "m.bin" : "d.bin");
    {
      globe::ScratchArrayFile f(path.string(),
                                in_memory ? std::optional<uint64_t>(in_memory) : std::nullopt);
      std::vector<int32_t> a(1000), b(300);
      for (size_t i = 0; i < a.size(); ++i)
        a[i] = int32_t(i * 7) - 3000;
      for (size_t i = 0; i < b.size(); ++i)
        b[i] = int32_t(i) * -11;
      f.write_array<int32_t>(8000, b);  // past the first, written first
      f.write_array<int32_t>(0, a);
      std::vector<int32_t> ra(a.size()), rb(b.size());
      f.read_array<int32_t>(8000, rb);
      f.read_array<int32_t>(0, ra);
      EXPECT_EQ(ra, a);
      EXPECT_EQ(rb, b);
      EXPECT_EQ(fs::exists(path), in_memory == 0);
      std::vector<uint8_t> past(16);
      try {
        f.read_array<uint8_t>(in_memory ? (1 << 20) - 8 : 9200 - 8, past);
        ADD_FAILURE() << "a read past the end did not throw";
      } catch (const globe::OutputError& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
      }
    }
    EXPECT_FALSE(fs::exists(path));
  }
}

// A window's rows (stride apart in memory) go to consecutive bytes of the
// file and come back into another window; rows of 400 KB go through the
// file's 1 MiB buffer in batches of two, so seven rows take four batches.
TEST(ScratchArrayFile, RowsOfAWindowComeBackOnDiskAndInMemory) {
  TempDir dir;
  const size_t row = 400 << 10, rows = 7, stride = row + 24, at = 100;
  std::vector<uint8_t> window(rows * stride, 0);
  for (size_t i = 0; i < window.size(); ++i)
    window[i] = uint8_t(i * 31 + i / 977);
  for (const bool in_memory : {false, true}) {
    const fs::path path = dir / (in_memory ? "m.bin" : "d.bin");
    globe::ScratchArrayFile f(path.string(),
                              in_memory ? std::optional<uint64_t>(at + rows * row) : std::nullopt);
    f.write_rows_at(at, window.data(), row, rows, stride);
    std::vector<uint8_t> flat(rows * row);
    f.read_at(at, flat.data(), flat.size());
    for (size_t r = 0; r < rows; ++r)
      ASSERT_EQ(0, std::memcmp(flat.data() + r * row, window.data() + r * stride, row))
          << "row " << r << (in_memory ? " in memory" : " on disk");
    std::vector<uint8_t> back(window.size(), 0);
    f.read_rows_at(at, back.data(), row, rows, stride);
    for (size_t r = 0; r < rows; ++r) {
      EXPECT_EQ(0, std::memcmp(back.data() + r * stride, window.data() + r * stride, row))
          << "row " << r << (in_memory ? " in memory" : " on disk");
      EXPECT_EQ(back[r * stride + row], 0) << "the gap between rows is left alone";
    }
  }
}
