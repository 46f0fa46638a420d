// Shared `info` output (see package_info.hpp).
#include "kit/package_info.hpp"

#include <cstdio>
#include <filesystem>

namespace globe {

void print_package_info(tileformat::PackageReader& reader, const std::string& path) {
  std::printf("package: %s\n", path.c_str());
  std::error_code ec;
  std::printf("file size: %llu bytes\n",
              static_cast<unsigned long long>(std::filesystem::file_size(path, ec)));
  std::printf("metadata:\n");
  for (const auto& [k, v] : reader.metadata()) {
    std::string value = v;
    if (value.size() > 100) value = value.substr(0, 97) + "...";
    std::printf("  %-22s %s\n", k.c_str(), value.c_str());
  }
  if (auto it = reader.metadata().find("globe:left_out"); it != reader.metadata().end())
    std::printf("left out: %s\n", it->second.c_str());
  std::printf("zoom levels:\n  %4s %10s %14s %12s  %s\n", "zoom", "tiles", "bytes", "bytes/tile",
              "x range, y range");
  uint64_t tiles = 0, bytes = 0;
  for (const auto& z : reader.zoom_summaries()) {
    std::printf("  %4d %10llu %14llu %12llu  x %u..%u, y %u..%u\n", z.zoom,
                static_cast<unsigned long long>(z.tiles), static_cast<unsigned long long>(z.bytes),
                static_cast<unsigned long long>(z.tiles ? z.bytes / z.tiles : 0), z.min_x, z.max_x,
                z.min_y, z.max_y);
    tiles += z.tiles;
    bytes += z.bytes;
  }
  std::printf("total: %llu tiles, %llu unique blobs, %llu tile bytes\n",
              static_cast<unsigned long long>(tiles),
              static_cast<unsigned long long>(reader.unique_blobs()),
              static_cast<unsigned long long>(bytes));
}

InfoJson package_info_json(tileformat::PackageReader& reader, const std::string& path,
                           tileformat::PackageKind kind) {
  InfoJson info;
  std::error_code ec;
  info.text("package", path)
      .text("kind", tileformat::describe(kind).info_key)
      .integer("file_bytes", std::filesystem::file_size(path, ec));
  InfoJson meta;
  for (const auto& [k, v] : reader.metadata())
    meta.text(k, v);
  info.object("metadata", meta);
  std::vector<InfoJson> zooms;
  uint64_t tiles = 0, bytes = 0;
  for (const auto& z : reader.zoom_summaries()) {
    InfoJson row;
    row.integer("zoom", uint64_t(z.zoom))
        .integer("tiles", z.tiles)
        .integer("bytes", z.bytes)
        .raw("x", "[" + std::to_string(z.min_x) + "," + std::to_string(z.max_x) + "]")
        .raw("y", "[" + std::to_string(z.min_y) + "," + std::to_string(z.max_y) + "]");
    zooms.push_back(row);
    tiles += z.tiles;
    bytes += z.bytes;
  }
  return info.objects("zooms", zooms)
      .integer("tiles", tiles)
      .integer("unique_blobs", reader.unique_blobs())
      .integer("tile_bytes", bytes);
}

void print_info_json(const InfoJson& info) {
  std::printf("%s\n", info.str().c_str());
}

void print_kind_info_json(tileformat::PackageReader& reader, const std::string& path,
                          tileformat::PackageKind kind, const InfoJson& section) {
  print_info_json(
      package_info_json(reader, path, kind).object(tileformat::describe(kind).info_key, section));
}

}  // namespace globe
