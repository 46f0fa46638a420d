// Resolving relative URLs (see url.hpp).
#include "net/url.hpp"

#include <cctype>

namespace globe::net {
namespace {

bool has_scheme(const std::string& s) {
  const size_t colon = s.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  for (size_t i = 0; i < colon; ++i) {
    const char c = s[i];
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.'))
      return false;
  }
  return true;
}

// "a/./b/../c" -> "a/c" on the path of an absolute URL.
std::string remove_dots(const std::string& path) {
  std::string out;
  size_t at = 0;
  while (at < path.size()) {
    size_t next = path.find('/', at + 1);
    if (next == std::string::npos) next = path.size();
    const std::string seg = path.substr(at, next - at);  // "/name"
    if (seg == "/.") {
      if (next == path.size()) out += "/";
    } else if (seg == "/..") {
      const size_t cut = out.rfind('/');
      out.erase(cut == std::string::npos ? 0 : cut);
      if (next == path.size()) out += "/";
    } else {
      out += seg;
    }
    at = next;
  }
  return out;
}

}  // namespace

std::string resolve_url(const std::string& base, const std::string& ref) {
  if (ref.empty()) return base.substr(0, base.find_first_of("#"));
  if (has_scheme(ref)) return ref;
  const size_t scheme_end = base.find("://");
  if (scheme_end == std::string::npos) return ref;
  const std::string scheme = base.substr(0, scheme_end + 1);  // "http:"
  if (ref.rfind("//", 0) == 0) return scheme + ref;
  const size_t path_at = base.find('/', scheme_end + 3);
  const std::string authority = base.substr(0, path_at);  // "http://host:port"
  if (ref[0] == '/') return authority + remove_dots(ref);
  std::string path = path_at == std::string::npos ? "/" : base.substr(path_at);
  path = path.substr(0, path.find_first_of("?#"));
  path = path.substr(0, path.rfind('/') + 1);  // the document's folder
  return authority + remove_dots(path + ref);
}

std::string fill_placeholder(std::string s, const std::string& what, const std::string& with) {
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + with.size()))
    s.replace(at, what.size(), with);
  return s;
}

}  // namespace globe::net
