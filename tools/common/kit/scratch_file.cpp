// Scratch record files (see scratch_file.hpp).
#include "kit/scratch_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "runtime/errors.hpp"
#include "tileformat/byte_io.hpp"

namespace globe {

ScratchFile::ScratchFile(std::string path) : path_(std::move(path)) {
  file_ = std::fopen(path_.c_str(), "w+b");
  if (!file_)
    throw OutputError(path_ + ": cannot create scratch file (" + std::strerror(errno) +
                      "); check free space and permissions next to the output");
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
}

ScratchFile::~ScratchFile() {
  std::fclose(file_);
  std::error_code ec;
  std::filesystem::remove(path_, ec);
}

void ScratchFile::write(const void* data, size_t size) {
  if (size && std::fwrite(data, 1, size, file_) != size)
    throw OutputError(path_ + ": cannot write scratch data (" + std::strerror(errno) +
                      "); check free space");
  bytes_written_ += size;
}

void ScratchFile::append(std::span<const uint8_t> record) {
  tileformat::ByteWriter len;
  len.u32(static_cast<uint32_t>(record.size()));
  const std::vector<uint8_t> head = len.take();
  write(head.data(), head.size());
  write(record.data(), record.size());
}

void ScratchFile::rewind() {
  if (std::fflush(file_) != 0)
    throw OutputError(path_ + ": cannot write scratch data (" + std::strerror(errno) +
                      "); check free space");
  std::rewind(file_);
}

bool ScratchFile::next(std::vector<uint8_t>& record) {
  uint8_t head[4];
  const size_t got = std::fread(head, 1, sizeof head, file_);
  if (got == 0 && std::feof(file_)) return false;
  if (got != sizeof head) throw OutputError(path_ + ": scratch file truncated while reading back");
  record.resize(tileformat::ByteReader(head, "scratch record", "scratch").u32());
  if (!record.empty() && std::fread(record.data(), 1, record.size(), file_) != record.size())
    throw OutputError(path_ + ": scratch file truncated while reading back");
  return true;
}

}  // namespace globe
