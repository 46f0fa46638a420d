// JSON objects for `info --json` (see info_json.hpp).
#include "kit/info_json.hpp"

#include <cmath>
#include <cstdio>

#include "tileformat/json.hpp"

namespace globe {

InfoJson& InfoJson::member(const std::string& key, const std::string& json) {
  body_ += (body_.empty() ? "\"" : ",\"") + tileformat::json_escape(key) + "\":" + json;
  return *this;
}

InfoJson& InfoJson::integer(const std::string& key, uint64_t v) {
  return member(key, std::to_string(v));
}

InfoJson& InfoJson::number(const std::string& key, double v) {
  if (!std::isfinite(v)) return member(key, "null");
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return member(key, buf);
}

InfoJson& InfoJson::boolean(const std::string& key, bool v) {
  return member(key, v ? "true" : "false");
}

InfoJson& InfoJson::text(const std::string& key, const std::string& v) {
  return member(key, "\"" + tileformat::json_escape(v) + "\"");
}

InfoJson& InfoJson::texts(const std::string& key, const std::vector<std::string>& v) {
  std::string a = "[";
  for (size_t i = 0; i < v.size(); ++i)
    a += (i ? ",\"" : "\"") + tileformat::json_escape(v[i]) + "\"";
  return member(key, a + "]");
}

InfoJson& InfoJson::raw(const std::string& key, const std::string& json) {
  return member(key, json);
}

InfoJson& InfoJson::objects(const std::string& key, const std::vector<InfoJson>& v) {
  std::string a = "[";
  for (size_t i = 0; i < v.size(); ++i)
    a += (i ? "," : "") + v[i].str();
  return member(key, a + "]");
}

}  // namespace globe
