// A builder's transient scratch stream: records appended to a file next to
// the output, then read back in order. Every builder's scratch data goes
// through this one class and the one byte codec (tileformat/byte_io.hpp):
// each record is its byte length (u32, little endian) and its bytes. The file
// is deleted when the object goes; a killed build leaves it behind and a
// resumed build recreates it from the input (docs/robustness.md). State that
// a resume keeps lives in the package and in tileformat::StagingStore.
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

namespace globe {

class ScratchFile {
 public:
  // Creates (or truncates) `path`; throws OutputError naming it.
  explicit ScratchFile(std::string path);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  void append(std::span<const uint8_t> record);
  // Ends writing; next() then reads the records from the first.
  void rewind();
  // The next record into `record`; false at the end. Throws OutputError if
  // the file ends inside a record.
  bool next(std::vector<uint8_t>& record);

  const std::string& path() const { return path_; }
  uint64_t bytes_written() const { return bytes_written_; }

 private:
  void write(const void* data, size_t size);
  std::string path_;
  std::FILE* file_ = nullptr;
  uint64_t bytes_written_ = 0;
};

}  // namespace globe
