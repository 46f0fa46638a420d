// Export outputs (see tile_output.hpp).
#include "web/tile_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <utility>

#include "kit/package_output.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/json.hpp"
#include "tileformat/package.hpp"

namespace globe {
namespace {

namespace fs = std::filesystem;
namespace pm = tileformat::pmtiles;

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// The TileJSON-like metadata every output kind records.
std::string metadata_json(const ExportInfo& i, const std::string& tiles_url) {
  std::string j = "{\"tilejson\":\"3.0.0\",\"name\":\"" + tileformat::json_escape(i.name) +
                  "\",\"description\":\"" + tileformat::json_escape(i.description) +
                  "\",\"format\":\"" + i.format + "\",\"type\":\"" + i.type +
                  "\",\"minzoom\":" + std::to_string(i.min_zoom) +
                  ",\"maxzoom\":" + std::to_string(i.max_zoom) + ",\"bounds\":[" + number(i.west) +
                  "," + number(i.south) + "," + number(i.east) + "," + number(i.north) +
                  "],\"scheme\":\"" + (i.tms_rows ? "tms" : "xyz") + "\"";
  if (!tiles_url.empty()) j += ",\"tiles\":[\"" + tiles_url + "\"]";
  if (!i.extra_json.empty()) j += "," + i.extra_json;
  return j + "}";
}

OutputError write_error(const std::string& path, const std::exception& e) {
  return OutputError(path + ": " + e.what() + "; nothing was written under that name");
}

class PmtilesOutput : public TileOutput {
 public:
  PmtilesOutput(const std::string& path, bool force) : path_(path) {
    try {
      writer_ = std::make_unique<pm::PmtilesWriter>(
          path, force ? tileformat::IfExists::kOverwrite : tileformat::IfExists::kFail);
    } catch (const tileformat::PackageError& e) {
      throw OutputError(e.what());
    }
  }
  void put(int z, uint32_t x, uint32_t y, std::span<const uint8_t> bytes) override {
    try {
      writer_->add(pm::tile_id(z, x, y), bytes);
    } catch (const tileformat::PackageError& e) {
      throw write_error(path_, e);
    }
  }
  uint64_t finish(const ExportInfo& i) override {
    pm::ArchiveInfo a;
    a.tile_type = i.tile_type;
    a.tile_compression = i.tile_compression;
    a.min_zoom = i.min_zoom, a.max_zoom = i.max_zoom;
    a.min_lon = i.west, a.min_lat = i.south, a.max_lon = i.east, a.max_lat = i.north;
    a.center_lon = (i.west + i.east) / 2, a.center_lat = (i.south + i.north) / 2;
    a.center_zoom = i.min_zoom;
    a.metadata_json = metadata_json(i, "");
    try {
      writer_->finish(a);
    } catch (const tileformat::PackageError& e) {
      throw write_error(path_, e);
    }
    return writer_->bytes_written();
  }
  uint64_t tiles() const override { return writer_->addressed_tiles(); }

 private:
  std::string path_;
  std::unique_ptr<pm::PmtilesWriter> writer_;
};

class MbtilesOutput : public TileOutput {
 public:
  MbtilesOutput(const std::string& path, bool force) : path_(path) {
    try {
      writer_ = std::make_unique<tileformat::PackageWriter>(
          path, force ? tileformat::IfExists::kOverwrite : tileformat::IfExists::kFail);
    } catch (const tileformat::PackageError& e) {
      throw OutputError(e.what());
    }
  }
  void put(int z, uint32_t x, uint32_t y, std::span<const uint8_t> bytes) override {
    if (bytes.empty()) return;
    try {
      writer_->put_tile({z, x, y}, bytes);  // stored with TMS rows
      ++tiles_;
    } catch (const tileformat::PackageError& e) {
      throw write_error(path_, e);
    }
  }
  uint64_t finish(const ExportInfo& i) override {
    try {
      writer_->set_metadata("name", i.name);
      writer_->set_metadata("description", i.description);
      writer_->set_metadata("format", i.format);
      writer_->set_metadata("type", i.type);
      writer_->set_metadata("version", "1");
      writer_->set_metadata("minzoom", std::to_string(i.min_zoom));
      writer_->set_metadata("maxzoom", std::to_string(i.max_zoom));
      writer_->set_metadata("bounds", number(i.west) + "," + number(i.south) + "," +
                                          number(i.east) + "," + number(i.north));
      writer_->set_metadata("center", number((i.west + i.east) / 2) + "," +
                                          number((i.south + i.north) / 2) + "," +
                                          std::to_string(i.min_zoom));
      writer_->set_metadata("json", metadata_json(i, ""));
      for (const auto& [name, text] : i.side_files)
        writer_->set_metadata(name, text);
      writer_->commit();
    } catch (const tileformat::PackageError& e) {
      throw write_error(path_, e);
    }
    std::error_code ec;
    return fs::file_size(path_, ec);
  }
  uint64_t tiles() const override { return tiles_; }

 private:
  std::string path_;
  std::unique_ptr<tileformat::PackageWriter> writer_;
  uint64_t tiles_ = 0;
};

// DIR.tmp/{z}/{x}/{y}.EXT, renamed to DIR by finish(); a DIR replaced with
// --force is removed only then.
class DirectoryOutput : public TileOutput {
 public:
  DirectoryOutput(const std::string& path, bool force, std::string ext, bool tms)
      : path_(path), temp_(path + ".tmp"), ext_(std::move(ext)), force_(force), tms_(tms) {
    std::error_code ec;
    if (fs::exists(path_, ec) && !force)
      throw OutputError(path_ + ": already exists (use --force to replace it)");
    fs::remove_all(temp_, ec);
    if (!fs::create_directories(temp_, ec) || ec)
      throw OutputError(temp_ + ": cannot create the folder (" + ec.message() + ")");
  }
  ~DirectoryOutput() override {
    std::error_code ec;
    if (!finished_) fs::remove_all(temp_, ec);
  }
  void put(int z, uint32_t x, uint32_t y, std::span<const uint8_t> bytes) override {
    if (bytes.empty()) return;
    const uint32_t row = tms_ ? static_cast<uint32_t>((uint64_t{1} << z) - 1 - y) : y;
    const fs::path dir = fs::path(temp_) / std::to_string(z) / std::to_string(x);
    std::error_code ec;
    fs::create_directories(dir, ec);
    const fs::path file = dir / (std::to_string(row) + "." + ext_);
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    out.close();
    if (!out) throw OutputError(file.string() + ": cannot write (disk full?)");
    bytes_ += bytes.size();
    ++tiles_;
  }
  uint64_t finish(const ExportInfo& i) override {
    {
      std::ofstream meta(fs::path(temp_) / "metadata.json");
      meta << metadata_json(i, "{z}/{x}/{y}." + ext_) << "\n";
      if (!meta) throw OutputError(temp_ + "/metadata.json: cannot write (disk full?)");
      for (const auto& [name, text] : i.side_files) {
        std::ofstream side(fs::path(temp_) / name);
        side << text;
        if (!side) throw OutputError(temp_ + "/" + name + ": cannot write (disk full?)");
      }
    }
    std::error_code ec;
    if (fs::exists(path_, ec)) {
      if (!force_) throw OutputError(path_ + ": already exists (use --force to replace it)");
      fs::remove_all(path_, ec);
      if (ec) throw OutputError(path_ + ": cannot remove the old output (" + ec.message() + ")");
    }
    fs::rename(temp_, path_, ec);
    if (ec) throw OutputError(path_ + ": cannot rename " + temp_ + " (" + ec.message() + ")");
    finished_ = true;
    return bytes_;
  }
  uint64_t tiles() const override { return tiles_; }

 private:
  std::string path_, temp_, ext_;
  bool force_, tms_, finished_ = false;
  uint64_t bytes_ = 0, tiles_ = 0;
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

std::vector<tileformat::TileId> tiles_in_output_order(tileformat::PackageReader& reader,
                                                      int min_zoom, int max_zoom) {
  std::vector<std::pair<uint64_t, tileformat::TileId>> items;
  for (int z = min_zoom; z <= max_zoom; ++z)
    for (const tileformat::TileId& id : reader.tile_ids(z))
      items.emplace_back(pm::tile_id(z, id.x, id.y), id);
  std::sort(items.begin(), items.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<tileformat::TileId> out;
  out.reserve(items.size());
  for (const auto& [_, id] : items)
    out.push_back(id);
  return out;
}

OutputKind output_kind(const std::string& path) {
  if (ends_with(path, ".pmtiles")) return OutputKind::kPmtiles;
  if (ends_with(path, ".mbtiles")) return OutputKind::kMbtiles;
  return OutputKind::kDirectory;
}

std::unique_ptr<TileOutput> TileOutput::open(const std::string& given, bool force,
                                             const std::string& extension, bool tms_rows) {
  const std::string path = CliArgs::to_output_path(given);  // "out/": the folder "out"
  if (output_kind(path) != OutputKind::kDirectory) check_output_folder(path);
  switch (output_kind(path)) {
    case OutputKind::kPmtiles:
      return std::make_unique<PmtilesOutput>(path, force);
    case OutputKind::kMbtiles:
      return std::make_unique<MbtilesOutput>(path, force);
    default:
      return std::make_unique<DirectoryOutput>(path, force, extension, tms_rows);
  }
}

}  // namespace globe
