// RFC 9110's ranges, conditionals and gzip negotiation (see http_semantics.hpp).
#include "serve/http_semantics.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace globe::serve::http {
namespace {

constexpr uint64_t kHuge = std::numeric_limits<uint64_t>::max();

bool is_ows(char c) {
  return c == ' ' || c == '\t';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_ows(s.front()))
    s.remove_prefix(1);
  while (!s.empty() && is_ows(s.back()))
    s.remove_suffix(1);
  return s;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) !=
        std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

// 1*DIGIT, saturating at kHuge (a position past any body); false if empty or
// not all digits.
bool parse_digits(std::string_view s, uint64_t& out) {
  if (s.empty()) return false;
  uint64_t v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
    const uint64_t d = uint64_t(c - '0');
    v = v > (kHuge - d) / 10 ? kHuge : v * 10 + d;
  }
  out = v;
  return true;
}

// The list elements of a field value (RFC 9110 §5.6.1: empty elements and
// the whitespace around commas are ignored).
std::vector<std::string_view> list_elements(std::string_view value) {
  std::vector<std::string_view> out;
  size_t at = 0;
  while (at <= value.size()) {
    const size_t comma = value.find(',', at);
    const std::string_view e = trim(
        value.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at));
    if (!e.empty()) out.push_back(e);
    if (comma == std::string_view::npos) break;
    at = comma + 1;
  }
  return out;
}

struct EntityTag {
  bool weak = false;
  std::string_view opaque;  // with its quotes
};

// The entity tags of an If-None-Match / If-Range value; `star` set for `*`.
// Commas may stand inside a quoted tag (etagc includes %x2C), so the list
// is split by the quotes, not by commas. False on malformed input.
bool entity_tags(std::string_view value, std::vector<EntityTag>& out, bool& star) {
  star = false;
  size_t at = 0;
  for (;;) {
    while (at < value.size() && (is_ows(value[at]) || value[at] == ','))
      ++at;
    if (at >= value.size()) return true;
    if (value[at] == '*') {
      star = true;
      ++at;
      continue;
    }
    EntityTag t;
    if (value.compare(at, 2, "W/") == 0) {
      t.weak = true;
      at += 2;
    }
    if (at >= value.size() || value[at] != '"') return false;
    const size_t close = value.find('"', at + 1);
    if (close == std::string_view::npos) return false;
    t.opaque = value.substr(at, close - at + 1);
    out.push_back(t);
    at = close + 1;
  }
}

EntityTag parse_own(std::string_view etag) {
  EntityTag t;
  if (etag.compare(0, 2, "W/") == 0) {
    t.weak = true;
    etag.remove_prefix(2);
  }
  t.opaque = etag;
  return t;
}

}  // namespace

RangeRequest parse_range(std::string_view header, uint64_t size, size_t max_ranges) {
  RangeRequest whole;
  const size_t eq = header.find('=');
  if (eq == std::string_view::npos || !iequals(trim(header.substr(0, eq)), "bytes")) return whole;
  const std::vector<std::string_view> specs = list_elements(header.substr(eq + 1));
  if (specs.empty() || specs.size() > max_ranges) return whole;
  RangeRequest out;
  uint64_t total = 0;
  for (std::string_view spec : specs) {
    const size_t dash = spec.find('-');
    if (dash == std::string_view::npos) return whole;
    const std::string_view a = spec.substr(0, dash), b = spec.substr(dash + 1);
    uint64_t first = 0, last = kHuge;
    if (a.empty()) {  // suffix-range: the last b bytes
      uint64_t suffix = 0;
      if (!parse_digits(b, suffix)) return whole;
      if (suffix == 0 || size == 0) continue;  // unsatisfiable, but valid
      first = suffix >= size ? 0 : size - suffix;
      last = size - 1;
    } else {  // int-range
      if (!parse_digits(a, first)) return whole;
      if (!b.empty()) {
        if (!parse_digits(b, last)) return whole;
        if (last < first) return whole;  // invalid (§14.1.1)
      }
      if (first >= size) continue;  // unsatisfiable, but valid
      last = std::min(last, size - 1);
    }
    out.ranges.push_back({first, last});
    total += last - first + 1;
  }
  if (out.ranges.empty()) {
    out.kind = RangeRequest::Kind::kUnsatisfiable;
    return out;
  }
  if (out.ranges.size() > 1 && total > size) return whole;  // overlaps that amplify
  out.kind = RangeRequest::Kind::kRanges;
  return out;
}

std::string content_range(const ByteRange& r, uint64_t size) {
  return "bytes " + std::to_string(r.first) + "-" + std::to_string(r.last) + "/" +
         std::to_string(size);
}

std::string unsatisfied_range(uint64_t size) {
  return "bytes */" + std::to_string(size);
}

bool none_match_fails(std::string_view if_none_match, std::string_view etag) {
  std::vector<EntityTag> tags;
  bool star = false;
  if (!entity_tags(if_none_match, tags, star)) return false;
  if (star) return true;
  if (etag.empty()) return false;
  const EntityTag own = parse_own(etag);
  for (const EntityTag& t : tags)
    if (t.opaque == own.opaque) return true;  // weak comparison
  return false;
}

bool if_range_holds(std::string_view if_range, std::string_view etag,
                    std::string_view last_modified) {
  const std::string_view v = trim(if_range);
  if (v.empty()) return true;
  if (v.front() == '"' || v.compare(0, 2, "W/") == 0) {
    std::vector<EntityTag> tags;
    bool star = false;
    if (!entity_tags(v, tags, star) || star || tags.size() != 1 || etag.empty()) return false;
    const EntityTag own = parse_own(etag);
    return !tags[0].weak && !own.weak && tags[0].opaque == own.opaque;  // strong comparison
  }
  return !last_modified.empty() && v == last_modified;
}

bool accepts_gzip(std::string_view accept_encoding) {
  bool gzip = false, refused = false, star = false;
  for (std::string_view e : list_elements(accept_encoding)) {
    const size_t semi = e.find(';');
    const std::string_view coding = trim(e.substr(0, semi));
    bool positive = true;
    if (semi != std::string_view::npos) {
      std::string_view params = e.substr(semi + 1);
      const size_t q = params.find_first_of("qQ");
      if (q != std::string_view::npos) {
        std::string_view value = trim(params.substr(q + 1));
        if (!value.empty() && value.front() == '=') {
          value = trim(value.substr(1));
          positive = std::strtod(std::string(value).c_str(), nullptr) > 0;
        }
      }
    }
    if (iequals(coding, "gzip") || iequals(coding, "x-gzip")) {
      (positive ? gzip : refused) = true;
    } else if (coding == "*") {
      star = star || positive;
    }
  }
  return gzip || (star && !refused);
}

std::string multipart_byteranges(const std::vector<ByteRange>& ranges,
                                 const std::vector<std::string>& parts, uint64_t size,
                                 const std::string& content_type, std::string& boundary) {
  // A boundary of 24 hexadecimal digits from a simple mix of the ranges,
  // changed until it occurs in no part.
  uint64_t mix = 0x9E3779B97F4A7C15ULL ^ size;
  for (const ByteRange& r : ranges)
    mix = (mix ^ r.first ^ (r.last << 17)) * 0x100000001B3ULL;
  for (;;) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "globe-%016llx", static_cast<unsigned long long>(mix));
    boundary = buf;
    bool clash = false;
    for (const std::string& p : parts)
      clash = clash || p.find(boundary) != std::string::npos;
    if (!clash) break;
    mix = mix * 0x100000001B3ULL + 1;
  }
  std::string out;
  for (size_t i = 0; i < ranges.size(); ++i) {
    out += "\r\n--" + boundary + "\r\nContent-Type: " + content_type +
           "\r\nContent-Range: " + content_range(ranges[i], size) + "\r\n\r\n";
    out += parts[i];
  }
  out += "\r\n--" + boundary + "--\r\n";
  return out;
}

}  // namespace globe::serve::http
