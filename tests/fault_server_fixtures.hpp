// The fault-injecting test server (tests/support/fault_server) as a child
// process of a test, and its request log: used by the network tests of lib/net
// (net_fault_test.cpp) and of globe-view's remote sources
// (viewer_remote_test.cpp). The server is stopped by an RAII guard even when
// an assertion fails.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "test_paths.hpp"
#include "test_support.hpp"

namespace globe_test {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ------------------------------------------------------------- the log ----

// One line of fault_server's --log (fault_server --help).
struct LogEntry {
  double t = 0, done = 0;
  std::string method, path, range, if_none_match, user_agent, fault;
  int status = 0;
  long long bytes = 0;
  bool held = false;
  int conn = 0;
};

// A flat JSON object of strings, numbers and booleans (what the server
// writes); nullopt if the line is not one.
inline std::optional<std::map<std::string, std::string>> parse_flat_json(const std::string& line) {
  std::map<std::string, std::string> out;
  size_t i = 0;
  auto skip = [&] {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
      ++i;
  };
  auto string = [&]() -> std::optional<std::string> {
    if (i >= line.size() || line[i] != '"') return std::nullopt;
    std::string s;
    for (++i; i < line.size() && line[i] != '"'; ++i) {
      if (line[i] != '\\') {
        s += line[i];
        continue;
      }
      if (++i >= line.size()) return std::nullopt;
      if (line[i] == 'u') {
        if (i + 4 >= line.size()) return std::nullopt;
        s += char(std::stoi(line.substr(i + 1, 4), nullptr, 16));
        i += 4;
      } else {
        s += line[i] == 'n' ? '\n' : line[i] == 't' ? '\t' : line[i];
      }
    }
    if (i >= line.size()) return std::nullopt;
    ++i;
    return s;
  };
  skip();
  if (i >= line.size() || line[i++] != '{') return std::nullopt;
  while (true) {
    skip();
    const auto key = string();
    skip();
    if (!key || i >= line.size() || line[i++] != ':') return std::nullopt;
    skip();
    if (i < line.size() && line[i] == '"') {
      const auto value = string();
      if (!value) return std::nullopt;
      out[*key] = *value;
    } else {
      const size_t end = line.find_first_of(",}", i);
      if (end == std::string::npos) return std::nullopt;
      out[*key] = line.substr(i, end - i);
      i = end;
    }
    skip();
    if (i >= line.size()) return std::nullopt;
    if (line[i] == '}') return out;
    if (line[i++] != ',') return std::nullopt;
  }
}

inline std::vector<LogEntry> read_log(const fs::path& file) {
  std::vector<LogEntry> entries;
  std::istringstream in(globe_test::read_file(file));
  for (std::string line; std::getline(in, line);) {
    const auto m = parse_flat_json(line);
    if (!m) {
      ADD_FAILURE() << file << ": not a log line: " << line;
      continue;
    }
    auto get = [&](const char* k) {
      const auto it = m->find(k);
      return it == m->end() ? std::string() : it->second;
    };
    LogEntry e;
    e.t = std::atof(get("t").c_str());
    e.done = std::atof(get("done").c_str());
    e.method = get("method");
    e.path = get("path");
    e.range = get("range");
    e.if_none_match = get("if_none_match");
    e.user_agent = get("user_agent");
    e.fault = get("fault");
    e.status = std::atoi(get("status").c_str());
    e.bytes = std::atoll(get("bytes").c_str());
    e.held = get("held") == "true";
    e.conn = std::atoi(get("conn").c_str());
    entries.push_back(e);
  }
  std::stable_sort(entries.begin(), entries.end(),
                   [](const LogEntry& a, const LogEntry& b) { return a.t < b.t; });
  return entries;
}

inline size_t count_path(const std::vector<LogEntry>& log, const std::string& p) {
  return size_t(
      std::count_if(log.begin(), log.end(), [&](const LogEntry& e) { return e.path == p; }));
}

// ------------------------------------------------------------ the server --

// fault_server --root ROOT --port 0 --log SCRATCH/requests.jsonl OPTIONS, as
// a child process until stop() or destruction (SIGTERM, then SIGKILL after
// 10 s; always reaped). port() is 0 if it did not say it was listening.
class FaultServer {
 public:
  FaultServer(const fs::path& root, const std::vector<std::string>& options,
              const fs::path& scratch)
      : log_path_(scratch / "requests.jsonl"), err_path_(scratch / "fault_server.stderr") {
    std::vector<std::string> args{globe_test::paths::fault_server(),
                                  "--root",
                                  root.string(),
                                  "--port",
                                  "0",
                                  "--log",
                                  log_path_.string()};
    args.insert(args.end(), options.begin(), options.end());
    std::vector<char*> argv;
    for (std::string& a : args)
      argv.push_back(a.data());
    argv.push_back(nullptr);
    const int err = ::open(err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    int out[2];
    if (err < 0 || ::pipe2(out, O_CLOEXEC) != 0) {
      ADD_FAILURE() << "cannot make a pipe or " << err_path_;
      return;
    }
    pid_ = ::fork();
    if (pid_ == 0) {  // only async-signal-safe calls from here on
      ::dup2(out[1], 1);
      ::dup2(err, 2);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(out[1]);
    ::close(err);
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
    const std::string prefix = "listening on 127.0.0.1:";
    if (line.rfind(prefix, 0) == 0) port_ = std::atoi(line.c_str() + prefix.size());
    if (port_ <= 0) ADD_FAILURE() << "fault_server did not start: " << line << "\n" << errors();
  }
  ~FaultServer() { stop(); }
  FaultServer(const FaultServer&) = delete;
  FaultServer& operator=(const FaultServer&) = delete;

  int port() const { return port_; }
  std::string url(const std::string& p) const {
    return "http://127.0.0.1:" + std::to_string(port_) + p;
  }
  // Stops it; then its log is complete (each request's line is written when
  // its answer has been sent, so a client can see an answer before its line).
  // Its exit status (-1: killed or not started).
  int stop() {
    if (pid_ <= 0) return status_;
    ::kill(pid_, SIGTERM);
    int st = 0;
    for (int i = 0; i < 200; ++i) {
      if (::waitpid(pid_, &st, WNOHANG) == pid_) {
        pid_ = -1;
        return status_ = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &st, 0);
    pid_ = -1;
    ADD_FAILURE() << "fault_server ignored SIGTERM for 10 s";
    return status_ = -1;
  }
  std::vector<LogEntry> log() const { return read_log(log_path_); }
  // The log as it is now, re-read until `ready` holds or `timeout_s` passes.
  template <class Pred>
  std::vector<LogEntry> wait_log(Pred ready, double timeout_s) const {
    const auto t0 = std::chrono::steady_clock::now();
    while (true) {
      std::vector<LogEntry> l = log();
      if (ready(l) || seconds_since(t0) > timeout_s) return l;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  std::string errors() const { return globe_test::read_file(err_path_); }

 private:
  fs::path log_path_, err_path_;
  pid_t pid_ = -1;
  int port_ = 0, status_ = -1;
};

}  // namespace globe_test
