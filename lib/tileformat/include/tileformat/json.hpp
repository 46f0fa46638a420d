// The JSON that packages carry in their metadata (globe:inputs,
// globe:classes, globe:layers) and that style files use: a small reader
// (RFC 8259: objects, arrays, strings with escapes, numbers, true, false,
// null) and the string escaping writers need. Here so that the library and
// the viewer read it without GDAL's CPLJSON (docs/architecture.md).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tileformat {

class JsonValue {
 public:
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };
  using Members = std::vector<std::pair<std::string, JsonValue>>;  // in document order

  // Parses a whole document; throws JsonError ("line L, column C: what").
  static JsonValue parse(std::string_view text);

  Type type() const { return type_; }
  bool is_null() const { return type_ == Type::kNull; }
  bool is_bool() const { return type_ == Type::kBool; }
  bool is_number() const { return type_ == Type::kNumber; }
  bool is_string() const { return type_ == Type::kString; }
  bool is_array() const { return type_ == Type::kArray; }
  bool is_object() const { return type_ == Type::kObject; }

  // The value; throws JsonError if the type differs.
  bool boolean() const;
  double number() const;
  const std::string& string() const;
  const std::vector<JsonValue>& array() const;
  const Members& members() const;
  // An object's member (the last one of that name), or nullptr (also for
  // non-objects).
  const JsonValue* find(std::string_view key) const;
  // The value as compact JSON text (numbers with 17 significant digits).
  std::string text() const;

 private:
  friend class JsonParser;
  Type type_ = Type::kNull;
  bool bool_ = false;
  double number_ = 0;
  std::string string_;
  std::vector<JsonValue> array_;
  Members members_;
};

class JsonError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `s` as the inside of a JSON string literal (quotes, backslashes and
// control characters escaped).
std::string json_escape(std::string_view s);

}  // namespace tileformat
