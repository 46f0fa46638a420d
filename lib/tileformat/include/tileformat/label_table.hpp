// The labels table of a vector package (docs/tileformat.md §13): the names
// the tools chose for the viewer to place - one row per labelled feature,
// with its text, anchor, priority and, for a line, the path a label follows.
// The one place that knows the table's SQL.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tileformat/package.hpp"

namespace tileformat {

enum class LabelPlacement : int { kPoint = 0, kArea = 1, kLine = 2 };

struct LabelRecord {
  int64_t id = 0;       // 1..N in the order the tool wrote them
  int64_t feature = 0;  // features.id of what it names
  std::string text;     // UTF-8
  double priority = 0;  // larger first
  double lon = 0,
         lat = 0;  // anchor (degrees): a point, an area's pole of inaccessibility, a line's middle
  LabelPlacement placement = LabelPlacement::kPoint;
  std::vector<double> path;  // lines: lon, lat, lon, lat, ... (degrees); empty otherwise
};

class LabelTableWriter {
 public:
  // Creates the table in the writer's open transaction, unless a resumed
  // build's file already holds it (complete, as the features table).
  explicit LabelTableWriter(PackageWriter& writer);
  ~LabelTableWriter();
  bool complete() const { return complete_; }
  // Adds a row with the next id (precondition: !complete()); returns the id.
  int64_t add(const LabelRecord& label);
  int64_t count() const { return next_ - 1; }

 private:
  std::unique_ptr<SqliteStatement> insert_;
  int64_t next_ = 1;
  bool complete_ = false;
};

class LabelTableReader {
 public:
  // Throws FormatError if the package has no labels table.
  explicit LabelTableReader(PackageReader& reader);
  ~LabelTableReader();
  // Whether `reader`'s package holds a labels table.
  static bool exists(PackageReader& reader);
  int64_t count();
  // Every row in id order.
  void for_each(const std::function<void(const LabelRecord&)>& fn);

 private:
  PackageReader& reader_;
};

inline bool has_labels(PackageReader& reader) {
  return LabelTableReader::exists(reader);
}

}  // namespace tileformat
