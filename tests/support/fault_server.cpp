// fault_server: a static HTTP/1.1 file server on 127.0.0.1 that misbehaves on
// purpose, for the tests of lib/net (tests/net_fault_test.cpp) and of a viewer
// streaming tiles over a bad network. Plain POSIX sockets and one thread per
// connection, no HTTP library: the faults need control of every byte.
//
// It serves GET and HEAD of the files under --root with Content-Type (from the
// extension), Content-Length, a strong ETag (size and mtime), Last-Modified,
// Cache-Control, 304 for If-None-Match / If-Modified-Since, single Range
// requests (206, 416) and keep-alive. Faults come from two places:
// - random ones (--error-rate ...), drawn from one generator seeded by --seed:
//   each request takes exactly two draws (its latency and its fault), in the
//   order the requests arrive, so a run is reproducible given that order;
// - exact ones, ROOT/.faults: lines "PATH FAULT [N]": the first N requests of
//   PATH get FAULT, later ones are served normally (no N: every request).
//   These override the random fault (the latency still applies).
// --log FILE writes one JSON line per request (flushed) that the tests read:
// when it arrived, what it asked, what it was answered and how many body
// bytes were sent. See usage() for the options and the log's fields.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <regex.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const char* const kUsage = R"(usage: fault_server --root DIR [options]

Serves the files under DIR over HTTP/1.1 on 127.0.0.1 and injects faults.
Prints "listening on 127.0.0.1:PORT" on stdout when ready; stops on SIGTERM
or SIGINT (exit 0). Exit 2: bad command line; 1: cannot listen or log.

  --root DIR             the folder served (required)
  --port N               port to listen on; 0 (default) = any free one
  --port-file FILE       also write the port to FILE (atomically)
  --log FILE             one JSON line per request (see below)
  --seed S               seed of the fault generator (default 1)
  --max-age N            Cache-Control: max-age=N; 0 (default) = no-cache
  --idle-timeout S       close a keep-alive connection idle for S s (default 30)

Random faults (each request draws one of them, at most, with these
probabilities; they apply only to paths matching --fault-paths):
  --latency MIN_MS:MAX_MS  wait this long (uniform) before answering
  --error-rate P           500 Internal Server Error
  --throttle-rate P        429 Too Many Requests with Retry-After
  --retry-after S          the Retry-After of a 429, seconds (default 2)
  --truncate-rate P        headers with the full Content-Length, half the
                           body, then close
  --wrong-type-rate P      200 with Content-Type text/html and an HTML body
  --reset-rate P           headers and part of the body, then close with a
                           TCP reset (SO_LINGER 0)
  --drip-rate P            the body --drip-bytes at a time (default 16), one
                           piece every --drip-interval-ms (default 200)
  --fault-paths REGEX      POSIX extended regex; faults and latency apply only
                           to request paths it matches (default: all)

Exact faults: DIR/.faults (read at start; never served), lines
  PATH FAULT [N]         the first N requests of PATH (the URL path, e.g.
                         /tiles/3/1/2.png) get FAULT, one of 500 429 truncate
                         wrongtype reset drip 404 204; no N = all of them.
                         Blank lines and lines starting with # are ignored.

A 429 (random or exact) holds the whole server for Retry-After seconds from
the moment it was sent: a request that arrives during a hold is answered as
usual but logged with "held":true (a client that ignored Retry-After).

Log lines (--log), in the order the answers finished:
  {"t":1.234,"method":"GET","path":"/a.png","range":"bytes=0-9",
   "if_none_match":"\"...\"","user_agent":"...","status":206,"fault":"none",
   "bytes":10,"held":false,"conn":3,"done":1.240}
  t: seconds since start (monotonic) when the request's headers arrived;
  done: when its answer was sent (or abandoned); fault: none 500 429
  truncate wrongtype reset drip 404 204; bytes: body bytes sent; conn: the
  connection's number (1, 2, ... in accept order). Missing headers are "".
)";

// ---------------------------------------------------------------- options --

struct Options {
  fs::path root;
  int port = 0;
  std::string port_file, log_file;
  uint64_t seed = 1;
  long max_age = 0;
  int idle_timeout_s = 30;
  int latency_min_ms = 0, latency_max_ms = 0;
  double error_rate = 0, throttle_rate = 0, truncate_rate = 0, wrong_type_rate = 0, reset_rate = 0,
         drip_rate = 0;
  int retry_after_s = 2;
  int drip_bytes = 16, drip_interval_ms = 200;
  std::string fault_paths;
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

double parse_number(const std::string& name, const std::string& text, double lo, double hi) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(v >= lo && v <= hi))
    throw UsageError(name + ": expected a number in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "], got '" + text + "'");
  return v;
}

Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      std::exit(0);
    }
    if (i + 1 >= argc) throw UsageError(a + ": unknown option or missing value");
    const std::string v = argv[++i];
    if (a == "--root") {
      o.root = v;
    } else if (a == "--port") {
      o.port = int(parse_number(a, v, 0, 65535));
    } else if (a == "--port-file") {
      o.port_file = v;
    } else if (a == "--log") {
      o.log_file = v;
    } else if (a == "--seed") {
      o.seed = uint64_t(parse_number(a, v, 0, 9e15));
    } else if (a == "--max-age") {
      o.max_age = long(parse_number(a, v, 0, 1e9));
    } else if (a == "--idle-timeout") {
      o.idle_timeout_s = int(parse_number(a, v, 1, 86400));
    } else if (a == "--latency") {
      const size_t colon = v.find(':');
      if (colon == std::string::npos) throw UsageError(a + ": expected MIN_MS:MAX_MS");
      o.latency_min_ms = int(parse_number(a, v.substr(0, colon), 0, 600000));
      o.latency_max_ms = int(parse_number(a, v.substr(colon + 1), 0, 600000));
      if (o.latency_max_ms < o.latency_min_ms) throw UsageError(a + ": MAX_MS < MIN_MS");
    } else if (a == "--error-rate") {
      o.error_rate = parse_number(a, v, 0, 1);
    } else if (a == "--throttle-rate") {
      o.throttle_rate = parse_number(a, v, 0, 1);
    } else if (a == "--retry-after") {
      o.retry_after_s = int(parse_number(a, v, 0, 86400));
    } else if (a == "--truncate-rate") {
      o.truncate_rate = parse_number(a, v, 0, 1);
    } else if (a == "--wrong-type-rate") {
      o.wrong_type_rate = parse_number(a, v, 0, 1);
    } else if (a == "--reset-rate") {
      o.reset_rate = parse_number(a, v, 0, 1);
    } else if (a == "--drip-rate") {
      o.drip_rate = parse_number(a, v, 0, 1);
    } else if (a == "--drip-bytes") {
      o.drip_bytes = int(parse_number(a, v, 1, 1 << 20));
    } else if (a == "--drip-interval-ms") {
      o.drip_interval_ms = int(parse_number(a, v, 1, 600000));
    } else if (a == "--fault-paths") {
      o.fault_paths = v;
    } else {
      throw UsageError(a + ": unknown option");
    }
  }
  if (o.root.empty()) throw UsageError("--root DIR is required");
  if (!fs::is_directory(o.root)) throw UsageError("--root " + o.root.string() + ": not a folder");
  const double sum = o.error_rate + o.throttle_rate + o.truncate_rate + o.wrong_type_rate +
                     o.reset_rate + o.drip_rate;
  if (sum > 1) throw UsageError("the fault rates add up to more than 1");
  return o;
}

// ------------------------------------------------------------------ state --

enum class Fault { kNone, k500, k429, kTruncate, kWrongType, kReset, kDrip, k404, k204 };

const char* fault_name(Fault f) {
  switch (f) {
    case Fault::kNone:
      return "none";
    case Fault::k500:
      return "500";
    case Fault::k429:
      return "429";
    case Fault::kTruncate:
      return "truncate";
    case Fault::kWrongType:
      return "wrongtype";
    case Fault::kReset:
      return "reset";
    case Fault::kDrip:
      return "drip";
    case Fault::k404:
      return "404";
    case Fault::k204:
      return "204";
  }
  return "none";
}

std::optional<Fault> fault_from_name(const std::string& s) {
  for (Fault f : {Fault::k500, Fault::k429, Fault::kTruncate, Fault::kWrongType, Fault::kReset,
                  Fault::kDrip, Fault::k404, Fault::k204})
    if (s == fault_name(f)) return f;
  return std::nullopt;
}

struct PathRule {
  Fault fault = Fault::kNone;
  long remaining = -1;  // -1: every request
};

class Server {
 public:
  explicit Server(Options o) : opt_(std::move(o)), start_(Clock::now()), rng_(opt_.seed) {
    if (!opt_.fault_paths.empty()) {
      const int rc = ::regcomp(&fault_re_, opt_.fault_paths.c_str(), REG_EXTENDED | REG_NOSUB);
      if (rc != 0) {
        char msg[256];
        ::regerror(rc, &fault_re_, msg, sizeof msg);
        throw UsageError("--fault-paths " + opt_.fault_paths + ": " + msg);
      }
      have_re_ = true;
    }
    read_fault_file();
    if (!opt_.log_file.empty()) {
      log_ = std::fopen(opt_.log_file.c_str(), "w");
      if (!log_) throw std::runtime_error(opt_.log_file + ": " + std::strerror(errno));
    }
  }
  ~Server() {
    if (have_re_) ::regfree(&fault_re_);
    if (log_) std::fclose(log_);
  }

  const Options& options() const { return opt_; }
  double now_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  bool stopping() const { return stop_.load(); }
  // Sleeps up to `ms`; false if the server is stopping.
  bool sleep_ms(int ms) {
    std::unique_lock lock(stop_mutex_);
    return !stop_cv_.wait_for(lock, std::chrono::milliseconds(ms), [&] { return stop_.load(); });
  }
  void request_stop() {
    {
      std::lock_guard lock(stop_mutex_);
      stop_ = true;
    }
    stop_cv_.notify_all();
    std::lock_guard lock(conn_mutex_);
    for (int fd : conn_fds_)
      ::shutdown(fd, SHUT_RDWR);
  }

  // Connection bookkeeping: stop() wakes every open connection and waits.
  int add_connection(int fd) {
    std::lock_guard lock(conn_mutex_);
    conn_fds_.insert(fd);
    if (stop_) ::shutdown(fd, SHUT_RDWR);
    return ++conn_count_;
  }
  void remove_connection(int fd) {
    std::lock_guard lock(conn_mutex_);
    conn_fds_.erase(fd);
    ::close(fd);
    conn_cv_.notify_all();
  }
  void wait_connections() {
    std::unique_lock lock(conn_mutex_);
    conn_cv_.wait(lock, [&] { return conn_fds_.empty(); });
  }

  // The latency and fault of the next request of `path`: two draws of the
  // generator for every request, whether or not they are used.
  std::pair<int, Fault> draw(const std::string& path) {
    uint64_t a, b;
    {
      std::lock_guard lock(rng_mutex_);
      a = rng_();
      b = rng_();
    }
    const bool eligible = !have_re_ || ::regexec(&fault_re_, path.c_str(), 0, nullptr, 0) == 0;
    int latency = 0;
    Fault fault = Fault::kNone;
    if (eligible) {
      const uint64_t span = uint64_t(opt_.latency_max_ms - opt_.latency_min_ms) + 1;
      latency = opt_.latency_min_ms + int(a % span);
      double u = double(b >> 11) * 0x1.0p-53, edge = 0;
      const std::pair<double, Fault> table[] = {
          {opt_.error_rate, Fault::k500},         {opt_.throttle_rate, Fault::k429},
          {opt_.truncate_rate, Fault::kTruncate}, {opt_.wrong_type_rate, Fault::kWrongType},
          {opt_.reset_rate, Fault::kReset},       {opt_.drip_rate, Fault::kDrip}};
      for (const auto& [rate, f] : table) {
        edge += rate;
        if (u < edge) {
          fault = f;
          break;
        }
      }
    }
    std::lock_guard lock(rules_mutex_);
    const auto it = rules_.find(path);
    if (it != rules_.end() && it->second.remaining != 0) {
      fault = it->second.fault;
      if (it->second.remaining > 0) --it->second.remaining;
    }
    return {latency, fault};
  }

  // A 429 was sent now: hold the server for Retry-After seconds.
  void start_hold() {
    std::lock_guard lock(hold_mutex_);
    hold_until_ = std::max(hold_until_, now_s() + opt_.retry_after_s);
  }
  bool in_hold(double t) {
    std::lock_guard lock(hold_mutex_);
    return t < hold_until_;
  }

  void log_line(const std::string& line) {
    if (!log_) return;
    std::lock_guard lock(log_mutex_);
    std::fputs(line.c_str(), log_);
    std::fputc('\n', log_);
    std::fflush(log_);
  }

 private:
  void read_fault_file() {
    const fs::path file = opt_.root / ".faults";
    std::ifstream in(file);
    if (!in) return;
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      std::istringstream words(line);
      std::string path, name;
      if (!(words >> path) || path[0] == '#') continue;
      long count = -1;
      const bool has_name = bool(words >> name);
      if (has_name && !(words >> count)) count = -1;
      const auto fault = has_name ? fault_from_name(name) : std::nullopt;
      if (!fault || count == 0 || count < -1)
        throw UsageError(file.string() + ":" + std::to_string(n) + ": expected 'PATH FAULT [N]'" +
                         " (FAULT: 500 429 truncate wrongtype reset drip 404 204; N > 0), got '" +
                         line + "'");
      rules_[path] = PathRule{*fault, count};
    }
  }

  Options opt_;
  Clock::time_point start_;
  std::mt19937_64 rng_;
  std::mutex rng_mutex_;
  regex_t fault_re_{};
  bool have_re_ = false;
  std::map<std::string, PathRule> rules_;
  std::mutex rules_mutex_;
  std::mutex hold_mutex_;
  double hold_until_ = -1;
  std::FILE* log_ = nullptr;
  std::mutex log_mutex_;
  std::atomic<bool> stop_{false};
  std::mutex stop_mutex_;
  std::condition_variable stop_cv_;
  std::mutex conn_mutex_;
  std::condition_variable conn_cv_;
  std::set<int> conn_fds_;
  int conn_count_ = 0;
};

// ---------------------------------------------------------------- helpers --

std::string lower(std::string s) {
  for (char& c : s)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  size_t a = 0, b = s.size();
  while (a < b && (s[a] == ' ' || s[a] == '\t'))
    ++a;
  while (b > a && (s[b - 1] == ' ' || s[b - 1] == '\t'))
    --b;
  return s.substr(a, b - a);
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += char(c);
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += char(c);
    }
  }
  return out + "\"";
}

std::string http_date(time_t t) {
  tm g{};
  ::gmtime_r(&t, &g);
  static const char* const kDays[] = {"Sun", "Mon", "Tue", "Wed", "Thu", "Fri", "Sat"};
  static const char* const kMonths[] = {"Jan", "Feb", "Mar", "Apr", "May", "Jun",
                                        "Jul", "Aug", "Sep", "Oct", "Nov", "Dec"};
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s, %02d %s %04d %02d:%02d:%02d GMT", kDays[g.tm_wday], g.tm_mday,
                kMonths[g.tm_mon], g.tm_year + 1900, g.tm_hour, g.tm_min, g.tm_sec);
  return buf;
}

// An IMF-fixdate ("Sun, 06 Nov 1994 08:49:37 GMT"); nullopt if not one.
std::optional<time_t> parse_http_date(const std::string& s) {
  tm g{};
  const char* end = ::strptime(s.c_str(), "%a, %d %b %Y %H:%M:%S GMT", &g);
  if (!end || *end != '\0') return std::nullopt;
  return ::timegm(&g);
}

const char* content_type(const fs::path& p) {
  static const std::map<std::string, const char*> kTypes = {
      {".png", "image/png"},
      {".jpg", "image/jpeg"},
      {".jpeg", "image/jpeg"},
      {".webp", "image/webp"},
      {".json", "application/json"},
      {".pbf", "application/x-protobuf"},
      {".terrain", "application/vnd.quantized-mesh"},
      {".pmtiles", "application/octet-stream"},
      {".mbtiles", "application/octet-stream"}};
  const auto it = kTypes.find(lower(p.extension().string()));
  return it == kTypes.end() ? "application/octet-stream" : it->second;
}

// %XX decoding; nullopt on a bad escape or a NUL.
std::optional<std::string> percent_decode(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '%') {
      out += s[i];
      continue;
    }
    if (i + 2 >= s.size() || !std::isxdigit(static_cast<unsigned char>(s[i + 1])) ||
        !std::isxdigit(static_cast<unsigned char>(s[i + 2])))
      return std::nullopt;
    const char c = char(std::stoi(s.substr(i + 1, 2), nullptr, 16));
    if (c == '\0') return std::nullopt;
    out += c;
    i += 2;
  }
  return out;
}

bool send_all(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::send(fd, data, size, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= size_t(n);
  }
  return true;
}

bool send_all(int fd, const std::string& s) {
  return send_all(fd, s.data(), s.size());
}

// A single byte range of a `size`-byte body: "bytes=a-b", "bytes=a-",
// "bytes=-n". nullopt: no usable Range (absent, malformed or several ranges:
// the whole body is sent, RFC 9110 14.2). {-1,-1}: unsatisfiable (416).
std::optional<std::pair<int64_t, int64_t>> parse_range(const std::string& header, int64_t size) {
  const std::string h = trim(header);
  if (h.rfind("bytes=", 0) != 0) return std::nullopt;
  const std::string spec = trim(h.substr(6));
  if (spec.find(',') != std::string::npos) return std::nullopt;
  const size_t dash = spec.find('-');
  if (dash == std::string::npos) return std::nullopt;
  const std::string a = trim(spec.substr(0, dash)), b = trim(spec.substr(dash + 1));
  auto number = [](const std::string& s) -> std::optional<int64_t> {
    if (s.empty() || s.size() > 18 || s.find_first_not_of("0123456789") != std::string::npos)
      return std::nullopt;
    return std::stoll(s);
  };
  if (a.empty()) {  // suffix: the last n bytes
    const auto n = number(b);
    if (!n) return std::nullopt;
    if (*n == 0 || size == 0) return std::make_pair(int64_t(-1), int64_t(-1));
    return std::make_pair(std::max<int64_t>(0, size - *n), size - 1);
  }
  const auto first = number(a);
  if (!first) return std::nullopt;
  int64_t last = size - 1;
  if (!b.empty()) {
    const auto l = number(b);
    if (!l || *l < *first) return std::nullopt;
    last = std::min(*l, size - 1);
  }
  if (*first >= size) return std::make_pair(int64_t(-1), int64_t(-1));
  return std::make_pair(*first, last);
}

// ------------------------------------------------------------- connection --

struct HttpRequest {
  std::string method, target, version;
  std::map<std::string, std::string> headers;  // lower-case names
  std::string header(const std::string& name) const {
    const auto it = headers.find(name);
    return it == headers.end() ? "" : it->second;
  }
};

class Connection {
 public:
  Connection(Server& server, int fd, int number) : s_(server), fd_(fd), number_(number) {}

  void run() {
    while (!s_.stopping()) {
      HttpRequest req;
      const int got = read_request(req);
      if (got <= 0) {
        if (got < 0) send_simple(400, "Bad Request", "bad request\n", true);
        return;
      }
      if (!answer(req)) return;
    }
  }

 private:
  // 1: a request; 0: the peer closed, idle timeout or stop; -1: malformed.
  int read_request(HttpRequest& req) {
    size_t end;
    const auto idle_until = Clock::now() + std::chrono::seconds(s_.options().idle_timeout_s);
    while ((end = buffer_.find("\r\n\r\n")) == std::string::npos) {
      if (buffer_.size() > 64 * 1024) return -1;
      if (s_.stopping() || Clock::now() > idle_until) return 0;
      pollfd p{fd_, POLLIN, 0};
      const int r = ::poll(&p, 1, 200);
      if (r < 0 && errno != EINTR) return 0;
      if (r <= 0) continue;
      char buf[8192];
      const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) return 0;
      buffer_.append(buf, size_t(n));
    }
    const std::string head = buffer_.substr(0, end);
    buffer_.erase(0, end + 4);
    std::istringstream lines(head);
    std::string line;
    std::getline(lines, line);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream first(line);
    if (!(first >> req.method >> req.target >> req.version)) return -1;
    if (req.version.rfind("HTTP/1.", 0) != 0) return -1;
    while (std::getline(lines, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const size_t colon = line.find(':');
      if (colon == std::string::npos) return -1;
      req.headers[lower(trim(line.substr(0, colon)))] = trim(line.substr(colon + 1));
    }
    // A body (none is expected of GET/HEAD) is read and dropped.
    const std::string length = req.header("content-length");
    if (!length.empty()) {
      const long long n = std::atoll(length.c_str());
      if (n < 0 || n > (1 << 20)) return -1;
      while (buffer_.size() < size_t(n)) {
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, 5000) <= 0) return 0;
        char buf[8192];
        const ssize_t got = ::recv(fd_, buf, sizeof buf, 0);
        if (got <= 0) return 0;
        buffer_.append(buf, size_t(got));
      }
      buffer_.erase(0, size_t(n));
    }
    return 1;
  }

  void send_simple(int status, const char* reason, const std::string& body, bool close) {
    std::string h =
        "HTTP/1.1 " + std::to_string(status) + " " + reason +
        "\r\nContent-Type: text/plain\r\nContent-Length: " + std::to_string(body.size()) + "\r\n" +
        (close ? "Connection: close\r\n" : "") + "\r\n";
    send_all(fd_, h + body);
  }

  struct Answer {
    int status = 0;
    std::string reason;
    std::vector<std::string> headers;  // "Name: value"
    std::string body;                  // small bodies (errors, HTML)
    bool file_body = false;            // else the file's bytes [first, first + length)
    int64_t first = 0, length = 0;
  };

  // Serves one request; false: the connection is to be closed.
  bool answer(const HttpRequest& req) {
    const double t = s_.now_s();
    const bool held = s_.in_hold(t);
    std::string path = req.target;
    const size_t query = path.find_first_of("?#");
    if (query != std::string::npos) path.resize(query);
    const bool head = req.method == "HEAD";
    bool keep_alive = lower(req.header("connection")) != "close" && req.version == "HTTP/1.1";

    const auto [latency_ms, drawn] = s_.draw(path);
    Fault fault = drawn;
    if (latency_ms > 0 && !s_.sleep_ms(latency_ms)) return false;

    Answer a = plan(req, path, head, fault);
    const std::string connection = keep_alive ? "" : "Connection: close\r\n";
    std::string out = "HTTP/1.1 " + std::to_string(a.status) + " " + a.reason + "\r\n";
    for (const std::string& h : a.headers)
      out += h + "\r\n";
    out += "Date: " + http_date(::time(nullptr)) + "\r\nServer: fault_server\r\n" + connection;
    out += "\r\n";

    // The body, read now (small files; a range of a large one).
    std::string body = a.body;
    if (a.file_body && !head) {
      body.resize(size_t(a.length));
      const int file = ::open(resolved_.c_str(), O_RDONLY | O_CLOEXEC);
      ssize_t got = file < 0 ? -1 : ::pread(file, body.data(), body.size(), a.first);
      if (file >= 0) ::close(file);
      if (got != ssize_t(body.size())) body.resize(got > 0 ? size_t(got) : 0);
    }
    if (head) body.clear();

    size_t sent = 0;
    bool ok = true;
    if (fault == Fault::k429) s_.start_hold();
    if (fault == Fault::kTruncate || fault == Fault::kReset) {
      // Headers promise the whole body; part of it comes, then the end.
      const size_t part = fault == Fault::kTruncate ? body.size() / 2 : body.size() / 3;
      ok = send_all(fd_, out) && send_all(fd_, body.data(), part);
      if (ok) sent = part;
      if (fault == Fault::kReset) {
        linger l{1, 0};
        ::setsockopt(fd_, SOL_SOCKET, SO_LINGER, &l, sizeof l);
      } else {
        ::shutdown(fd_, SHUT_WR);
      }
      keep_alive = false;
    } else if (fault == Fault::kDrip) {
      ok = send_all(fd_, out);
      const size_t step = size_t(s_.options().drip_bytes);
      while (ok && sent < body.size()) {
        const size_t n = std::min(step, body.size() - sent);
        ok = send_all(fd_, body.data() + sent, n);
        if (ok) sent += n;
        if (ok && sent < body.size() && !s_.sleep_ms(s_.options().drip_interval_ms)) ok = false;
      }
    } else {
      ok = send_all(fd_, out + body);
      if (ok) sent = body.size();
    }
    const double done = s_.now_s();

    std::ostringstream line;
    char tbuf[32], dbuf[32];
    std::snprintf(tbuf, sizeof tbuf, "%.3f", t);
    std::snprintf(dbuf, sizeof dbuf, "%.3f", done);
    line << "{\"t\":" << tbuf << ",\"method\":" << json_string(req.method)
         << ",\"path\":" << json_string(path) << ",\"range\":" << json_string(req.header("range"))
         << ",\"if_none_match\":" << json_string(req.header("if-none-match"))
         << ",\"user_agent\":" << json_string(req.header("user-agent"))
         << ",\"status\":" << a.status << ",\"fault\":\"" << fault_name(fault)
         << "\",\"bytes\":" << sent << ",\"held\":" << (held ? "true" : "false")
         << ",\"conn\":" << number_ << ",\"done\":" << dbuf << "}";
    s_.log_line(line.str());
    return ok && keep_alive;
  }

  // What to answer (status, headers, body); may turn `fault` into kNone when
  // it cannot apply (a body fault on a 304 or an error answer).
  Answer plan(const HttpRequest& req, const std::string& path, bool head, Fault& fault) {
    const Options& o = s_.options();
    Answer a;
    auto simple = [&](int status, const char* reason, const std::string& body) {
      a.status = status;
      a.reason = reason;
      a.body = body;
      a.headers = {"Content-Type: text/plain", "Content-Length: " + std::to_string(body.size())};
    };
    const std::string cache_control =
        "Cache-Control: " +
        (o.max_age > 0 ? "max-age=" + std::to_string(o.max_age) : std::string("no-cache"));

    if (req.method != "GET" && req.method != "HEAD") {
      simple(405, "Method Not Allowed", "only GET and HEAD\n");
      a.headers.push_back("Allow: GET, HEAD");
      fault = Fault::kNone;
      return a;
    }
    switch (fault) {
      case Fault::k500:
        simple(500, "Internal Server Error", "injected fault: 500\n");
        return a;
      case Fault::k429:
        simple(429, "Too Many Requests", "injected fault: 429\n");
        a.headers.push_back("Retry-After: " + std::to_string(o.retry_after_s));
        return a;
      case Fault::k404:
        simple(404, "Not Found", "injected fault: 404\n");
        return a;
      case Fault::k204:
        a.status = 204;
        a.reason = "No Content";
        return a;
      case Fault::kWrongType: {
        // A captive portal's page, with headers that would let it be cached.
        a.status = 200;
        a.reason = "OK";
        a.body =
            "<!DOCTYPE html>\n<html><head><title>Sign in</title></head>"
            "<body><p>Sign in to the network to continue.</p></body></html>\n";
        a.headers = {"Content-Type: text/html; charset=utf-8",
                     "Content-Length: " + std::to_string(a.body.size()), cache_control,
                     "ETag: \"portal\""};
        return a;
      }
      default:
        break;
    }

    // A file under the root.
    const auto decoded = percent_decode(path);
    if (!decoded || decoded->empty() || (*decoded)[0] != '/') {
      simple(400, "Bad Request", "bad path\n");
      fault = Fault::kNone;
      return a;
    }
    for (const auto& part : fs::path(*decoded))
      if (part == "..") {
        simple(403, "Forbidden", "path escapes the root\n");
        fault = Fault::kNone;
        return a;
      }
    resolved_ = o.root / fs::path(decoded->substr(1));
    struct stat st {};
    if (*decoded == "/.faults" || ::stat(resolved_.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
      simple(404, "Not Found", "not found\n");
      fault = Fault::kNone;
      return a;
    }
    const int64_t size = st.st_size;
    const int64_t mtime_ns = int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
    char etag_buf[64];
    std::snprintf(etag_buf, sizeof etag_buf, "\"%llx-%llx\"", static_cast<unsigned long long>(size),
                  static_cast<unsigned long long>(mtime_ns));
    const std::string etag = etag_buf;
    const std::vector<std::string> validators = {"ETag: " + etag,
                                                 "Last-Modified: " + http_date(st.st_mtim.tv_sec),
                                                 cache_control, "Accept-Ranges: bytes"};

    // Conditional requests: If-None-Match wins over If-Modified-Since.
    bool not_modified = false;
    const std::string inm = req.header("if-none-match");
    if (!inm.empty()) {
      std::istringstream tags(inm);
      for (std::string tag; std::getline(tags, tag, ',');) {
        tag = trim(tag);
        if (tag.rfind("W/", 0) == 0) tag = tag.substr(2);  // weak comparison (RFC 9110 13.1.2)
        if (tag == "*" || tag == etag) not_modified = true;
      }
    } else if (const auto since = parse_http_date(req.header("if-modified-since"))) {
      not_modified = st.st_mtim.tv_sec <= *since;
    }
    if (not_modified) {
      a.status = 304;
      a.reason = "Not Modified";
      a.headers = validators;
      fault = Fault::kNone;
      return a;
    }

    a.headers = {std::string("Content-Type: ") + content_type(resolved_)};
    a.headers.insert(a.headers.end(), validators.begin(), validators.end());
    const std::string range = req.header("range");
    const auto r = range.empty() ? std::nullopt : parse_range(range, size);
    if (r && r->first < 0) {
      simple(416, "Range Not Satisfiable", "range past the end\n");
      a.headers.push_back("Content-Range: bytes */" + std::to_string(size));
      fault = Fault::kNone;
      return a;
    }
    a.file_body = true;
    if (r) {
      a.status = 206;
      a.reason = "Partial Content";
      a.first = r->first;
      a.length = r->second - r->first + 1;
      a.headers.push_back("Content-Range: bytes " + std::to_string(r->first) + "-" +
                          std::to_string(r->second) + "/" + std::to_string(size));
    } else {
      a.status = 200;
      a.reason = "OK";
      a.length = size;
    }
    a.headers.push_back("Content-Length: " + std::to_string(a.length));
    if (head && (fault == Fault::kTruncate || fault == Fault::kReset || fault == Fault::kDrip))
      fault = Fault::kNone;  // no body to spoil
    return a;
  }

  Server& s_;
  int fd_;
  int number_;
  std::string buffer_;
  fs::path resolved_;
};

// ------------------------------------------------------------------- main --

int serve(const Options& options) {
  // SIGTERM and SIGINT are taken by sigwait() on a thread of their own, which
  // wakes the accept loop through a pipe; every other thread blocks them.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  ::signal(SIGPIPE, SIG_IGN);

  Server server(options);
  const int listener = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int one = 1;
  ::setsockopt(listener, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(uint16_t(options.port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof addr;
  if (listener < 0 || ::bind(listener, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::listen(listener, 256) != 0 ||
      ::getsockname(listener, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    std::cerr << "fault_server: cannot listen on 127.0.0.1:" << options.port << ": "
              << std::strerror(errno) << "\n";
    return 1;
  }
  const int port = ntohs(addr.sin_port);
  if (!options.port_file.empty()) {
    const std::string tmp = options.port_file + ".tmp";
    std::ofstream(tmp) << port << "\n";
    fs::rename(tmp, options.port_file);
  }

  int wake[2];
  if (::pipe2(wake, O_CLOEXEC) != 0) return 1;
  std::thread signal_thread([&] {
    int sig = 0;
    sigwait(&signals, &sig);
    const char c = 1;
    [[maybe_unused]] const ssize_t n = ::write(wake[1], &c, 1);
  });

  std::cout << "listening on 127.0.0.1:" << port << std::endl;

  while (true) {
    pollfd p[2] = {{listener, POLLIN, 0}, {wake[0], POLLIN, 0}};
    if (::poll(p, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (p[1].revents) break;
    if (!(p[0].revents & POLLIN)) continue;
    const int fd = ::accept4(listener, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) continue;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    const int number = server.add_connection(fd);
    std::thread([&server, fd, number] {
      Connection(server, fd, number).run();
      server.remove_connection(fd);
    }).detach();
  }
  ::close(listener);
  server.request_stop();
  server.wait_connections();
  // The signal thread returned after its one signal, or is still waiting
  // (the loop ended for another reason): wake it so it can be joined.
  pthread_kill(signal_thread.native_handle(), SIGTERM);
  signal_thread.join();
  ::close(wake[0]);
  ::close(wake[1]);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return serve(parse_options(argc, argv));
  } catch (const UsageError& e) {
    std::cerr << "fault_server: " << e.what() << "\n(fault_server --help for the options)\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "fault_server: " << e.what() << "\n";
    return 1;
  }
}
