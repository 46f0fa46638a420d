// Random-access scratch files (see scratch_array_file.hpp).
#include "scratch_array_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "errors.hpp"

namespace globe {

ScratchArrayFile::ScratchArrayFile(std::string path, std::optional<uint64_t> in_memory_bytes)
    : path_(std::move(path)) {
  if (in_memory_bytes) {
    memory_.resize(*in_memory_bytes);
    return;
  }
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw OutputError(path_ + ": cannot create scratch file (" + std::strerror(errno) +
                      "); check free space and permissions next to the output");
}

ScratchArrayFile::~ScratchArrayFile() {
  if (fd_ < 0) return;
  ::close(fd_);
  std::error_code ec;
  std::filesystem::remove(path_, ec);
}

void ScratchArrayFile::write_at(uint64_t offset, const void* data, size_t bytes) {
  if (fd_ < 0) {
    if (offset + bytes > memory_.size())
      throw OutputError(path_ + ": scratch data past its in-memory size (a bug)");
    std::memcpy(memory_.data() + offset, data, bytes);
    return;
  }
  const auto* p = static_cast<const uint8_t*>(data);
  while (bytes > 0) {
    const ssize_t n = ::pwrite(fd_, p, bytes, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw OutputError(path_ + ": cannot write scratch data (" +
                        std::strerror(n < 0 ? errno : ENOSPC) + "); check free space");
    p += n;
    offset += uint64_t(n);
    bytes -= size_t(n);
  }
}

void ScratchArrayFile::read_at(uint64_t offset, void* data, size_t bytes) const {
  if (fd_ < 0) {
    if (offset + bytes > memory_.size())
      throw OutputError(path_ + ": scratch read past its in-memory size (a bug)");
    std::memcpy(data, memory_.data() + offset, bytes);
    return;
  }
  auto* p = static_cast<uint8_t*>(data);
  while (bytes > 0) {
    const ssize_t n = ::pread(fd_, p, bytes, static_cast<off_t>(offset));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw OutputError(path_ + ": scratch file " + (n < 0 ? std::strerror(errno) : "truncated") +
                        " while reading back");
    p += n;
    offset += uint64_t(n);
    bytes -= size_t(n);
  }
}

}  // namespace globe
