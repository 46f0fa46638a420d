// Random-access scratch files (see scratch_array_file.hpp).
#include "kit/scratch_array_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "runtime/errors.hpp"

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

namespace {

// Rows go through a buffer of at most 1 MiB to and from a file: a few calls
// per array, not one per row. Calls fn(first row, rows, buffer) per batch.
template <typename F>
void in_row_batches(size_t row_bytes, size_t rows, F fn) {
  const size_t batch = std::max<size_t>(1, (size_t(1) << 20) / std::max<size_t>(1, row_bytes));
  std::vector<uint8_t> buffer(std::min(rows, batch) * row_bytes);
  for (size_t r = 0; r < rows; r += batch)
    fn(r, std::min(batch, rows - r), buffer.data());
}

}  // namespace

void ScratchArrayFile::write_rows_at(uint64_t offset, const void* data, size_t row_bytes,
                                     size_t rows, size_t stride) {
  const auto* p = static_cast<const uint8_t*>(data);
  if (fd_ < 0) {
    for (size_t r = 0; r < rows; ++r)
      write_at(offset + r * row_bytes, p + r * stride, row_bytes);
    return;
  }
  in_row_batches(row_bytes, rows, [&](size_t first, size_t n, uint8_t* buffer) {
    for (size_t k = 0; k < n; ++k)
      std::memcpy(buffer + k * row_bytes, p + (first + k) * stride, row_bytes);
    write_at(offset + first * row_bytes, buffer, n * row_bytes);
  });
}

void ScratchArrayFile::read_rows_at(uint64_t offset, void* data, size_t row_bytes, size_t rows,
                                    size_t stride) const {
  auto* p = static_cast<uint8_t*>(data);
  if (fd_ < 0) {
    for (size_t r = 0; r < rows; ++r)
      read_at(offset + r * row_bytes, p + r * stride, row_bytes);
    return;
  }
  in_row_batches(row_bytes, rows, [&](size_t first, size_t n, uint8_t* buffer) {
    read_at(offset + first * row_bytes, buffer, n * row_bytes);
    for (size_t k = 0; k < n; ++k)
      std::memcpy(p + (first + k) * stride, buffer + k * row_bytes, row_bytes);
  });
}

}  // namespace globe
