// Helpers of the globe-serve tests: the server as a child process (started on
// a free port, stopped with SIGTERM), and a raw HTTP/1.1 client written here
// over plain sockets, so requests can be anything (hostile ones included) and
// nothing is shared with the server's HTTP library.
#pragma once

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "test_paths.hpp"
#include "test_support.hpp"

namespace globe_test {

inline std::string serve_path() {
  return globe_test::paths::serve();
}

// globe-serve ARGS --port 0 -q, until destroyed. port() is 0 if it did not
// print its URL within 20 s; log() is its stderr.
class ServeProcess {
 public:
  explicit ServeProcess(const std::vector<std::string>& args, const fs::path& scratch)
      : log_path_(scratch / "serve.log") {
    int out[2];
    if (::pipe(out) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], 1);
      const int err = ::open(log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(err, 2);
      ::close(out[0]);
      std::vector<std::string> all{serve_path()};
      all.insert(all.end(), args.begin(), args.end());
      all.insert(all.end(), {"--port", "0"});
      std::vector<char*> argv;
      for (std::string& a : all)
        argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(out[1]);
    std::string line;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (line.find('\n') == std::string::npos && std::chrono::steady_clock::now() < deadline) {
      pollfd p{out[0], POLLIN, 0};
      if (::poll(&p, 1, 200) <= 0) continue;
      char buf[256];
      const ssize_t n = ::read(out[0], buf, sizeof buf);
      if (n <= 0) break;
      line.append(buf, size_t(n));
    }
    ::close(out[0]);
    const size_t colon = line.rfind(':');
    if (line.rfind("http://127.0.0.1:", 0) == 0 && colon != std::string::npos)
      port_ = std::atoi(line.c_str() + colon + 1);
  }
  ~ServeProcess() { stop(); }
  // SIGTERM; the exit status (-1 if it had to be killed).
  int stop() {
    if (pid_ <= 0) return status_;
    ::kill(pid_, SIGTERM);
    int st = 0;
    for (int i = 0; i < 100; ++i) {
      if (::waitpid(pid_, &st, WNOHANG) == pid_) {
        pid_ = -1;
        return status_ = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &st, 0);
    pid_ = -1;
    return status_ = -1;
  }
  bool alive() const {
    return pid_ > 0 && ::kill(pid_, 0) == 0 && ::waitpid(pid_, nullptr, WNOHANG) == 0;
  }
  int port() const { return port_; }
  std::string log() const { return read_file(log_path_); }
  // A line of /proc/PID/status in megabytes ("VmRSS", "VmHWM": the peak);
  // -1 if the server is gone.
  double memory_mb(const std::string& field) const {
    std::ifstream in("/proc/" + std::to_string(pid_) + "/status");
    for (std::string line; std::getline(in, line);)
      if (line.rfind(field + ":", 0) == 0) return std::atof(line.c_str() + field.size() + 1) / 1024;
    return -1;
  }

 private:
  fs::path log_path_;
  pid_t pid_ = -1;
  int port_ = 0, status_ = -1;
};

struct HttpReply {
  int status = 0;                              // 0: no (parsable) answer
  std::map<std::string, std::string> headers;  // names in lower case
  std::string body;
  std::string header(const std::string& name) const {
    const auto it = headers.find(name);
    return it == headers.end() ? "" : it->second;
  }
};

// Sends `raw` bytes to 127.0.0.1:port (then, if `half_close`, shuts the
// writing side) and reads until the server closes or `timeout_ms` passes.
inline std::string raw_exchange(int port, const std::string& raw, int timeout_ms = 5000,
                                bool half_close = false) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(uint16_t(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd);
    return "";
  }
  size_t sent = 0;
  while (sent < raw.size()) {
    const ssize_t n = ::send(fd, raw.data() + sent, raw.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;
    sent += size_t(n);
  }
  if (half_close) ::shutdown(fd, SHUT_WR);
  std::string in;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (std::chrono::steady_clock::now() < deadline) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    char buf[65536];
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    in.append(buf, size_t(n));
  }
  ::close(fd);
  return in;
}

// Parses one HTTP/1.1 response (Content-Length bodies; the rest of the bytes otherwise).
inline HttpReply parse_reply(const std::string& in) {
  HttpReply r;
  const size_t end = in.find("\r\n\r\n");
  if (in.rfind("HTTP/1.1 ", 0) != 0 || end == std::string::npos) return r;
  r.status = std::atoi(in.c_str() + 9);
  size_t at = in.find("\r\n") + 2;
  while (at < end) {
    const size_t eol = in.find("\r\n", at);
    const std::string line = in.substr(at, eol - at);
    const size_t colon = line.find(':');
    if (colon != std::string::npos) {
      std::string name = line.substr(0, colon);
      std::transform(name.begin(), name.end(), name.begin(), ::tolower);
      size_t v = colon + 1;
      while (v < line.size() && line[v] == ' ')
        ++v;
      r.headers[name] = line.substr(v);
    }
    at = eol + 2;
  }
  r.body = in.substr(end + 4);
  if (r.headers.count("content-length"))
    r.body = r.body.substr(0, std::stoul(r.headers["content-length"]));
  return r;
}

// GET (or another method) with extra header lines ("Name: value\r\n"...).
inline HttpReply http_get(int port, const std::string& target, const std::string& headers = "",
                          const std::string& method = "GET", int timeout_ms = 5000) {
  return parse_reply(raw_exchange(port,
                                  method + " " + target +
                                      " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                                      "\r\n" + headers + "Connection: close\r\n\r\n",
                                  timeout_ms));
}

}  // namespace globe_test
