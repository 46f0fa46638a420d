// Vector packages' labels table (see label_table.hpp).
#include "tileformat/label_table.hpp"

#include <cstring>

#include "tileformat/error.hpp"

namespace tileformat {
namespace {

// A path as stored: little-endian IEEE doubles, lon then lat per point.
std::vector<uint8_t> encode_path(const std::vector<double>& path) {
  std::vector<uint8_t> out(path.size() * 8);
  for (size_t i = 0; i < path.size(); ++i) {
    uint64_t bits;
    std::memcpy(&bits, &path[i], 8);
    for (int b = 0; b < 8; ++b)
      out[i * 8 + b] = static_cast<uint8_t>(bits >> (8 * b));
  }
  return out;
}

std::vector<double> decode_path(std::span<const uint8_t> blob, const std::string& file) {
  if (blob.size() % 16 != 0)
    throw FormatError("13", file + ": a label path of " + std::to_string(blob.size()) +
                                " bytes (not whole lon/lat pairs); rebuild the package");
  std::vector<double> out(blob.size() / 8);
  for (size_t i = 0; i < out.size(); ++i) {
    uint64_t bits = 0;
    for (int b = 0; b < 8; ++b)
      bits |= uint64_t{blob[i * 8 + b]} << (8 * b);
    std::memcpy(&out[i], &bits, 8);
  }
  return out;
}

bool has_table(SqliteDb& db) {
  return db.query_int("SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND name = 'labels'")
             .value_or(0) != 0;
}

}  // namespace

bool LabelTableReader::exists(PackageReader& reader) {
  return has_table(reader.db());
}

LabelTableWriter::LabelTableWriter(PackageWriter& writer) {
  complete_ = writer.resumed() && has_table(writer.db());
  if (complete_) {
    next_ = writer.db().query_int("SELECT count(*) FROM labels").value_or(0) + 1;
    return;
  }
  writer.db().exec(
      "CREATE TABLE labels (id INTEGER PRIMARY KEY, feature INTEGER NOT NULL, text TEXT NOT "
      "NULL, priority REAL NOT NULL, lon REAL NOT NULL, lat REAL NOT NULL, placement INTEGER "
      "NOT NULL, path BLOB)");
  insert_ = std::make_unique<SqliteStatement>(
      writer.db(),
      "INSERT INTO labels (id, feature, text, priority, lon, lat, placement, path) VALUES (?, ?, "
      "?, ?, ?, ?, ?, ?)");
}

LabelTableWriter::~LabelTableWriter() = default;

int64_t LabelTableWriter::add(const LabelRecord& l) {
  const int64_t id = next_++;
  insert_->bind(1, id).bind(2, l.feature).bind(3, l.text);
  insert_->bind_double(4, l.priority).bind_double(5, l.lon).bind_double(6, l.lat);
  insert_->bind(7, static_cast<int64_t>(l.placement));
  if (l.path.empty())
    insert_->bind_null(8);
  else
    insert_->bind(8, encode_path(l.path));
  insert_->step();
  insert_->reset();
  return id;
}

LabelTableReader::LabelTableReader(PackageReader& reader) : reader_(reader) {
  if (!has_table(reader.db()))
    throw FormatError("13", reader.db().path() +
                                ": no labels table; build the package with "
                                "--label-field");
}

LabelTableReader::~LabelTableReader() = default;

int64_t LabelTableReader::count() {
  return reader_.db().query_int("SELECT count(*) FROM labels").value_or(0);
}

void LabelTableReader::for_each(const std::function<void(const LabelRecord&)>& fn) {
  SqliteStatement all(reader_.db(),
                      "SELECT id, feature, text, priority, lon, lat, placement, path FROM labels "
                      "ORDER BY id");
  while (all.step()) {
    LabelRecord r;
    r.id = all.column_int(0);
    r.feature = all.column_int(1);
    r.text = all.column_text(2);
    r.priority = all.column_double(3);
    r.lon = all.column_double(4);
    r.lat = all.column_double(5);
    const int64_t p = all.column_int(6);
    if (p < 0 || p > 2)
      throw FormatError("13", reader_.db().path() + ": label " + std::to_string(r.id) +
                                  " has placement " + std::to_string(p) + " (0..2)");
    r.placement = static_cast<LabelPlacement>(p);
    if (!all.column_is_null(7)) r.path = decode_path(all.column_blob(7), reader_.db().path());
    fn(r);
  }
}

}  // namespace tileformat
