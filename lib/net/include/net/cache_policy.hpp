// HTTP caching rules as pure functions: Cache-Control (RFC 9111 5.2), HTTP
// dates (RFC 9110 5.6.7: IMF-fixdate, RFC 850, asctime), freshness from
// max-age / Expires / Date / Age, Retry-After (RFC 9110 10.2.3), content-type
// checks and the cache key. What HttpClient decides from a response's
// headers; no I/O and no clock of their own (the caller passes "now"), so
// that tests check them directly. Implemented in src/cache_policy.cpp.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace globe::net {

struct CacheControl {
  bool no_store = false;           // never stored
  bool no_cache = false;           // stored, but revalidated before each use
  std::optional<int64_t> max_age;  // seconds; a negative or malformed value is absent
};
// Directives are case-insensitive, separated by commas; unknown ones ignored.
CacheControl parse_cache_control(std::string_view value);

// Unix seconds of an HTTP date in any of the three forms, or nullopt.
std::optional<int64_t> parse_http_date(std::string_view value);

// The headers that decide freshness, as sent ("" if absent).
struct FreshnessHeaders {
  std::string cache_control;
  std::string expires;
  std::string date;
  std::string age;
};
// CacheEntry::expires_at for a response received at now_s: now + max-age - Age
// if max-age is given, else Expires (taken relative to Date when there is one,
// so that the server's clock error cancels out), else 0 (stale at once; an
// invalid Expires too). no-cache: 0.
int64_t expires_at(const FreshnessHeaders& headers, int64_t now_s);

// Seconds to wait from a Retry-After value (delay-seconds or an HTTP date,
// never negative), or nullopt if it is neither.
std::optional<double> retry_after_s(std::string_view value, int64_t now_s);

// Whether `content_type` (parameters ignored, case-insensitive) starts with
// one of `accept_types`; an empty list accepts anything.
bool content_type_accepted(std::string_view content_type,
                           const std::vector<std::string>& accept_types);

// The DiskCache key of a request: the URL, plus "#range=A-B" for a range
// "bytes=A-B".
std::string cache_key(const std::string& url, const std::string& range);

}  // namespace globe::net
