// The features table of a line package (docs/tileformat.md §7.4): every kept
// feature's source layer and attributes (a JSON object), by the id its tiles
// refer to. The one place that knows the table's SQL.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "tileformat/package.hpp"

namespace tileformat {

struct FeatureRecord {
  std::string layer;
  std::string properties;  // JSON object
};

class FeatureTableWriter {
 public:
  // Creates the table in the writer's open transaction, unless the file
  // already holds it: a resumed build whose table was committed before the
  // interruption (the table is filled in one transaction, so it is then
  // complete and nothing is to be added).
  explicit FeatureTableWriter(PackageWriter& writer);
  ~FeatureTableWriter();
  bool complete() const { return complete_; }
  // Adds one row (precondition: !complete()).
  void add(int64_t id, const std::string& layer, const std::string& properties_json);

 private:
  std::unique_ptr<SqliteStatement> insert_;
  bool complete_ = false;
};

class FeatureTableReader {
 public:
  // Throws FormatError if the package has no features table.
  explicit FeatureTableReader(PackageReader& reader);
  ~FeatureTableReader();
  int64_t count();
  int64_t max_id();  // 0 for an empty table
  std::optional<FeatureRecord> get(int64_t id);
  // Every row in id order.
  void for_each(const std::function<void(int64_t id, const FeatureRecord&)>& fn);

 private:
  PackageReader& reader_;
  std::unique_ptr<SqliteStatement> lookup_;
};

}  // namespace tileformat
