// A JSON object written member by member, for `info --json` (docs/cli.md
// "info --json"): keys in the order added, strings escaped, integers exact,
// other numbers with 17 significant digits.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace globe {

class InfoJson {
 public:
  InfoJson& integer(const std::string& key, uint64_t v);
  InfoJson& number(const std::string& key, double v);
  InfoJson& boolean(const std::string& key, bool v);
  InfoJson& text(const std::string& key, const std::string& v);
  InfoJson& texts(const std::string& key, const std::vector<std::string>& v);
  // `json` is already JSON text (an object, array or value).
  InfoJson& raw(const std::string& key, const std::string& json);
  InfoJson& object(const std::string& key, const InfoJson& v) { return raw(key, v.str()); }
  InfoJson& objects(const std::string& key, const std::vector<InfoJson>& v);
  std::string str() const { return "{" + body_ + "}"; }

 private:
  InfoJson& member(const std::string& key, const std::string& json);
  std::string body_;
};

}  // namespace globe
