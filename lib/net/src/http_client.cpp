// HttpClient (net/http_client.hpp): the scheduling and the policy. One
// thread owns every request's state: other threads only append commands
// (get, cancel, set_priority) to an inbox under a mutex and wake the thread
// through curl_multi_wakeup. Each turn of the loop takes the finished
// transfers, the inbox and the due timers, then starts the highest-priority
// queued requests whose host is under its cap and not held by a 429, then
// calls the callbacks with no lock held. Touches the network through
// CurlMulti (curl_multi.cpp) and the disk through DiskCache
// (disk_cache.cpp), nothing else.
#include "net/http_client.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <set>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include "curl_multi.hpp"
#include "net/cache_policy.hpp"
#include "net/disk_cache.hpp"

namespace globe::net {

const char* to_string(Outcome o) {
  switch (o) {
    case Outcome::kOk:
      return "ok";
    case Outcome::kNoContent:
      return "no content";
    case Outcome::kBroken:
      return "broken";
    case Outcome::kFailed:
      return "failed";
    case Outcome::kCancelled:
      return "cancelled";
    case Outcome::kOffline:
      return "offline";
  }
  return "unknown";
}

namespace {

using Clock = std::chrono::steady_clock;

// The backoff's jitter is drawn from a generator seeded with a constant:
// two runs of one scenario wait the same.
constexpr uint32_t kBackoffSeed = 0x676c6f62;  // "glob"

int64_t unix_now() {
  return std::chrono::duration_cast<std::chrono::seconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// "scheme://host:port" of a URL, lower case, the port made explicit: the
// unit of the per-host cap and of 429 holds.
std::string host_key(const std::string& url) {
  const size_t scheme_end = url.find("://");
  if (scheme_end == std::string::npos) return url;
  std::string scheme = url.substr(0, scheme_end);
  const size_t start = scheme_end + 3;
  const size_t end = url.find_first_of("/?#", start);
  std::string authority = url.substr(start, end == std::string::npos ? end : end - start);
  if (const size_t at = authority.rfind('@'); at != std::string::npos)
    authority = authority.substr(at + 1);
  std::string out = scheme + "://" + authority;
  for (char& c : out)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const size_t bracket = authority.rfind(']');  // an IPv6 literal's colons are not a port's
  const size_t colon = authority.rfind(':');
  const bool has_port =
      colon != std::string::npos && (bracket == std::string::npos || colon > bracket);
  if (!has_port) out += scheme == "https" ? ":443" : ":80";
  return out;
}

// The part of a whole body that a range "bytes=A-B" / "bytes=A-" /
// "bytes=-N" asks for, for a server that answered 200 to a range request;
// nullopt if the range cannot be read or lies outside the body.
std::optional<std::vector<uint8_t>> slice_for_range(const std::string& range,
                                                    const std::vector<uint8_t>& body) {
  std::string r = range;
  if (r.starts_with("bytes=")) r = r.substr(6);
  const size_t dash = r.find('-');
  if (dash == std::string::npos || r.find(',') != std::string::npos) return std::nullopt;
  const auto number = [](const std::string& s) -> std::optional<uint64_t> {
    if (s.empty() || s.size() > 18 || s.find_first_not_of("0123456789") != std::string::npos)
      return std::nullopt;
    return std::stoull(s);
  };
  const auto a = number(r.substr(0, dash)), b = number(r.substr(dash + 1));
  const uint64_t size = body.size();
  uint64_t first = 0, last = 0;
  if (a) {
    first = *a;
    last = b ? std::min(*b, size - 1) : size - 1;
  } else if (b && *b > 0) {
    first = size - std::min(*b, size);
    last = size - 1;
  } else {
    return std::nullopt;
  }
  if (size == 0 || first >= size || last < first) return std::nullopt;
  return std::vector<uint8_t>(body.begin() + static_cast<ptrdiff_t>(first),
                              body.begin() + static_cast<ptrdiff_t>(last + 1));
}

}  // namespace

struct HttpClient::Impl {
  enum class State { kQueued, kWaiting, kRunning };
  struct Job {
    RequestId id = 0;
    Request request;
    std::function<void(Response)> done;
    std::string key, host;
    State state = State::kQueued;
    int attempts = 0;
    int last_status = 0;
    std::optional<CacheEntry> stale;  // the cached answer a 304 would confirm
    Clock::time_point wake;           // kWaiting: when it goes back to the queue
  };
  struct Command {
    enum class Kind { kGet, kCancel, kPriority } kind = Kind::kGet;
    RequestId id = 0;
    double priority = 0;
    Request request;
    std::function<void(Response)> done;
  };
  struct Answer {
    std::function<void(Response)> done;
    Response response;
  };
  // Counters any thread reads.
  struct Counters {
    std::atomic<uint64_t> requests{0}, bytes{0}, cache_hits{0}, revalidated{0}, retries{0},
        no_content{0}, broken{0}, failed{0}, cancelled{0};
    std::atomic<int> in_flight{0};
  };

  ClientOptions options;
  std::unique_ptr<DiskCache> cache;
  detail::CurlMulti curl;
  Counters counters;
  std::atomic<RequestId> next_id{1};

  // Shared with the other threads, under `mu`.
  std::mutex mu;
  std::vector<Command> inbox;
  bool stopping = false;
  bool finished = false;  // the thread has answered everything and ended

  // The client thread's alone.
  std::unordered_map<RequestId, Job> jobs;
  std::set<std::pair<double, RequestId>> queue;  // (-priority, id): highest first, then oldest
  std::multimap<Clock::time_point, RequestId> timers;
  std::unordered_map<std::string, Clock::time_point> held_until;  // hosts that sent a 429
  std::unordered_map<std::string, int> running_per_host;
  int running = 0;
  std::unordered_map<std::string, int> no_content;  // cache key -> the 404 / 410 / 204 it got
  std::unordered_set<std::string> reported_broken;
  std::mt19937 rng{kBackoffSeed};
  std::vector<Answer> answers;

  std::thread thread;  // last: started when the rest is ready

  explicit Impl(ClientOptions o)
      : options(std::move(o)),
        cache(options.cache_dir.empty()
                  ? nullptr
                  : std::make_unique<DiskCache>(options.cache_dir, options.cache_max_bytes)),
        curl(detail::CurlSettings{options.user_agent, options.max_connections_per_host,
                                  options.max_connections, options.connect_timeout_s,
                                  options.transfer_timeout_s, options.low_speed_bytes_per_s,
                                  options.low_speed_time_s}) {}

  // ----- the loop -----

  void run() {
    for (;;) {
      std::vector<detail::TransferResult> results;
      try {
        results = curl.perform();
      } catch (const NetError& e) {
        log(e.what());
      }
      for (detail::TransferResult& r : results)
        on_result(r);
      // After the results: a command sent before a transfer ended is seen in
      // the same turn as its end (the queue is whole when a slot frees).
      std::vector<Command> commands;
      bool stop = false;
      {
        std::lock_guard lock(mu);
        commands.swap(inbox);
        stop = stopping;
      }
      for (Command& c : commands)
        apply(c, stop);
      if (stop) {
        cancel_everything();
        deliver();
        std::lock_guard lock(mu);
        if (inbox.empty()) {
          finished = true;
          return;
        }
        continue;  // a callback asked for more: cancelled on the next turn
      }
      const Clock::time_point now = Clock::now();
      fire_timers(now);
      dispatch(now);
      deliver();
      try {
        curl.wait(wait_ms(Clock::now()));
      } catch (const NetError& e) {
        log(e.what());
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
  }

  int wait_ms(Clock::time_point now) const {
    Clock::duration wait = std::chrono::seconds(1);  // a safety tick
    if (!timers.empty()) wait = std::min(wait, timers.begin()->first - now);
    for (const auto& [host, until] : held_until)
      if (until > now) wait = std::min(wait, until - now);
    const auto ms = std::chrono::ceil<std::chrono::milliseconds>(wait).count();
    return static_cast<int>(std::max<int64_t>(0, ms));
  }

  // While stopping, a get is cancelled without a look at the cache.
  void apply(Command& c, bool stopping_now) {
    switch (c.kind) {
      case Command::Kind::kGet:
        if (stopping_now) {
          Job& job = jobs[c.id];
          job.id = c.id;
          job.done = std::move(c.done);
          Response r;
          r.outcome = Outcome::kCancelled;
          finish(job, std::move(r));
        } else {
          admit(c.id, std::move(c.request), std::move(c.done));
        }
        break;
      case Command::Kind::kCancel:
        cancel_job(c.id);
        break;
      case Command::Kind::kPriority:
        reprioritize(c.id, c.priority);
        break;
    }
  }

  // ----- a new request: remembered answers, the cache, else the queue -----

  void admit(RequestId id, Request request, std::function<void(Response)> done) {
    Job& job = jobs[id];
    job.id = id;
    job.key = cache_key(request.url, request.range);
    job.host = host_key(request.url);
    job.request = std::move(request);
    job.done = std::move(done);
    if (std::isnan(job.request.priority)) job.request.priority = 0;

    if (const auto it = no_content.find(job.key); it != no_content.end()) {
      job.last_status = it->second;
      answer_no_content(job);
      return;
    }
    const bool cached = cache && job.request.use_cache;
    std::optional<CacheEntry> entry;
    if (cached) {
      try {
        entry = cache->find(job.key);
      } catch (const NetError& e) {
        log(e.what());
      }
      if (entry && !content_type_accepted(entry->content_type, job.request.accept_types))
        entry.reset();  // stored for a request that accepted another type
    }
    if (options.offline) {
      if (entry) {
        answer_from_cache(job, std::move(*entry), false);
      } else {
        Response r;
        r.outcome = Outcome::kOffline;
        r.error = job.request.url + ": offline and not in the cache";
        finish(job, std::move(r));
      }
      return;
    }
    if (entry && entry->expires_at > unix_now()) {
      answer_from_cache(job, std::move(*entry), false);
      return;
    }
    if (entry && (!entry->etag.empty() || !entry->last_modified.empty()))
      job.stale = std::move(entry);
    enqueue(job);
  }

  void enqueue(Job& job) {
    job.state = State::kQueued;
    queue.emplace(-job.request.priority, job.id);
  }

  // ----- starting transfers -----

  bool host_held(const std::string& host, Clock::time_point now) {
    const auto it = held_until.find(host);
    if (it == held_until.end()) return false;
    if (it->second <= now) {
      held_until.erase(it);
      return false;
    }
    return true;
  }

  void dispatch(Clock::time_point now) {
    const int per_host = std::max(1, options.max_connections_per_host);
    const int total = std::max(1, options.max_connections);
    for (auto it = queue.begin(); it != queue.end() && running < total;) {
      Job& job = jobs.at(it->second);
      if (running_per_host[job.host] >= per_host || host_held(job.host, now)) {
        ++it;
        continue;
      }
      it = queue.erase(it);
      // Answered 404/204 while this one waited in the queue: no request.
      if (const auto known = no_content.find(job.key); known != no_content.end()) {
        job.last_status = known->second;
        answer_no_content(job);
        continue;
      }
      start(job);
    }
  }

  void start(Job& job) {
    detail::TransferSpec spec;
    spec.url = job.request.url;
    if (!job.request.range.empty()) {
      const std::string& r = job.request.range;
      spec.headers.push_back("Range: " + (r.starts_with("bytes=") ? r : "bytes=" + r));
      spec.compressed = false;
    }
    if (job.stale) {
      if (!job.stale->etag.empty()) spec.headers.push_back("If-None-Match: " + job.stale->etag);
      if (!job.stale->last_modified.empty())
        spec.headers.push_back("If-Modified-Since: " + job.stale->last_modified);
    }
    try {
      curl.start(job.id, spec);
    } catch (const NetError& e) {
      fail(job, e.what());
      return;
    }
    job.state = State::kRunning;
    ++job.attempts;
    ++counters.requests;
    if (job.attempts > 1) ++counters.retries;
    ++running;
    ++running_per_host[job.host];
  }

  void stopped_running(const Job& job) {
    --running;
    if (--running_per_host[job.host] <= 0) running_per_host.erase(job.host);
  }

  // ----- finished transfers -----

  void on_result(detail::TransferResult& r) {
    const auto it = jobs.find(r.token);
    if (it == jobs.end() || it->second.state != State::kRunning) return;
    Job& job = it->second;
    stopped_running(job);
    counters.bytes += r.bytes_received;
    if (r.status != 0) job.last_status = r.status;
    const std::string& url = job.request.url;
    switch (r.failure) {
      case detail::TransferFailure::kRetryable:
        retry(job, url + ": " + r.error);
        return;
      case detail::TransferFailure::kPermanent:
        fail(job, url + ": " + r.error);
        return;
      case detail::TransferFailure::kNone:
        break;
    }
    const int s = r.status;
    const std::string status = "HTTP " + std::to_string(s);
    if (s == 304) {
      if (job.stale) {
        revalidated(job, r);
      } else {
        fail(job, url + ": " + status + " to a request that was not conditional");
      }
    } else if (s == 204 || s == 404 || s == 410) {
      no_content.emplace(job.key, s);
      if (job.stale) erase_cached(job.key);
      answer_no_content(job);
    } else if (s >= 200 && s < 300) {
      answer_body(job, r);
    } else if (s == 429 || (s == 503 && !r.header("retry-after").empty())) {
      const auto wait = retry_after_s(r.header("retry-after"), unix_now());
      retry_after_hold(job, url + ": " + status, wait ? *wait : backoff_s(job.attempts));
    } else if (s >= 500 || s == 408) {
      retry(job, url + ": " + status);
    } else {
      fail(job, url + ": " + status);
    }
  }

  void answer_body(Job& job, detail::TransferResult& r) {
    const std::string& url = job.request.url;
    std::vector<uint8_t> body = std::move(r.body);
    if (!job.request.range.empty() && r.status != 206) {
      // The server ignored the range and sent the whole body: cut it.
      auto part = slice_for_range(job.request.range, body);
      if (!part) {
        broken(job, url + ": the server ignored the range " + job.request.range + " and sent " +
                        std::to_string(body.size()) + " bytes");
        return;
      }
      body = std::move(*part);
    }
    const std::string type = r.header("content-type");
    if (!content_type_accepted(type, job.request.accept_types)) {
      broken(job, url + ": content type '" + type + "' is not one asked for");
      return;
    }
    if (job.request.validate) {
      std::string why;
      try {
        why = job.request.validate(body, type);
      } catch (const std::exception& e) {
        why = e.what();
      }
      if (!why.empty()) {
        broken(job, url + ": " + why);
        return;
      }
    }
    const std::string cache_control = r.header("cache-control");
    const int64_t now = unix_now();
    if (cache && job.request.use_cache) {
      if (parse_cache_control(cache_control).no_store) {
        if (job.stale) erase_cached(job.key);
      } else {
        CacheEntry entry;
        entry.body = body;
        entry.content_type = type;
        entry.etag = r.header("etag");
        entry.last_modified = r.header("last-modified");
        entry.stored_at = now;
        entry.expires_at = expires_at(
            {cache_control, r.header("expires"), r.header("date"), r.header("age")}, now);
        try {
          cache->put(job.key, entry);
        } catch (const NetError& e) {
          log(e.what());
        }
      }
    }
    Response out;
    out.outcome = Outcome::kOk;
    out.body = std::move(body);
    out.content_type = type;
    out.etag = r.header("etag");
    finish(job, std::move(out));
  }

  void revalidated(Job& job, const detail::TransferResult& r) {
    CacheEntry entry = std::move(*job.stale);
    job.stale.reset();
    const std::string etag = r.header("etag"), last_modified = r.header("last-modified");
    if (!etag.empty()) entry.etag = etag;
    if (!last_modified.empty()) entry.last_modified = last_modified;
    const int64_t now = unix_now();
    entry.expires_at = expires_at(
        {r.header("cache-control"), r.header("expires"), r.header("date"), r.header("age")}, now);
    try {
      cache->refresh(job.key, entry.expires_at, etag, last_modified);
    } catch (const NetError& e) {
      log(e.what());
    }
    answer_from_cache(job, std::move(entry), true);
  }

  void erase_cached(const std::string& key) {
    try {
      cache->erase(key);
    } catch (const NetError& e) {
      log(e.what());
    }
  }

  // ----- retries -----

  // Full jitter: uniform in [0, min(max, initial * 2^(n-1))] before retry n.
  double backoff_s(int attempts_made) {
    const double base = std::max(0.0, options.backoff_initial_s);
    const double cap = std::max(0.0, options.backoff_max_s);
    const double top = std::min(cap, base * std::ldexp(1.0, std::min(attempts_made, 60) - 1));
    return std::uniform_real_distribution<double>(0.0, top)(rng);
  }

  // Another attempt after the backoff; kFailed once the retries are spent.
  void retry(Job& job, const std::string& why) {
    if (retries_spent(job, why)) return;
    job.state = State::kWaiting;
    job.wake = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                  std::chrono::duration<double>(backoff_s(job.attempts)));
    timers.emplace(job.wake, job.id);
  }

  // A 429: no request to the job's host for `wait_s`, then the job again.
  // The host is held even when the job has no retry left: the server asked
  // for no request from this client, whichever job it answered.
  void retry_after_hold(Job& job, const std::string& why, double wait_s) {
    const Clock::time_point now = Clock::now();
    wait_s = std::clamp(wait_s, 0.0, 24.0 * 3600);
    const auto until =
        now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(wait_s));
    Clock::time_point& held = held_until[job.host];
    if (held < until) {
      if (held <= now) {
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.1f", wait_s);
        log(job.host + " asked to wait " + seconds + " s (" + why + ")");
      }
      held = until;
    }
    if (retries_spent(job, why)) return;
    enqueue(job);
  }

  bool retries_spent(Job& job, const std::string& why) {
    if (job.attempts <= options.max_retries) return false;
    fail(job, why + " (" + std::to_string(job.attempts) + " attempts)");
    return true;
  }

  void fire_timers(Clock::time_point now) {
    while (!timers.empty() && timers.begin()->first <= now) {
      const RequestId id = timers.begin()->second;
      timers.erase(timers.begin());
      if (const auto it = jobs.find(id); it != jobs.end() && it->second.state == State::kWaiting)
        enqueue(it->second);
    }
  }

  // ----- cancel and priority -----

  void cancel_job(RequestId id) {
    const auto it = jobs.find(id);
    if (it == jobs.end()) return;
    Job& job = it->second;
    switch (job.state) {
      case State::kQueued:
        queue.erase({-job.request.priority, id});
        break;
      case State::kWaiting:
        for (auto [t, end] = timers.equal_range(job.wake); t != end; ++t)
          if (t->second == id) {
            timers.erase(t);
            break;
          }
        break;
      case State::kRunning:
        curl.abort(id);
        stopped_running(job);
        break;
    }
    Response r;
    r.outcome = Outcome::kCancelled;
    finish(job, std::move(r));
  }

  void cancel_everything() {
    std::vector<RequestId> ids;
    for (const auto& [id, job] : jobs)
      ids.push_back(id);
    std::sort(ids.begin(), ids.end());
    for (RequestId id : ids)
      cancel_job(id);
  }

  void reprioritize(RequestId id, double priority) {
    const auto it = jobs.find(id);
    if (it == jobs.end() || std::isnan(priority)) return;
    Job& job = it->second;
    if (job.state == State::kQueued) {
      queue.erase({-job.request.priority, id});
      job.request.priority = priority;
      queue.emplace(-priority, id);
    } else {
      job.request.priority = priority;  // for when it comes back to the queue
    }
  }

  // ----- answers -----

  void answer_from_cache(Job& job, CacheEntry entry, bool after_304) {
    Response r;
    r.outcome = Outcome::kOk;
    r.body = std::move(entry.body);
    r.content_type = std::move(entry.content_type);
    r.etag = std::move(entry.etag);
    r.from_cache = true;
    r.revalidated = after_304;
    ++counters.cache_hits;
    if (after_304) ++counters.revalidated;
    finish(job, std::move(r));
  }

  void answer_no_content(Job& job) {
    Response r;
    r.outcome = Outcome::kNoContent;
    finish(job, std::move(r));
  }

  void broken(Job& job, const std::string& why) {
    if (reported_broken.insert(job.key).second) log(why);
    Response r;
    r.outcome = Outcome::kBroken;
    r.error = why;
    finish(job, std::move(r));
  }

  void fail(Job& job, const std::string& why) {
    Response r;
    r.outcome = Outcome::kFailed;
    r.error = why;
    finish(job, std::move(r));
  }

  // The job's answer, to be delivered at the end of this turn; the job is gone.
  void finish(Job& job, Response r) {
    r.status = job.last_status;
    r.attempts = job.attempts;
    switch (r.outcome) {
      case Outcome::kNoContent:
        ++counters.no_content;
        break;
      case Outcome::kBroken:
        ++counters.broken;
        break;
      case Outcome::kFailed:
        ++counters.failed;
        break;
      case Outcome::kCancelled:
        ++counters.cancelled;
        break;
      case Outcome::kOk:
      case Outcome::kOffline:
        break;
    }
    answers.push_back({std::move(job.done), std::move(r)});
    jobs.erase(job.id);
  }

  void deliver() {
    while (!answers.empty()) {
      std::vector<Answer> now;
      now.swap(answers);
      for (Answer& a : now) {
        --counters.in_flight;
        call(a.done, std::move(a.response));
      }
    }
  }

  void call(std::function<void(Response)>& done, Response r) {
    if (!done) return;
    try {
      done(std::move(r));
    } catch (const std::exception& e) {
      log(std::string("a request's callback threw: ") + e.what());
    } catch (...) {
      log("a request's callback threw");
    }
  }

  void log(const std::string& line) {
    if (options.log) {
      try {
        options.log(line);
      } catch (...) {
        // The log is the last resort: a failing one is not reported again.
      }
    } else {
      std::fprintf(stderr, "%s\n", line.c_str());
    }
  }

  // ----- other threads -----

  void send(Command c) {
    bool queued = false;
    {
      std::lock_guard lock(mu);
      if (!finished) {
        inbox.push_back(std::move(c));
        queued = true;
      }
    }
    if (queued) {
      curl.wakeup();
    } else if (c.kind == Command::Kind::kGet) {  // the thread has ended: cancelled at once
      --counters.in_flight;
      ++counters.cancelled;
      Response r;
      r.outcome = Outcome::kCancelled;
      call(c.done, std::move(r));
    }
  }
};

HttpClient::HttpClient(ClientOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {
  impl_->thread = std::thread([impl = impl_.get()] { impl->run(); });
}

HttpClient::~HttpClient() {
  {
    std::lock_guard lock(impl_->mu);
    impl_->stopping = true;
  }
  impl_->curl.wakeup();
  impl_->thread.join();
}

RequestId HttpClient::get(Request request, std::function<void(Response)> done) {
  Impl::Command c;
  c.kind = Impl::Command::Kind::kGet;
  c.id = impl_->next_id++;
  c.request = std::move(request);
  c.done = std::move(done);
  ++impl_->counters.in_flight;
  const RequestId id = c.id;
  impl_->send(std::move(c));
  return id;
}

void HttpClient::cancel(RequestId id) {
  Impl::Command c;
  c.kind = Impl::Command::Kind::kCancel;
  c.id = id;
  impl_->send(std::move(c));
}

void HttpClient::set_priority(RequestId id, double priority) {
  Impl::Command c;
  c.kind = Impl::Command::Kind::kPriority;
  c.id = id;
  c.priority = priority;
  impl_->send(std::move(c));
}

Response HttpClient::get_blocking(Request request) {
  if (std::this_thread::get_id() == impl_->thread.get_id())
    throw NetError(request.url +
                   ": get_blocking from the client's own thread (a callback) would wait forever; "
                   "use get");
  std::promise<Response> promise;
  std::future<Response> answer = promise.get_future();
  get(std::move(request), [&promise](Response r) { promise.set_value(std::move(r)); });
  return answer.get();
}

ClientStats HttpClient::stats() const {
  const Impl::Counters& c = impl_->counters;
  ClientStats s;
  s.requests = c.requests;
  s.bytes = c.bytes;
  s.cache_hits = c.cache_hits;
  s.revalidated = c.revalidated;
  s.retries = c.retries;
  s.no_content = c.no_content;
  s.broken = c.broken;
  s.failed = c.failed;
  s.cancelled = c.cancelled;
  s.in_flight = c.in_flight;
  return s;
}

const ClientOptions& HttpClient::options() const {
  return impl_->options;
}

}  // namespace globe::net
