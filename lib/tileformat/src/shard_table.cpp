// Shard packages' metadata and table (see shard_table.hpp).
#include "tileformat/shard_table.hpp"

#include <charconv>

#include "tileformat/error.hpp"

namespace tileformat {
namespace {

constexpr const char* kSection = "10";

bool has_shard_table(SqliteDb& db) {
  return db.query_int(
               "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND name = 'shard_parts'")
             .value_or(0) != 0;
}

uint64_t parse_count(const std::string& key, const std::string& text) {
  uint64_t v = 0;
  const char* end = text.data() + text.size();
  auto r = std::from_chars(text.data(), end, v);
  if (r.ec != std::errc() || r.ptr != end)
    throw FormatError(kSection, "metadata key " + key + " is not a count: '" + text + "'");
  return v;
}

std::string required(const MetadataMap& meta, const std::string& key) {
  auto it = meta.find(key);
  if (it == meta.end()) throw FormatError(kSection, "metadata key " + key + " is missing");
  return it->second;
}

}  // namespace

MetadataMap to_metadata(const ShardMetadata& m) {
  return {{"globe:shard", std::to_string(m.index) + "/" + std::to_string(m.count)},
          {"globe:shard_split_zoom", std::to_string(m.split_zoom)},
          {"globe:shard_roots", std::to_string(m.roots)},
          {"globe:shard_build", m.build},
          {"globe:shard_min_zoom", std::to_string(m.min_zoom)},
          {"globe:shard_center_zoom", std::to_string(m.center_zoom)}};
}

std::optional<ShardMetadata> read_shard_metadata(const MetadataMap& meta) {
  auto it = meta.find("globe:shard");
  if (it == meta.end()) return std::nullopt;
  ShardMetadata m;
  const std::string& s = it->second;
  const size_t slash = s.find('/');
  if (slash == std::string::npos)
    throw FormatError(kSection, "metadata globe:shard is not INDEX/COUNT: '" + s + "'");
  m.index = static_cast<int>(parse_count("globe:shard", s.substr(0, slash)));
  m.count = static_cast<int>(parse_count("globe:shard", s.substr(slash + 1)));
  if (m.count < 1 || m.index >= m.count)
    throw FormatError(kSection, "metadata globe:shard names shard " + s + ", out of range");
  m.split_zoom = static_cast<int>(
      parse_count("globe:shard_split_zoom", required(meta, "globe:shard_split_zoom")));
  if (m.split_zoom > kMaxZoom)
    throw FormatError(kSection,
                      "metadata globe:shard_split_zoom is above zoom " + std::to_string(kMaxZoom));
  m.roots = parse_count("globe:shard_roots", required(meta, "globe:shard_roots"));
  m.build = required(meta, "globe:shard_build");
  m.min_zoom =
      static_cast<int>(parse_count("globe:shard_min_zoom", required(meta, "globe:shard_min_zoom")));
  m.center_zoom = static_cast<int>(
      parse_count("globe:shard_center_zoom", required(meta, "globe:shard_center_zoom")));
  if (m.min_zoom > m.split_zoom || m.center_zoom > kMaxZoom)
    throw FormatError(kSection,
                      "metadata globe:shard_min_zoom or globe:shard_center_zoom is out "
                      "of range");
  return m;
}

MetadataMap without_shard_keys(MetadataMap meta) {
  for (const auto& [key, value] : to_metadata(ShardMetadata{}))
    meta.erase(key);
  return meta;
}

ShardTableWriter::ShardTableWriter(PackageWriter& writer) {
  continued_ = writer.resumed() && has_shard_table(writer.db());
  if (!continued_)
    writer.db().exec(
        "CREATE TABLE shard_parts (part INTEGER NOT NULL, zoom_level INTEGER NOT NULL, "
        "tile_column INTEGER NOT NULL, tile_row INTEGER NOT NULL, data BLOB NOT NULL, "
        "PRIMARY KEY (part, zoom_level, tile_row, tile_column))");
  insert_ = std::make_unique<SqliteStatement>(
      writer.db(),
      "INSERT OR REPLACE INTO shard_parts (part, zoom_level, tile_column, tile_row, data) "
      "VALUES (?, ?, ?, ?, ?)");
}

ShardTableWriter::~ShardTableWriter() = default;

void ShardTableWriter::put(ShardPartTag tag, TileId id, std::span<const uint8_t> data) {
  // Rows here are XYZ (y = 0 at the top): the table is ours, not MBTiles'.
  insert_->bind(1, int64_t{tag}).bind(2, int64_t{id.z}).bind(3, int64_t{id.x});
  insert_->bind(4, int64_t{id.y}).bind(5, data);
  insert_->step();
  insert_->reset();
}

void ShardTableWriter::put_roots(const std::vector<TileId>& roots) {
  if (continued_) return;
  for (const TileId& root : roots)
    put(kShardRoot, root, {});
}

ShardTableReader::ShardTableReader(PackageReader& reader) : reader_(reader) {
  if (!has_shard_table(reader.db()))
    throw FormatError(kSection, reader.db().path() +
                                    ": a shard package without its shard table; rebuild the "
                                    "shard");
  get_ = std::make_unique<SqliteStatement>(
      reader.db(),
      "SELECT data FROM shard_parts WHERE part = ? AND zoom_level = ? AND tile_column = ? AND "
      "tile_row = ?");
  list_ = std::make_unique<SqliteStatement>(
      reader.db(),
      "SELECT zoom_level, tile_column, tile_row FROM shard_parts WHERE part = ? "
      "ORDER BY zoom_level, tile_row, tile_column");
}

ShardTableReader::~ShardTableReader() = default;

std::optional<std::vector<uint8_t>> ShardTableReader::get(ShardPartTag tag, TileId id) {
  get_->reset();
  get_->bind(1, int64_t{tag}).bind(2, int64_t{id.z}).bind(3, int64_t{id.x});
  get_->bind(4, int64_t{id.y});
  std::optional<std::vector<uint8_t>> out;
  if (get_->step()) {
    const auto blob = get_->column_blob(0);
    out.emplace(blob.begin(), blob.end());
  }
  get_->reset();
  return out;
}

std::vector<TileId> ShardTableReader::list(ShardPartTag tag) {
  list_->reset();
  list_->bind(1, int64_t{tag});
  std::vector<TileId> ids;
  while (list_->step()) {
    const int64_t z = list_->column_int(0), x = list_->column_int(1), y = list_->column_int(2);
    if (z < 0 || z > kMaxZoom || x < 0 || y < 0 || x > UINT32_MAX || y > UINT32_MAX)
      throw FormatError(kSection, reader_.db().path() + ": shard table row " + std::to_string(z) +
                                      "/" + std::to_string(x) + "/" + std::to_string(y) +
                                      " is not a tile id");
    ids.push_back(TileId{static_cast<int>(z), static_cast<uint32_t>(x), static_cast<uint32_t>(y)});
  }
  list_->reset();
  return ids;
}

}  // namespace tileformat
