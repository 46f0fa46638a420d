// MBlock: the height block of one terrain tile (docs/tileformat.md §5).
// (steps+1)^2 samples on the global quantization grid (height = q * step),
// a validity mask, and the block's KPatch error tree (one saturated error per
// split vertex, §6). encode_mblock/decode_mblock are exact inverses.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tileformat {

struct MBlock {
  int size = 0;            // samples per side: 2^k + 1
  int lattice = 16;        // KPatch lattice L (§6)
  double step = 1.0;       // metres per quantum
  std::vector<int32_t> q;  // size*size quantized heights, row-major, north row first
  std::vector<uint8_t>
      valid;  // empty = all valid; else size*size, 1 = data, 0 = hole (filled in q)
  std::vector<uint32_t> vertex_error;  // kpatch_vertex_count(D) errors in quanta (rounded up)

  int steps() const { return size - 1; }
  double height(int x, int y) const { return q[static_cast<size_t>(y) * size + x] * step; }
  bool is_valid(int x, int y) const {
    return valid.empty() || valid[static_cast<size_t>(y) * size + x] != 0;
  }
};

struct MBlockStats {
  int32_t qmin = 0, qmax = 0;  // over valid samples
};

// Preconditions (checked, std::invalid_argument): size = 2^k+1 with
// 2^k >= 2*lattice, q/valid/vertex_error sized as documented, step > 0.
// kBestPacking tries every height coding of §5.2 and keeps the smallest;
// kBytePlanes always uses byte planes (faster, for scratch data).
enum class HeightCoding { kBytePlanes, kBestPacking };
std::vector<uint8_t> encode_mblock(const MBlock& block, int zstd_level = 9,
                                   HeightCoding coding = HeightCoding::kBestPacking);

// The same blob with another error tree (§5.4); heights and mask are copied,
// not re-encoded. Throws FormatError for a malformed blob.
std::vector<uint8_t> replace_vertex_errors(std::span<const uint8_t> blob,
                                           const std::vector<uint32_t>& errors, int zstd_level = 9);

// Throws FormatError citing §4/§5 for anything malformed.
MBlock decode_mblock(std::span<const uint8_t> blob);
MBlockStats mblock_stats(const MBlock& block);

// A square grid of quantized heights with its validity, coded like an
// MBlock's heights (§5.2) and mask (§5.3) but without header, error tree or
// blob wrapper: builders' intermediate blocks (any size 1..65535), never a
// package tile.
struct HeightGrid {
  int size = 0;
  std::vector<int32_t> q;      // size * size
  std::vector<uint8_t> valid;  // size * size, 1 = data
};
std::vector<uint8_t> encode_height_grid(const HeightGrid& grid, int zstd_level,
                                        HeightCoding coding);
// Throws FormatError for malformed bytes.
HeightGrid decode_height_grid(std::span<const uint8_t> bytes);

// Largest |q| the format accepts (heights beyond it need a larger step).
// Bound so that every 2D-predictor residual fits an int32 (|r| <= 4 * kMaxQuantum).
inline constexpr int32_t kMaxQuantum = (int32_t{1} << 29) - 1;

}  // namespace tileformat
