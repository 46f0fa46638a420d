// Files as streamed bodies (see file_body.hpp).
#include "serve/file_body.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <ctime>

namespace globe::serve {

std::shared_ptr<const OpenFile> OpenFile::open(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return nullptr;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    errno = EISDIR;
    return nullptr;
  }
  std::shared_ptr<OpenFile> f(new OpenFile);
  f->fd_ = fd;
  f->size_ = uint64_t(st.st_size);
  char tag[80];
  std::snprintf(tag, sizeof tag, "\"%llx-%llx-%llx\"", static_cast<unsigned long long>(st.st_ino),
                static_cast<unsigned long long>(st.st_size),
                static_cast<unsigned long long>(st.st_mtim.tv_sec) * 1000000000ULL +
                    static_cast<unsigned long long>(st.st_mtim.tv_nsec));
  f->etag_ = tag;
  std::tm utc{};
  ::gmtime_r(&st.st_mtim.tv_sec, &utc);
  char date[40];
  std::strftime(date, sizeof date, "%a, %d %b %Y %H:%M:%S GMT", &utc);  // IMF-fixdate
  f->last_modified_ = date;
  return f;
}

OpenFile::~OpenFile() {
  if (fd_ >= 0) ::close(fd_);
}

HttpResponse file_response(std::shared_ptr<const OpenFile> file, const std::string& content_type) {
  HttpResponse out;
  out.content_type = content_type;
  out.stream_size = file->size();
  out.send_length = file->size();
  out.etag = file->etag();
  out.last_modified = file->last_modified();
  out.stream = [file](uint64_t offset, char* to, uint64_t length) -> int64_t {
    const ssize_t n = ::pread(file->fd(), to, length, off_t(offset));
    return n < 0 ? -1 : int64_t(n);
  };
  return out;
}

}  // namespace globe::serve
