// PMTiles v3 writer (see pmtiles.hpp).
#include "tileformat/pmtiles.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include "tileformat/error.hpp"
#include "tileformat/fnv1a.hpp"

namespace tileformat::pmtiles {
namespace {

namespace fs = std::filesystem;

constexpr size_t kHeaderBytes = 127;
constexpr size_t kRootLimit = 16384;  // header + root directory: the first request

void put_varint(std::vector<uint8_t>& out, uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<uint8_t>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<uint8_t>(v));
}

void put_le(std::vector<uint8_t>& out, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i)
    out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

int32_t e7(double degrees) {
  return static_cast<int32_t>(std::lround(std::clamp(degrees, -180.0, 180.0) * 1e7));
}

void write_all(std::FILE* f, const void* data, size_t n, const std::string& path) {
  if (n && std::fwrite(data, 1, n, f) != n)
    throw PackageError(path + ": cannot write (disk full?)");
}

// The directories: the root alone if it fits the first 16 KiB with the
// header, else leaves of `leaf_size` entries (doubled until the root of
// their first ids fits).
struct Directories {
  std::vector<uint8_t> root, leaves;
};

Directories build_directories(const std::vector<Entry>& entries) {
  Directories d;
  d.root = encode_directory(entries);
  if (kHeaderBytes + d.root.size() <= kRootLimit) return d;
  for (size_t leaf_size = 4096;; leaf_size *= 2) {
    d.leaves.clear();
    std::vector<Entry> root;
    for (size_t i = 0; i < entries.size(); i += leaf_size) {
      const size_t n = std::min(leaf_size, entries.size() - i);
      const std::vector<uint8_t> leaf =
          encode_directory(std::span<const Entry>(entries).subspan(i, n));
      root.push_back({entries[i].tile_id, d.leaves.size(), static_cast<uint32_t>(leaf.size()), 0});
      d.leaves.insert(d.leaves.end(), leaf.begin(), leaf.end());
    }
    d.root = encode_directory(root);
    if (kHeaderBytes + d.root.size() <= kRootLimit) return d;
  }
}

}  // namespace

uint64_t tile_id(int z, uint32_t x, uint32_t y) {
  if (z < 0 || z > 31) throw std::invalid_argument("PMTiles zoom out of 0..31");
  const uint64_t n = uint64_t{1} << z;
  if (x >= n || y >= n) throw std::invalid_argument("PMTiles tile outside its zoom");
  uint64_t id = ((uint64_t{1} << (2 * z)) - 1) / 3;  // tiles of the zooms below
  uint64_t tx = x, ty = y;
  for (uint64_t s = n / 2; s > 0; s /= 2) {
    const uint64_t rx = (tx & s) ? 1 : 0, ry = (ty & s) ? 1 : 0;
    id += s * s * ((3 * rx) ^ ry);
    if (ry == 0) {  // rotate the quadrant (Hilbert's recursion)
      if (rx == 1) tx = n - 1 - tx, ty = n - 1 - ty;
      std::swap(tx, ty);
    }
  }
  return id;
}

Zxy tile_zxy(uint64_t id) {
  int z = 0;
  uint64_t first = 0;
  while (z < 31 && id >= first + (uint64_t{1} << (2 * z)))
    first += uint64_t{1} << (2 * z), ++z;
  const uint64_t n = uint64_t{1} << z;
  uint64_t t = id - first, x = 0, y = 0;
  for (uint64_t s = 1; s < n; s *= 2) {
    const uint64_t rx = 1 & (t / 2), ry = 1 & (t ^ rx);
    if (ry == 0) {
      if (rx == 1) x = s - 1 - x, y = s - 1 - y;
      std::swap(x, y);
    }
    x += s * rx, y += s * ry;
    t /= 4;
  }
  return {z, static_cast<uint32_t>(x), static_cast<uint32_t>(y)};
}

std::vector<uint8_t> encode_directory(std::span<const Entry> entries) {
  std::vector<uint8_t> out;
  put_varint(out, entries.size());
  uint64_t last = 0;
  for (const Entry& e : entries) {
    put_varint(out, e.tile_id - last);
    last = e.tile_id;
  }
  for (const Entry& e : entries)
    put_varint(out, e.run_length);
  for (const Entry& e : entries)
    put_varint(out, e.length);
  for (size_t i = 0; i < entries.size(); ++i) {
    const bool follows =
        i > 0 && entries[i].offset == entries[i - 1].offset + entries[i - 1].length;
    put_varint(out, follows ? 0 : entries[i].offset + 1);
  }
  return out;
}

PmtilesWriter::PmtilesWriter(std::string final_path, IfExists if_exists)
    : final_path_(std::move(final_path)),
      temp_path_(final_path_ + ".tmp"),
      data_path_(final_path_ + ".tiles.tmp") {
  std::error_code ec;
  if (if_exists == IfExists::kFail && fs::exists(final_path_, ec))
    throw PackageError(final_path_ + ": already exists (use --force to replace it)");
  data_ = std::fopen(data_path_.c_str(), "w+b");
  if (!data_) throw PackageError(data_path_ + ": cannot create the staging file");
}

PmtilesWriter::~PmtilesWriter() {
  if (data_) std::fclose(data_);
  std::error_code ec;
  fs::remove(data_path_, ec);
  if (!finished_) fs::remove(temp_path_, ec);
}

bool PmtilesWriter::same_bytes(const Entry& stored, std::span<const uint8_t> bytes) {
  if (stored.length != bytes.size()) return false;
  compare_.resize(bytes.size());
  if (std::fseek(data_, static_cast<long>(stored.offset), SEEK_SET) != 0 ||
      std::fread(compare_.data(), 1, compare_.size(), data_) != compare_.size() ||
      std::fseek(data_, 0, SEEK_END) != 0)
    throw PackageError(data_path_ + ": cannot read back the staged tiles");
  return std::equal(compare_.begin(), compare_.end(), bytes.begin());
}

void PmtilesWriter::add(uint64_t id, std::span<const uint8_t> bytes) {
  if (any_ && id <= last_id_)
    throw std::logic_error("PMTiles tiles must come in increasing tile id order");
  any_ = true;
  last_id_ = id;
  if (bytes.empty()) return;
  ++addressed_;
  // A run: the same content as the previous tile, at the next id.
  if (!entries_.empty()) {
    Entry& prev = entries_.back();
    if (prev.tile_id + prev.run_length == id && same_bytes(prev, bytes)) {
      ++prev.run_length;
      return;
    }
  }
  const uint64_t h = fnv1a(bytes);
  std::vector<size_t>& same = by_hash_[h];
  for (size_t i : same)
    if (same_bytes(entries_[i], bytes)) {
      entries_.push_back({id, entries_[i].offset, entries_[i].length, 1});
      return;
    }
  if (bytes.size() > UINT32_MAX) throw PackageError(final_path_ + ": a tile of 4 GiB or more");
  write_all(data_, bytes.data(), bytes.size(), data_path_);
  same.push_back(entries_.size());
  entries_.push_back({id, data_bytes_, static_cast<uint32_t>(bytes.size()), 1});
  data_bytes_ += bytes.size();
  ++contents_;
}

void PmtilesWriter::finish(const ArchiveInfo& info) {
  const std::vector<uint8_t> meta(info.metadata_json.begin(), info.metadata_json.end());
  const Directories dirs = build_directories(entries_);
  const uint64_t root_at = kHeaderBytes, meta_at = root_at + dirs.root.size(),
                 leaves_at = meta_at + meta.size(), data_at = leaves_at + dirs.leaves.size();
  std::vector<uint8_t> head;
  head.insert(head.end(), {'P', 'M', 'T', 'i', 'l', 'e', 's', 3});
  for (uint64_t v : {root_at, uint64_t(dirs.root.size()), meta_at, uint64_t(meta.size()), leaves_at,
                     uint64_t(dirs.leaves.size()), data_at, data_bytes_, addressed_,
                     uint64_t(entries_.size()), contents_})
    put_le(head, v, 8);
  head.push_back(1);                                         // clustered
  head.push_back(static_cast<uint8_t>(Compression::kNone));  // internal compression
  head.push_back(static_cast<uint8_t>(info.tile_compression));
  head.push_back(static_cast<uint8_t>(info.tile_type));
  head.push_back(static_cast<uint8_t>(std::clamp(info.min_zoom, 0, 31)));
  head.push_back(static_cast<uint8_t>(std::clamp(info.max_zoom, 0, 31)));
  for (double d : {info.min_lon, info.min_lat, info.max_lon, info.max_lat})
    put_le(head, static_cast<uint32_t>(e7(d)), 4);
  head.push_back(static_cast<uint8_t>(std::clamp(info.center_zoom, 0, 31)));
  put_le(head, static_cast<uint32_t>(e7(info.center_lon)), 4);
  put_le(head, static_cast<uint32_t>(e7(info.center_lat)), 4);
  if (head.size() != kHeaderBytes) throw std::logic_error("PMTiles header size");

  std::FILE* out = std::fopen(temp_path_.c_str(), "wb");
  if (!out) throw PackageError(temp_path_ + ": cannot create");
  try {
    for (const std::vector<uint8_t>* part :
         std::initializer_list<const std::vector<uint8_t>*>{&head, &dirs.root, &meta, &dirs.leaves})
      write_all(out, part->data(), part->size(), temp_path_);
    if (std::fflush(data_) != 0 || std::fseek(data_, 0, SEEK_SET) != 0)
      throw PackageError(data_path_ + ": cannot read back the staged tiles");
    std::vector<uint8_t> buf(1 << 20);
    for (size_t n; (n = std::fread(buf.data(), 1, buf.size(), data_)) > 0;)
      write_all(out, buf.data(), n, temp_path_);
    if (std::ferror(data_)) throw PackageError(data_path_ + ": cannot read back the staged tiles");
    if (std::fflush(out) != 0) throw PackageError(temp_path_ + ": cannot write (disk full?)");
  } catch (...) {
    std::fclose(out);
    throw;
  }
  if (std::fclose(out) != 0) throw PackageError(temp_path_ + ": cannot write (disk full?)");
  std::error_code ec;
  fs::rename(temp_path_, final_path_, ec);
  if (ec) throw PackageError(final_path_ + ": cannot rename the finished archive: " + ec.message());
  finished_ = true;
  final_bytes_ = data_at + data_bytes_;
}

}  // namespace tileformat::pmtiles
