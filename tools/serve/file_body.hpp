// A file served as it is (a .pmtiles archive, a library's script): an open
// descriptor read on demand, and its validators from its identity — a strong
// ETag of inode, size and modification time, and Last-Modified — so that
// If-None-Match and If-Range work on files as on tiles.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "serve/http_server.hpp"

namespace globe::serve {

class OpenFile {
 public:
  // nullptr if `path` cannot be opened or is not a regular file (errno says why).
  static std::shared_ptr<const OpenFile> open(const std::string& path);
  ~OpenFile();
  OpenFile(const OpenFile&) = delete;
  OpenFile& operator=(const OpenFile&) = delete;

  int fd() const { return fd_; }
  uint64_t size() const { return size_; }
  const std::string& etag() const { return etag_; }
  const std::string& last_modified() const { return last_modified_; }

 private:
  OpenFile() = default;
  int fd_ = -1;
  uint64_t size_ = 0;
  std::string etag_, last_modified_;
};

// A 200 answer whose body is the whole of `file`, read as it is sent.
HttpResponse file_response(std::shared_ptr<const OpenFile> file, const std::string& content_type);

}  // namespace globe::serve
