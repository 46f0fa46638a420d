// A builder's transient random-access scratch file: fixed-size arrays written
// and read back at byte offsets the caller lays out (pwrite/pread, so any
// thread may read or write disjoint ranges at once). For work that does not
// fit in memory and is revisited out of order (the flow solver's chunks).
// The file is deleted when the object goes; a killed build leaves it behind
// and a resumed build recreates it from the input (docs/robustness.md).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace globe {

class ScratchArrayFile {
 public:
  // Creates (or truncates) `path`; throws OutputError naming it. With
  // `in_memory_bytes` nothing touches the disk: the arrays live in a buffer
  // of that size (for work that turned out to fit the budget); `path` only
  // names it in messages.
  explicit ScratchArrayFile(std::string path,
                            std::optional<uint64_t> in_memory_bytes = std::nullopt);
  ~ScratchArrayFile();
  ScratchArrayFile(const ScratchArrayFile&) = delete;
  ScratchArrayFile& operator=(const ScratchArrayFile&) = delete;

  // Throw OutputError naming the file (no space, a short read).
  void write_at(uint64_t offset, const void* data, size_t bytes);
  void read_at(uint64_t offset, void* data, size_t bytes) const;

  // `rows` rows of `row_bytes`, one after the other in the file from
  // `offset`, `stride` bytes apart in memory (a window's rows); a few calls
  // per array to a file.
  void write_rows_at(uint64_t offset, const void* data, size_t row_bytes, size_t rows,
                     size_t stride);
  void read_rows_at(uint64_t offset, void* data, size_t row_bytes, size_t rows,
                    size_t stride) const;

  template <typename T>
  void write_array(uint64_t offset, std::span<const T> values) {
    write_at(offset, values.data(), values.size_bytes());
  }
  template <typename T>
  void read_array(uint64_t offset, std::span<T> values) const {
    read_at(offset, values.data(), values.size_bytes());
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  std::vector<uint8_t> memory_;
};

}  // namespace globe
