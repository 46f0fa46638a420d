// HttpClient (lib/net) against a tiny HTTP/1.1 server run inside the test
// on 127.0.0.1 (an ephemeral port, a thread per connection), which records
// each request's path, headers and arrival time and answers through the
// test's handler. Covers the outcomes, retries, 429 holds, revalidation,
// the cache's freshness, cancel, priorities, the per-host cap, offline
// mode and ranges. Nothing here asserts that something was fast: the only
// timing asserted is Retry-After's lower bound.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <future>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "net/cache_policy.hpp"
#include "net/disk_cache.hpp"
#include "net/http_client.hpp"
#include "test_support.hpp"

namespace {

using namespace globe::net;
using Clock = std::chrono::steady_clock;
using globe_test::TempDir;

struct ServedRequest {
  std::string method, path;
  std::map<std::string, std::string> headers;  // lower-case names
  Clock::time_point arrived;
  int index = 0;  // how many requests for this path came before it

  std::string header(const std::string& name) const {
    const auto it = headers.find(name);
    return it == headers.end() ? "" : it->second;
  }
};

struct Reply {
  int status = 200;
  std::vector<std::pair<std::string, std::string>> headers;
  std::string body;
  // Announce more bytes than the body has, then close: a truncated body.
  long declared_length = -1;
};

// The server. The handler runs on the connection's thread and may block
// (a gate the test opens).
class TestServer {
 public:
  using Handler = std::function<Reply(const ServedRequest&)>;

  explicit TestServer(Handler handler) : handler_(std::move(handler)) {
    listen_fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    EXPECT_GE(listen_fd_, 0);
    const int one = 1;
    ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = 0;
    EXPECT_EQ(::bind(listen_fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    EXPECT_EQ(::listen(listen_fd_, 64), 0);
    socklen_t len = sizeof addr;
    ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
    acceptor_ = std::thread([this] { accept_loop(); });
  }

  ~TestServer() {
    ::shutdown(listen_fd_, SHUT_RDWR);  // wakes accept()
    acceptor_.join();
    ::close(listen_fd_);
    std::vector<std::thread> threads;
    {
      std::lock_guard lock(mu_);
      for (int fd : fds_)
        ::shutdown(fd, SHUT_RDWR);  // wakes recv()
      threads.swap(threads_);
    }
    for (std::thread& t : threads)
      t.join();
    for (int fd : fds_)
      ::close(fd);
  }

  std::string url(const std::string& path) const {
    return "http://127.0.0.1:" + std::to_string(port_) + path;
  }
  std::vector<ServedRequest> requests() const {
    std::lock_guard lock(mu_);
    return requests_;
  }
  int count(const std::string& path) const {
    std::lock_guard lock(mu_);
    return static_cast<int>(std::count_if(requests_.begin(), requests_.end(),
                                          [&](const ServedRequest& r) { return r.path == path; }));
  }
  int max_active() const { return max_active_; }
  int max_open() const { return max_open_; }

 private:
  void accept_loop() {
    for (;;) {
      const int fd = ::accept(listen_fd_, nullptr, nullptr);
      if (fd < 0) return;
      std::lock_guard lock(mu_);
      fds_.push_back(fd);
      threads_.emplace_back([this, fd] { serve(fd); });
    }
  }

  static void raise_max(std::atomic<int>& max, int value) {
    int seen = max.load();
    while (value > seen && !max.compare_exchange_weak(seen, value)) {
    }
  }

  void serve(int fd) {
    raise_max(max_open_, ++open_);
    std::string buffer;
    for (;;) {
      size_t end;
      while ((end = buffer.find("\r\n\r\n")) == std::string::npos) {
        char chunk[4096];
        const ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
        if (n <= 0) {
          --open_;
          return;
        }
        buffer.append(chunk, static_cast<size_t>(n));
      }
      ServedRequest req = parse(buffer.substr(0, end));
      buffer.erase(0, end + 4);
      req.arrived = Clock::now();
      {
        std::lock_guard lock(mu_);
        req.index = static_cast<int>(
            std::count_if(requests_.begin(), requests_.end(),
                          [&](const ServedRequest& r) { return r.path == req.path; }));
        requests_.push_back(req);
      }
      raise_max(max_active_, ++active_);
      const Reply reply = handler_(req);
      --active_;
      if (!send_reply(fd, reply) || reply.declared_length >= 0) {
        ::shutdown(fd, SHUT_RDWR);
        --open_;
        return;
      }
    }
  }

  static ServedRequest parse(const std::string& head) {
    ServedRequest r;
    std::istringstream in(head);
    std::string line;
    std::getline(in, line);
    std::istringstream first(line);
    first >> r.method >> r.path;
    while (std::getline(in, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const size_t colon = line.find(':');
      if (colon == std::string::npos) continue;
      std::string name = line.substr(0, colon);
      for (char& c : name)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      std::string value = line.substr(colon + 1);
      value.erase(0, value.find_first_not_of(' '));
      r.headers[name] = value;
    }
    return r;
  }

  static bool send_reply(int fd, const Reply& reply) {
    std::string out = "HTTP/1.1 " + std::to_string(reply.status) + " Whatever\r\n";
    for (const auto& [name, value] : reply.headers)
      out += name + ": " + value + "\r\n";
    if (reply.status != 204 && reply.status != 304) {
      const long length =
          reply.declared_length >= 0 ? reply.declared_length : static_cast<long>(reply.body.size());
      out += "Content-Length: " + std::to_string(length) + "\r\n";
    }
    out += "\r\n" + reply.body;
    size_t sent = 0;
    while (sent < out.size()) {
      const ssize_t n = ::send(fd, out.data() + sent, out.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) return false;
      sent += static_cast<size_t>(n);
    }
    return true;
  }

  Handler handler_;
  int listen_fd_ = -1;
  int port_ = 0;
  std::thread acceptor_;
  mutable std::mutex mu_;
  std::vector<int> fds_;
  std::vector<std::thread> threads_;
  std::vector<ServedRequest> requests_;
  std::atomic<int> active_{0}, max_active_{0}, open_{0}, max_open_{0};
};

Reply ok(const std::string& body, const std::string& type = "application/octet-stream",
         std::vector<std::pair<std::string, std::string>> headers = {}) {
  Reply r;
  r.body = body;
  r.headers = std::move(headers);
  r.headers.emplace_back("Content-Type", type);
  return r;
}

Reply status(int code, std::vector<std::pair<std::string, std::string>> headers = {}) {
  Reply r;
  r.status = code;
  r.headers = std::move(headers);
  return r;
}

std::string text(const std::vector<uint8_t>& body) {
  return std::string(body.begin(), body.end());
}

// Options for the tests: short backoffs, logs kept.
ClientOptions quick_options(std::vector<std::string>* log = nullptr) {
  ClientOptions o;
  o.user_agent = "globe-view/test";
  o.backoff_initial_s = 0.01;
  o.backoff_max_s = 0.05;
  o.max_retries = 3;
  if (log) o.log = [log](const std::string& line) { log->push_back(line); };
  return o;
}

Request req(const std::string& url) {
  Request r;
  r.url = url;
  return r;
}

// Waits (up to a minute: machines are noisy) until `done` holds.
bool eventually(const std::function<bool()>& done) {
  const auto until = Clock::now() + std::chrono::seconds(60);
  while (!done()) {
    if (Clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

// A gate a handler waits at until the test opens it.
class Gate {
 public:
  void wait() {
    std::unique_lock lock(mu_);
    cv_.wait(lock, [&] { return open_; });
  }
  void open() {
    std::lock_guard lock(mu_);
    open_ = true;
    cv_.notify_all();
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  bool open_ = false;
};

// Answers collected from callbacks, waited for by id.
class Answers {
 public:
  std::function<void(Response)> slot(const std::string& name) {
    return [this, name](Response r) {
      std::lock_guard lock(mu_);
      order_.push_back(name);
      got_.emplace(name, std::move(r));
      cv_.notify_all();
    };
  }
  Response wait(const std::string& name) {
    std::unique_lock lock(mu_);
    const bool came =
        cv_.wait_for(lock, std::chrono::seconds(60), [&] { return got_.count(name); });
    EXPECT_TRUE(came) << name << " never answered";
    return came ? got_.at(name) : Response{};
  }
  std::vector<std::string> order() {
    std::lock_guard lock(mu_);
    return order_;
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  std::map<std::string, Response> got_;
  std::vector<std::string> order_;
};

TEST(NetClient, OkCarriesBodyAndContentTypeAndSendsTheUserAgent) {
  TestServer server([](const ServedRequest&) { return ok("hello", "image/png"); });
  HttpClient client(quick_options());
  Request r = req(server.url("/tile.png"));
  r.accept_types = {"image/"};
  const Response got = client.get_blocking(r);
  EXPECT_EQ(got.outcome, Outcome::kOk) << got.error;
  EXPECT_EQ(got.status, 200);
  EXPECT_EQ(text(got.body), "hello");
  EXPECT_EQ(got.content_type, "image/png");
  EXPECT_EQ(got.attempts, 1);
  EXPECT_FALSE(got.from_cache);
  ASSERT_EQ(server.requests().size(), 1u);
  EXPECT_EQ(server.requests()[0].header("user-agent"), "globe-view/test");
  EXPECT_EQ(client.stats().requests, 1u);
  EXPECT_EQ(client.stats().bytes, 5u);
  EXPECT_EQ(client.stats().in_flight, 0);
}

TEST(NetClient, NotFoundIsAskedOnceThenRemembered) {
  TestServer server([](const ServedRequest&) { return status(404); });
  HttpClient client(quick_options());
  const Response first = client.get_blocking(req(server.url("/missing")));
  EXPECT_EQ(first.outcome, Outcome::kNoContent);
  EXPECT_EQ(first.status, 404);
  EXPECT_EQ(first.attempts, 1);
  const Response second = client.get_blocking(req(server.url("/missing")));
  EXPECT_EQ(second.outcome, Outcome::kNoContent);
  EXPECT_EQ(second.attempts, 0);
  EXPECT_EQ(server.count("/missing"), 1);
  EXPECT_EQ(client.stats().no_content, 2u);
}

TEST(NetClient, NoContentIsNoContentAndRemembered) {
  TestServer server([](const ServedRequest&) { return status(204); });
  HttpClient client(quick_options());
  EXPECT_EQ(client.get_blocking(req(server.url("/empty"))).outcome, Outcome::kNoContent);
  EXPECT_EQ(client.get_blocking(req(server.url("/empty"))).outcome, Outcome::kNoContent);
  EXPECT_EQ(server.count("/empty"), 1);
}

TEST(NetClient, ServerErrorIsRetried) {
  TestServer server([](const ServedRequest& r) { return r.index == 0 ? status(500) : ok("fine"); });
  HttpClient client(quick_options());
  const Response got = client.get_blocking(req(server.url("/flaky")));
  EXPECT_EQ(got.outcome, Outcome::kOk) << got.error;
  EXPECT_EQ(text(got.body), "fine");
  EXPECT_EQ(got.attempts, 2);
  EXPECT_EQ(server.count("/flaky"), 2);
  EXPECT_EQ(client.stats().retries, 1u);
  EXPECT_EQ(client.stats().requests, 2u);
}

TEST(NetClient, ServerErrorsUntilTheRetriesAreSpentFail) {
  TestServer server([](const ServedRequest&) { return status(503); });
  ClientOptions o = quick_options();
  o.max_retries = 2;
  HttpClient client(o);
  const Response got = client.get_blocking(req(server.url("/down")));
  EXPECT_EQ(got.outcome, Outcome::kFailed);
  EXPECT_EQ(got.status, 503);
  EXPECT_EQ(got.attempts, 3);
  EXPECT_NE(got.error.find(server.url("/down")), std::string::npos) << got.error;
  EXPECT_EQ(server.count("/down"), 3);
  EXPECT_EQ(client.stats().failed, 1u);
}

TEST(NetClient, OtherClientErrorsFailWithoutRetry) {
  TestServer server([](const ServedRequest&) { return status(403); });
  HttpClient client(quick_options());
  const Response got = client.get_blocking(req(server.url("/secret")));
  EXPECT_EQ(got.outcome, Outcome::kFailed);
  EXPECT_EQ(got.status, 403);
  EXPECT_EQ(server.count("/secret"), 1);
}

TEST(NetClient, TooManyRequestsHoldsTheHostForRetryAfter) {
  TestServer server([](const ServedRequest& r) {
    if (r.path == "/a" && r.index == 0) return status(429, {{"Retry-After", "1"}});
    return ok("ok " + r.path);
  });
  ClientOptions o = quick_options();
  o.max_connections_per_host = 1;  // /b waits behind /a, then behind the hold
  std::vector<std::string> log;
  o.log = [&log](const std::string& line) { log.push_back(line); };
  HttpClient client(o);
  Answers answers;
  client.get(req(server.url("/a")), answers.slot("a"));
  client.get(req(server.url("/b")), answers.slot("b"));
  const Response a = answers.wait("a"), b = answers.wait("b");
  EXPECT_EQ(a.outcome, Outcome::kOk) << a.error;
  EXPECT_EQ(a.attempts, 2);
  EXPECT_EQ(b.outcome, Outcome::kOk) << b.error;
  const auto served = server.requests();
  ASSERT_EQ(served.size(), 3u);
  EXPECT_EQ(served[0].path, "/a");
  for (size_t i = 1; i < served.size(); ++i)
    EXPECT_GE(served[i].arrived - served[0].arrived, std::chrono::seconds(1))
        << served[i].path << " came before Retry-After had passed";
  EXPECT_EQ(client.stats().retries, 1u);
  EXPECT_EQ(log.size(), 1u);  // the host asked to wait: said once
}

TEST(NetClient, StaleEntryIsRevalidatedWithItsETag) {
  TempDir dir;
  TestServer server([](const ServedRequest& r) {
    if (r.header("if-none-match") == "\"v1\"")
      return status(304, {{"ETag", "\"v1\""}, {"Cache-Control", "no-cache"}});
    return ok("tile v1", "image/png", {{"ETag", "\"v1\""}, {"Cache-Control", "no-cache"}});
  });
  ClientOptions o = quick_options();
  o.cache_dir = dir.path().string();
  HttpClient client(o);
  const Response first = client.get_blocking(req(server.url("/t")));
  EXPECT_EQ(first.outcome, Outcome::kOk);
  EXPECT_EQ(first.etag, "\"v1\"");
  EXPECT_FALSE(first.from_cache);
  const Response second = client.get_blocking(req(server.url("/t")));
  EXPECT_EQ(second.outcome, Outcome::kOk) << second.error;
  EXPECT_TRUE(second.from_cache);
  EXPECT_TRUE(second.revalidated);
  EXPECT_EQ(second.status, 304);
  EXPECT_EQ(second.attempts, 1);
  EXPECT_EQ(text(second.body), "tile v1");
  EXPECT_EQ(second.content_type, "image/png");
  ASSERT_EQ(server.count("/t"), 2);
  EXPECT_EQ(server.requests()[0].header("if-none-match"), "");
  EXPECT_EQ(server.requests()[1].header("if-none-match"), "\"v1\"");
  EXPECT_EQ(client.stats().revalidated, 1u);
  EXPECT_EQ(client.stats().cache_hits, 1u);
}

TEST(NetClient, LastModifiedIsRevalidatedWithIfModifiedSince) {
  TempDir dir;
  const std::string stamp = "Tue, 15 Nov 1994 12:45:26 GMT";
  TestServer server([&](const ServedRequest& r) {
    if (r.header("if-modified-since") == stamp) return status(304);
    return ok("old", "application/octet-stream", {{"Last-Modified", stamp}});
  });
  ClientOptions o = quick_options();
  o.cache_dir = dir.path().string();
  HttpClient client(o);
  EXPECT_FALSE(client.get_blocking(req(server.url("/lm"))).from_cache);
  const Response second = client.get_blocking(req(server.url("/lm")));
  EXPECT_TRUE(second.revalidated);
  EXPECT_EQ(text(second.body), "old");
}

TEST(NetClient, FreshEntryIsAnsweredWithoutARequest) {
  TempDir dir;
  TestServer server([](const ServedRequest&) {
    return ok("fresh", "application/json", {{"Cache-Control", "public, max-age=60"}});
  });
  ClientOptions o = quick_options();
  o.cache_dir = dir.path().string();
  HttpClient client(o);
  EXPECT_EQ(client.get_blocking(req(server.url("/tiles.json"))).outcome, Outcome::kOk);
  const Response second = client.get_blocking(req(server.url("/tiles.json")));
  EXPECT_EQ(second.outcome, Outcome::kOk);
  EXPECT_TRUE(second.from_cache);
  EXPECT_FALSE(second.revalidated);
  EXPECT_EQ(second.attempts, 0);
  EXPECT_EQ(text(second.body), "fresh");
  EXPECT_EQ(second.content_type, "application/json");
  EXPECT_EQ(server.count("/tiles.json"), 1);
}

TEST(NetClient, NoStoreIsNotCached) {
  TempDir dir;
  TestServer server([](const ServedRequest&) {
    return ok("private", "application/octet-stream", {{"Cache-Control", "no-store, max-age=60"}});
  });
  ClientOptions o = quick_options();
  o.cache_dir = dir.path().string();
  HttpClient client(o);
  EXPECT_EQ(client.get_blocking(req(server.url("/p"))).outcome, Outcome::kOk);
  const Response second = client.get_blocking(req(server.url("/p")));
  EXPECT_FALSE(second.from_cache);
  EXPECT_EQ(server.count("/p"), 2);
  EXPECT_EQ(DiskCache(o.cache_dir, o.cache_max_bytes).entries(), 0u);
}

TEST(NetClient, UseCacheFalseNeitherReadsNorWrites) {
  TempDir dir;
  TestServer server([](const ServedRequest&) {
    return ok("x", "application/octet-stream", {{"Cache-Control", "max-age=60"}});
  });
  ClientOptions o = quick_options();
  o.cache_dir = dir.path().string();
  HttpClient client(o);
  Request r = req(server.url("/header"));
  r.use_cache = false;
  client.get_blocking(r);
  client.get_blocking(r);
  EXPECT_EQ(server.count("/header"), 2);
  EXPECT_EQ(DiskCache(o.cache_dir, o.cache_max_bytes).entries(), 0u);
}

TEST(NetClient, WrongContentTypeIsBrokenNotCachedAndReportedOnce) {
  TempDir dir;
  TestServer server([](const ServedRequest&) {
    return ok("<html>", "text/html; charset=utf-8", {{"Cache-Control", "max-age=60"}});
  });
  std::vector<std::string> log;
  ClientOptions o = quick_options(&log);
  o.cache_dir = dir.path().string();
  HttpClient client(o);
  Request r = req(server.url("/tile.webp"));
  r.accept_types = {"image/", "application/octet-stream"};
  const Response first = client.get_blocking(r);
  EXPECT_EQ(first.outcome, Outcome::kBroken);
  EXPECT_NE(first.error.find("text/html"), std::string::npos) << first.error;
  EXPECT_EQ(first.attempts, 1);  // not retried
  EXPECT_EQ(client.get_blocking(r).outcome, Outcome::kBroken);
  EXPECT_EQ(server.count("/tile.webp"), 2);  // not cached
  EXPECT_EQ(log.size(), 1u);
  EXPECT_EQ(client.stats().broken, 2u);
}

TEST(NetClient, ValidateRejectsABody) {
  TestServer server([](const ServedRequest&) { return ok("garbage", "image/png"); });
  HttpClient client(quick_options());
  Request r = req(server.url("/bad.png"));
  r.validate = [](const std::vector<uint8_t>& body, const std::string& type) {
    return type == "image/png" && body.size() > 100 ? "" : "not a PNG";
  };
  const Response got = client.get_blocking(r);
  EXPECT_EQ(got.outcome, Outcome::kBroken);
  EXPECT_NE(got.error.find("not a PNG"), std::string::npos);
}

TEST(NetClient, TruncatedBodyIsRetriedThenFails) {
  TestServer server([](const ServedRequest&) {
    Reply r = ok(std::string(50, 'x'));
    r.declared_length = 100;
    return r;
  });
  ClientOptions o = quick_options();
  o.max_retries = 2;
  HttpClient client(o);
  const Response got = client.get_blocking(req(server.url("/short")));
  EXPECT_EQ(got.outcome, Outcome::kFailed);
  EXPECT_EQ(got.attempts, 3);
  EXPECT_EQ(server.count("/short"), 3);
  EXPECT_EQ(client.stats().retries, 2u);
}

TEST(NetClient, TruncatedOnceThenWhole) {
  TestServer server([](const ServedRequest& r) {
    Reply reply = ok(std::string(r.index == 0 ? 10 : 100, 'y'));
    if (r.index == 0) reply.declared_length = 100;
    return reply;
  });
  HttpClient client(quick_options());
  const Response got = client.get_blocking(req(server.url("/once")));
  EXPECT_EQ(got.outcome, Outcome::kOk) << got.error;
  EXPECT_EQ(got.body.size(), 100u);
  EXPECT_EQ(got.attempts, 2);
}

TEST(NetClient, RefusedConnectionFailsAfterRetries) {
  int port = 0;
  {
    TestServer gone([](const ServedRequest&) { return ok(""); });
    port = std::stoi(gone.url("").substr(std::string("http://127.0.0.1:").size()));
  }
  ClientOptions o = quick_options();
  o.max_retries = 1;
  HttpClient client(o);
  const Response got =
      client.get_blocking(req("http://127.0.0.1:" + std::to_string(port) + "/nobody"));
  EXPECT_EQ(got.outcome, Outcome::kFailed);
  EXPECT_EQ(got.attempts, 2);
  EXPECT_EQ(got.status, 0);
}

TEST(NetClient, CancelOfAQueuedRequest) {
  Gate gate;
  TestServer server([&](const ServedRequest& r) {
    if (r.path == "/busy") gate.wait();
    return ok("done");
  });
  ClientOptions o = quick_options();
  o.max_connections_per_host = 1;
  HttpClient client(o);
  Answers answers;
  client.get(req(server.url("/busy")), answers.slot("busy"));
  ASSERT_TRUE(eventually([&] { return server.count("/busy") == 1; }));
  const RequestId queued = client.get(req(server.url("/queued")), answers.slot("queued"));
  client.cancel(queued);
  const Response cancelled = answers.wait("queued");
  EXPECT_EQ(cancelled.outcome, Outcome::kCancelled);
  EXPECT_EQ(cancelled.attempts, 0);
  gate.open();
  EXPECT_EQ(answers.wait("busy").outcome, Outcome::kOk);
  client.cancel(queued);  // answered already: no effect
  EXPECT_EQ(server.count("/queued"), 0);
  EXPECT_EQ(client.stats().cancelled, 1u);
  EXPECT_EQ(client.stats().in_flight, 0);
}

TEST(NetClient, CancelOfARunningRequest) {
  Gate gate;
  TestServer server([&](const ServedRequest&) {
    gate.wait();
    return ok("late");
  });
  HttpClient client(quick_options());
  Answers answers;
  const RequestId id = client.get(req(server.url("/slow")), answers.slot("slow"));
  ASSERT_TRUE(eventually([&] { return server.count("/slow") == 1; }));
  client.cancel(id);
  EXPECT_EQ(answers.wait("slow").outcome, Outcome::kCancelled);
  gate.open();
}

TEST(NetClient, QueuedRequestsGoHighestPriorityFirst) {
  Gate gate;
  TestServer server([&](const ServedRequest& r) {
    if (r.path == "/gate") gate.wait();
    return ok(r.path);
  });
  ClientOptions o = quick_options();
  o.max_connections_per_host = 1;
  HttpClient client(o);
  Answers answers;
  Request first = req(server.url("/gate"));
  first.priority = 100;
  client.get(first, answers.slot("/gate"));
  ASSERT_TRUE(eventually([&] { return server.count("/gate") == 1; }));
  const std::vector<std::pair<std::string, double>> wanted = {{"/p1", 1},  {"/p5", 5}, {"/p3", 3},
                                                              {"/p5b", 5}, {"/p0", 0}, {"/p9", 0}};
  std::map<std::string, RequestId> ids;
  for (const auto& [path, priority] : wanted) {
    Request r = req(server.url(path));
    r.priority = priority;
    ids[path] = client.get(r, answers.slot(path));
  }
  client.set_priority(ids["/p9"], 9);  // moved to the front of the queue
  gate.open();
  for (const auto& [path, priority] : wanted)
    EXPECT_EQ(answers.wait(path).outcome, Outcome::kOk);
  std::vector<std::string> order;
  for (const ServedRequest& r : server.requests())
    order.push_back(r.path);
  EXPECT_EQ(order, (std::vector<std::string>{"/gate", "/p9", "/p5", "/p5b", "/p3", "/p1", "/p0"}));
}

TEST(NetClient, PerHostCapHolds) {
  TestServer server([](const ServedRequest& r) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return ok(r.path);
  });
  ClientOptions o = quick_options();
  o.max_connections_per_host = 2;
  HttpClient client(o);
  Answers answers;
  for (int i = 0; i < 10; ++i) {
    const std::string path = "/c" + std::to_string(i);
    client.get(req(server.url(path)), answers.slot(path));
  }
  for (int i = 0; i < 10; ++i)
    EXPECT_EQ(answers.wait("/c" + std::to_string(i)).outcome, Outcome::kOk);
  EXPECT_GE(server.max_active(), 1);
  EXPECT_LE(server.max_active(), 2);
  EXPECT_LE(server.max_open(), 2);
}

TEST(NetClient, OfflineAnswersFromTheCacheOnly) {
  TempDir dir;
  TestServer server([](const ServedRequest&) { return ok("cached", "image/png"); });
  ClientOptions o = quick_options();
  o.cache_dir = dir.path().string();
  {
    HttpClient online(o);
    // No freshness headers: stale at once, but kept for offline use.
    EXPECT_EQ(online.get_blocking(req(server.url("/have"))).outcome, Outcome::kOk);
  }
  o.offline = true;
  HttpClient offline(o);
  const Response hit = offline.get_blocking(req(server.url("/have")));
  EXPECT_EQ(hit.outcome, Outcome::kOk);
  EXPECT_TRUE(hit.from_cache);
  EXPECT_EQ(text(hit.body), "cached");
  const Response miss = offline.get_blocking(req(server.url("/lack")));
  EXPECT_EQ(miss.outcome, Outcome::kOffline);
  EXPECT_NE(miss.error.find("/lack"), std::string::npos);
  EXPECT_EQ(server.requests().size(), 1u);
  EXPECT_EQ(offline.stats().requests, 0u);
}

TEST(NetClient, RangeRequestsHaveTheirOwnCacheEntry) {
  TempDir dir;
  const std::string whole = "0123456789";
  TestServer server([&](const ServedRequest& r) {
    std::vector<std::pair<std::string, std::string>> headers = {{"Cache-Control", "max-age=60"}};
    if (r.header("range") == "bytes=2-5") {
      Reply reply = ok(whole.substr(2, 4), "application/octet-stream", headers);
      reply.status = 206;
      reply.headers.emplace_back("Content-Range", "bytes 2-5/10");
      return reply;
    }
    return ok(whole, "application/octet-stream", headers);
  });
  ClientOptions o = quick_options();
  o.cache_dir = dir.path().string();
  HttpClient client(o);
  Request part = req(server.url("/archive.pmtiles"));
  part.range = "bytes=2-5";
  const Response got = client.get_blocking(part);
  EXPECT_EQ(got.outcome, Outcome::kOk) << got.error;
  EXPECT_EQ(got.status, 206);
  EXPECT_EQ(text(got.body), "2345");
  ASSERT_EQ(server.requests().size(), 1u);
  EXPECT_EQ(server.requests()[0].header("range"), "bytes=2-5");
  // The whole body is another entry; the range is then answered by the cache.
  const Response all = client.get_blocking(req(server.url("/archive.pmtiles")));
  EXPECT_EQ(text(all.body), whole);
  EXPECT_FALSE(all.from_cache);
  const Response again = client.get_blocking(part);
  EXPECT_TRUE(again.from_cache);
  EXPECT_EQ(text(again.body), "2345");
  EXPECT_EQ(server.requests().size(), 2u);
  DiskCache cache(o.cache_dir, o.cache_max_bytes);
  EXPECT_TRUE(cache.find(server.url("/archive.pmtiles") + "#range=2-5").has_value());
  EXPECT_EQ(cache_key(server.url("/a"), "bytes=2-5"), server.url("/a") + "#range=2-5");
}

TEST(NetClient, RangeIgnoredByTheServerIsCut) {
  TestServer server([](const ServedRequest&) { return ok("0123456789"); });
  HttpClient client(quick_options());
  Request part = req(server.url("/whole"));
  part.range = "bytes=7-";
  const Response got = client.get_blocking(part);
  EXPECT_EQ(got.outcome, Outcome::kOk) << got.error;
  EXPECT_EQ(text(got.body), "789");
}

TEST(NetClient, CallbacksMayCallTheClient) {
  TestServer server([](const ServedRequest& r) { return ok(r.path); });
  HttpClient client(quick_options());
  std::promise<Response> second;
  client.get(req(server.url("/one")), [&](Response first) {
    EXPECT_EQ(first.outcome, Outcome::kOk);
    EXPECT_THROW(client.get_blocking(req(server.url("/x"))), NetError);
    client.get(req(server.url("/two")), [&](Response r) { second.set_value(std::move(r)); });
  });
  EXPECT_EQ(text(second.get_future().get().body), "/two");
}

TEST(NetClient, DestructionCancelsEverything) {
  Gate gate;
  TestServer server([&](const ServedRequest&) {
    gate.wait();
    return ok("never seen");
  });
  Answers answers;
  {
    ClientOptions o = quick_options();
    o.max_connections_per_host = 1;
    HttpClient client(o);
    client.get(req(server.url("/running")), answers.slot("running"));
    ASSERT_TRUE(eventually([&] { return server.count("/running") == 1; }));
    client.get(req(server.url("/queued")), answers.slot("queued"));
  }
  EXPECT_EQ(answers.order().size(), 2u);
  EXPECT_EQ(answers.wait("running").outcome, Outcome::kCancelled);
  EXPECT_EQ(answers.wait("queued").outcome, Outcome::kCancelled);
  gate.open();
}

TEST(NetClient, OutcomeNames) {
  EXPECT_STREQ(to_string(Outcome::kOk), "ok");
  EXPECT_STREQ(to_string(Outcome::kOffline), "offline");
}

}  // namespace
