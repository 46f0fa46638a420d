// Image tiles of one image package on their way to the GPU (docs/viewer.md
// "Imagery"): a fixed number of texture-array slots sized from the memory
// budget. The imagery pass reports the tiles its pixels wanted but did not
// find and the slots it read; the cache checks that a wanted tile exists,
// decodes it on a loader thread (PNG, JPEG or WebP, without GDAL) into
// premultiplied RGBA with its mip chain, and gives it a slot, evicting the
// least recently used tile the last frame did not read. Tiles the package
// lacks are known as absent (their pixels show the layer below); tiles that
// fail to decode are reported once on stderr and known as broken (their
// pixels show the finer tiles under them, one or two zooms down, where the
// package has them, else the nearest coarser tile: issue 55).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "data/block_cache.hpp"
#include "data/tile_loader.hpp"
#include "runtime/image_package.hpp"

namespace globe::viewer {

// Table values besides slot numbers (render/tile_table.hpp).
inline constexpr uint32_t kImageAbsent = 0xFFFFFFFEu;
inline constexpr uint32_t kImageBroken = 0xFFFFFFFDu;

// A decoded tile: premultiplied RGBA mip levels, finest first.
struct ImageMips {
  std::vector<std::vector<uint8_t>> levels;
};

// Decodes a tile blob into premultiplied RGBA mips (exposed for tests);
// throws std::runtime_error unless it is a size x size PNG, JPEG or WebP.
ImageMips decode_image_mips(std::span<const uint8_t> blob, int size);

struct ImageCacheStats {
  size_t slots = 0, resident = 0, known_absent = 0, loading = 0;
  uint64_t loaded = 0, evictions = 0, broken = 0, bytes_read = 0;
};

class ImageCache {
 public:
  // `slots`: texture layers this package may use.
  ImageCache(const std::string& path, ImagePackage package, int slots);
  ~ImageCache();
  ImageCache(const ImageCache&) = delete;
  ImageCache& operator=(const ImageCache&) = delete;

  const std::string& path() const { return path_; }
  const ImagePackage& package() const { return package_; }
  int slots() const { return slots_; }
  int levels() const;  // mip levels of a tile

  void begin_frame() { ++frame_; }
  void mark_used(uint32_t slot);
  // Returns whether the request was news: a tile now loading or now known
  // absent (false for tiles already known and for tiles past the tiling).
  bool request(tileformat::TileId id);
  void flush_requests();
  // Decoded tiles placed in slots: upload each (slot, mips) now.
  std::vector<std::pair<uint32_t, ImageMips>> take_loaded();
  // Every known tile -> its slot, kImageAbsent or kImageBroken.
  std::vector<std::pair<tileformat::TileId, uint32_t>> table() const;
  void wait_for_loader() { loader_->wait_all(); }
  bool loader_busy() { return loader_->busy(); }
  ImageCacheStats stats() const;

 private:
  using Loader = TileLoader<ImageMips>;
  struct Entry {
    bool loading = false;
    uint32_t value = kImageAbsent;  // slot, kImageAbsent or kImageBroken once known
    uint64_t last_used = 0;
  };
  // A free slot, evicting the least recently used tile the last frame did
  // not read; -1 if every slot is in view.
  int take_slot();

  std::string path_;
  ImagePackage package_;
  int slots_;
  uint64_t frame_ = 0;
  std::unordered_map<tileformat::TileId, Entry, TileKey> entries_;
  std::vector<tileformat::TileId> slot_tile_;  // per slot; z = -1 when free
  std::vector<uint64_t> slot_used_;
  std::vector<Loader::Job> wanted_;
  ImageCacheStats stats_;
  std::unique_ptr<Loader> loader_;
};

}  // namespace globe::viewer
