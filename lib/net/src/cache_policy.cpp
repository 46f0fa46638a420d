// HTTP caching rules (net/cache_policy.hpp): header parsing and freshness
// arithmetic, pure functions over strings and the caller's "now". Touches
// nothing but its arguments.
#include "net/cache_policy.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <limits>

namespace globe::net {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
    s.remove_prefix(1);
  while (!s.empty() &&
         (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\n'))
    s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// A non-negative decimal integer, saturated at int64's maximum; nullopt if
// `s` is empty or holds anything but digits.
std::optional<int64_t> parse_seconds(std::string_view s) {
  if (s.empty()) return std::nullopt;
  int64_t v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return std::nullopt;
    const int d = c - '0';
    if (v > (std::numeric_limits<int64_t>::max() - d) / 10) {
      v = std::numeric_limits<int64_t>::max();
    } else {
      v = v * 10 + d;
    }
  }
  return v;
}

// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's
// days_from_civil).
int64_t days_from_civil(int64_t y, unsigned m, unsigned d) {
  y -= m <= 2;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<int64_t>(doe) - 719468;
}

int month_of(std::string_view name) {
  static constexpr std::array<std::string_view, 12> kMonths = {
      "jan", "feb", "mar", "apr", "may", "jun", "jul", "aug", "sep", "oct", "nov", "dec"};
  const std::string l = lower(name);
  for (size_t i = 0; i < kMonths.size(); ++i)
    if (l == kMonths[i]) return static_cast<int>(i) + 1;
  return 0;
}

bool parse_clock(std::string_view s, int* h, int* m, int* sec) {
  if (s.size() != 8 || s[2] != ':' || s[5] != ':') return false;
  const auto two = [&](size_t at, int* out) {
    if (!std::isdigit(static_cast<unsigned char>(s[at])) ||
        !std::isdigit(static_cast<unsigned char>(s[at + 1])))
      return false;
    *out = (s[at] - '0') * 10 + (s[at + 1] - '0');
    return true;
  };
  return two(0, h) && two(3, m) && two(6, sec) && *h < 24 && *m < 60 && *sec <= 60;
}

}  // namespace

CacheControl parse_cache_control(std::string_view value) {
  CacheControl cc;
  while (!value.empty()) {
    const size_t comma = value.find(',');
    const std::string_view item = trim(value.substr(0, comma));
    value = comma == std::string_view::npos ? std::string_view() : value.substr(comma + 1);
    const size_t eq = item.find('=');
    const std::string name = lower(trim(item.substr(0, eq)));
    std::string_view arg = eq == std::string_view::npos ? "" : trim(item.substr(eq + 1));
    if (arg.size() >= 2 && arg.front() == '"' && arg.back() == '"')
      arg = arg.substr(1, arg.size() - 2);
    if (name == "no-store") {
      cc.no_store = true;
    } else if (name == "no-cache") {
      cc.no_cache = true;
    } else if (name == "max-age") {
      // Two max-age directives disagreeing: the smaller, the safe reading.
      if (const auto s = parse_seconds(arg))
        cc.max_age = cc.max_age ? std::min(*cc.max_age, *s) : *s;
    }
  }
  return cc;
}

std::optional<int64_t> parse_http_date(std::string_view value) {
  // Tokens split at spaces, commas and dashes: "Sun, 06 Nov 1994 08:49:37
  // GMT", "Sunday, 06-Nov-94 08:49:37 GMT", "Sun Nov  6 08:49:37 1994".
  std::vector<std::string_view> t;
  size_t i = 0;
  while (i < value.size()) {
    const auto sep = [&](char c) { return c == ' ' || c == ',' || c == '-' || c == '\t'; };
    while (i < value.size() && sep(value[i]))
      ++i;
    const size_t start = i;
    while (i < value.size() && !sep(value[i]))
      ++i;
    if (i > start) t.push_back(value.substr(start, i - start));
  }
  if (t.empty() || !std::isalpha(static_cast<unsigned char>(t[0][0]))) return std::nullopt;
  t.erase(t.begin());  // the weekday, not checked
  std::string_view day_s, month_s, year_s, clock_s;
  if (t.size() == 4 && month_of(t[0]) != 0) {  // asctime
    month_s = t[0], day_s = t[1], clock_s = t[2], year_s = t[3];
  } else if (t.size() == 5 && lower(t[4]) == "gmt") {  // IMF-fixdate, RFC 850
    day_s = t[0], month_s = t[1], year_s = t[2], clock_s = t[3];
  } else {
    return std::nullopt;
  }
  const auto day = parse_seconds(day_s);
  auto year = parse_seconds(year_s);
  const int month = month_of(month_s);
  int h = 0, m = 0, s = 0;
  if (!day || !year || month == 0 || *day < 1 || *day > 31 || !parse_clock(clock_s, &h, &m, &s))
    return std::nullopt;
  if (year_s.size() == 2) {
    *year += *year < 70 ? 2000 : 1900;  // RFC 850's two-digit years
  } else if (year_s.size() != 4) {
    return std::nullopt;
  }
  return days_from_civil(*year, static_cast<unsigned>(month), static_cast<unsigned>(*day)) * 86400 +
         h * 3600 + m * 60 + s;
}

int64_t expires_at(const FreshnessHeaders& headers, int64_t now_s) {
  const CacheControl cc = parse_cache_control(headers.cache_control);
  if (cc.no_cache || cc.no_store) return 0;
  constexpr int64_t kFar = int64_t{1} << 52;  // keeps the sums below from overflowing
  if (cc.max_age) {
    const int64_t age = std::min(parse_seconds(trim(headers.age)).value_or(0), kFar);
    const int64_t left = std::min(*cc.max_age, kFar) - age;
    return left > 0 ? now_s + left : 0;
  }
  if (headers.expires.empty()) return 0;
  const auto expires = parse_http_date(trim(headers.expires));
  if (!expires) return 0;  // RFC 9111 5.3: an invalid Expires is in the past
  if (const auto date = parse_http_date(trim(headers.date))) {
    const int64_t left = *expires - *date;
    return left > 0 ? now_s + std::min(left, kFar) : 0;
  }
  return *expires > now_s ? *expires : 0;
}

std::optional<double> retry_after_s(std::string_view value, int64_t now_s) {
  value = trim(value);
  if (const auto s = parse_seconds(value)) return static_cast<double>(*s);
  if (const auto date = parse_http_date(value))
    return static_cast<double>(std::max<int64_t>(0, *date - now_s));
  return std::nullopt;
}

bool content_type_accepted(std::string_view content_type,
                           const std::vector<std::string>& accept_types) {
  if (accept_types.empty()) return true;
  const std::string type = lower(trim(content_type.substr(0, content_type.find(';'))));
  if (type.empty()) return false;
  return std::any_of(accept_types.begin(), accept_types.end(),
                     [&](const std::string& a) { return type.starts_with(lower(a)); });
}

std::string cache_key(const std::string& url, const std::string& range) {
  if (range.empty()) return url;
  std::string_view r = trim(range);
  if (r.starts_with("bytes=")) r.remove_prefix(6);
  return url + "#range=" + std::string(r);
}

}  // namespace globe::net
