// Line packages' features table (see feature_table.hpp).
#include "tileformat/feature_table.hpp"

#include "tileformat/error.hpp"

namespace tileformat {
namespace {

bool has_features_table(SqliteDb& db) {
  return db.query_int(
               "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND "
               "name = 'features'")
             .value_or(0) != 0;
}

}  // namespace

FeatureTableWriter::FeatureTableWriter(PackageWriter& writer) {
  complete_ = writer.resumed() && has_features_table(writer.db());
  if (complete_) return;
  writer.db().exec(
      "CREATE TABLE features (id INTEGER PRIMARY KEY, layer TEXT NOT NULL, properties TEXT "
      "NOT NULL)");
  insert_ = std::make_unique<SqliteStatement>(
      writer.db(), "INSERT INTO features (id, layer, properties) VALUES (?, ?, ?)");
}

FeatureTableWriter::~FeatureTableWriter() = default;

void FeatureTableWriter::add(int64_t id, const std::string& layer,
                             const std::string& properties_json) {
  insert_->bind(1, id).bind(2, layer).bind(3, properties_json);
  insert_->step();
  insert_->reset();
}

FeatureTableReader::FeatureTableReader(PackageReader& reader) : reader_(reader) {
  if (!has_features_table(reader.db()))
    throw FormatError("7.4", reader.db().path() +
                                 ": a line package without its features table; rebuild it with "
                                 "globe-vectorize lines");
  lookup_ = std::make_unique<SqliteStatement>(
      reader.db(), "SELECT layer, properties FROM features WHERE id = ?");
}

FeatureTableReader::~FeatureTableReader() = default;

int64_t FeatureTableReader::count() {
  return reader_.db().query_int("SELECT count(*) FROM features").value_or(0);
}

int64_t FeatureTableReader::max_id() {
  return reader_.db().query_int("SELECT max(id) FROM features").value_or(0);
}

std::optional<FeatureRecord> FeatureTableReader::get(int64_t id) {
  lookup_->reset();
  lookup_->bind(1, id);
  std::optional<FeatureRecord> r;
  if (lookup_->step()) r = FeatureRecord{lookup_->column_text(0), lookup_->column_text(1)};
  lookup_->reset();
  return r;
}

void FeatureTableReader::for_each(const std::function<void(int64_t id, const FeatureRecord&)>& fn) {
  SqliteStatement all(reader_.db(), "SELECT id, layer, properties FROM features ORDER BY id");
  while (all.step())
    fn(all.column_int(0), FeatureRecord{all.column_text(1), all.column_text(2)});
}

}  // namespace tileformat
