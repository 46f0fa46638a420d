// mblock_entropy PACKAGE: how many bits the heights of a terrain package's
// MBlocks would take under other codings than the one it stores (issue 40,
// part 1), as empirical entropies of the residuals (per block, with or
// without the cost of sending each block's model):
//   planar   p = W + N - NW (what the package stores, docs/tileformat.md §5.2)
//   MED      JPEG-LS's median edge detector
//   +ctx     the residual's distribution conditioned on the magnitude of the
//            residuals west and north (an adaptive context coder's reach)
//   refine   every block but the roots coded as a refinement of its parent:
//            the nested samples (every other row and column) are the
//            parent's; the others are predicted by a cubic through the known
//            samples on their row, then on their column.
// Stored: the blobs' bytes (heights, mask and error trees, zstd); stored
// heights: the heights and mask alone, coded as the package codes them.
// Also: how fast the blobs decode (decode_mblock, one thread, repeated for at
// least half a second), in samples and in MB of 32-bit heights per second.
// Prints one table on stdout. Exit 1 for an unreadable package.
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <vector>

#include "tileformat/mblock.hpp"
#include "tileformat/package.hpp"

namespace {

using tileformat::MBlock;
using tileformat::TileId;

// Residual histograms per context; bits() is their empirical entropy, plus
// 16 bits per distinct residual per context when the model is sent.
class Entropy {
 public:
  void add(int context, int64_t residual) { ++hist_[context][residual]; }
  double bits(bool with_model) const {
    double e = 0;
    for (const auto& [c, m] : hist_) {
      uint64_t n = 0;
      for (const auto& [r, k] : m)
        n += k;
      for (const auto& [r, k] : m)
        e -= double(k) * std::log2(double(k) / double(n));
      if (with_model) e += 16.0 * double(m.size());
    }
    return e;
  }

 private:
  std::map<int, std::map<int64_t, uint64_t>> hist_;
};

int magnitude_bucket(int64_t a) {
  return std::min(12, int(std::bit_width(uint64_t(a))));
}

struct Totals {
  double planar[2] = {0, 0}, med[2] = {0, 0}, planar_ctx[2] = {0, 0}, refine[2] = {0, 0};
};

void add(double (&t)[2], const Entropy& e) {
  t[0] += e.bits(false);
  t[1] += e.bits(true);
}

// Planar and MED residuals of one block, order 0 and in context.
void code_flat(const MBlock& b, Totals& t, double (&planar_ctx_bits)[2]) {
  const int s = b.size;
  auto q = [&](int x, int y) { return int64_t{b.q[size_t(y) * s + x]}; };
  std::vector<int64_t> res(size_t(s) * s);
  Entropy planar, med, planar_ctx;
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      int64_t p = x ? q(x - 1, y) : (y ? q(x, y - 1) : 0), m = p;
      if (x && y) {
        const int64_t w = q(x - 1, y), n = q(x, y - 1), nw = q(x - 1, y - 1);
        p = w + n - nw;
        const int64_t lo = std::min(w, n), hi = std::max(w, n);
        m = nw >= hi ? lo : (nw <= lo ? hi : p);
      }
      const int64_t r = q(x, y) - p;
      res[size_t(y) * s + x] = r;
      planar.add(0, r);
      med.add(0, q(x, y) - m);
      const int64_t around = (x ? std::llabs(res[size_t(y) * s + x - 1]) : 0) +
                             (y ? std::llabs(res[size_t(y - 1) * s + x]) : 0);
      planar_ctx.add(magnitude_bucket(around), r);
    }
  add(t.planar, planar);
  add(t.med, med);
  planar_ctx_bits[0] = planar_ctx.bits(false);
  planar_ctx_bits[1] = planar_ctx.bits(true);
  t.planar_ctx[0] += planar_ctx_bits[0];
  t.planar_ctx[1] += planar_ctx_bits[1];
}

// The block as a refinement of `parent`; false if a nested sample differs
// from the parent's (then it cannot be coded so).
bool code_refinement(const MBlock& b, const MBlock& parent, TileId id, Totals& t) {
  const int n = b.size - 1;
  auto q = [&](int x, int y) {
    return int64_t{b.q[size_t(std::clamp(y, 0, n)) * b.size + std::clamp(x, 0, n)]};
  };
  const int ox = int(id.x & 1) * n / 2, oy = int(id.y & 1) * n / 2;
  for (int y = 0; y <= n; y += 2)
    for (int x = 0; x <= n; x += 2)
      if (b.is_valid(x, y) && parent.q[size_t(oy + y / 2) * b.size + ox + x / 2] != q(x, y))
        return false;
  auto cubic = [](int64_t a, int64_t b0, int64_t c, int64_t d) {
    return (-a + 9 * b0 + 9 * c - d + 8) >> 4;
  };
  Entropy e;
  for (int y = 0; y <= n; y += 2)  // between the row's nested samples
    for (int x = 1; x < n; x += 2)
      e.add(magnitude_bucket(std::llabs(q(x - 1, y) - q(x + 1, y))),
            q(x, y) - cubic(q(x - 3, y), q(x - 1, y), q(x + 1, y), q(x + 3, y)));
  for (int y = 1; y < n; y += 2)  // then every sample of the rows between
    for (int x = 0; x <= n; ++x)
      e.add(13 + magnitude_bucket(std::llabs(q(x, y - 1) - q(x, y + 1))),
            q(x, y) - cubic(q(x, y - 3), q(x, y - 1), q(x, y + 1), q(x, y + 3)));
  add(t.refine, e);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mblock_entropy TERRAIN.mbtiles\n");
    return 2;
  }
  try {
    tileformat::PackageReader reader(argv[1]);
    std::map<TileId, MBlock> blocks;
    uint64_t stored = 0, heights = 0, samples = 0, refined = 0;
    std::vector<std::vector<uint8_t>> blobs;
    reader.for_each_tile([&](TileId id, std::span<const uint8_t> blob) {
      stored += blob.size();
      blocks[id] = tileformat::decode_mblock(blob);
      blobs.emplace_back(blob.begin(), blob.end());
    });
    uint64_t decoded = 0;
    const auto t0 = std::chrono::steady_clock::now();
    double seconds = 0;
    while (seconds < 0.5) {
      for (const std::vector<uint8_t>& blob : blobs)
        decoded += tileformat::decode_mblock(blob).q.size();
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    Totals t;
    for (const auto& [id, b] : blocks) {
      samples += uint64_t(b.size) * b.size;
      tileformat::HeightGrid g{b.size, b.q, b.valid};
      if (g.valid.empty()) g.valid.assign(b.q.size(), 1);
      heights +=
          tileformat::encode_height_grid(g, 9, tileformat::HeightCoding::kBestPacking).size();
      double flat[2];
      code_flat(b, t, flat);
      const auto parent = id.z > 0 ? blocks.find({id.z - 1, id.x / 2, id.y / 2}) : blocks.end();
      if (parent != blocks.end() && code_refinement(b, parent->second, id, t)) {
        ++refined;
      } else {  // a root: coded on its own
        t.refine[0] += flat[0];
        t.refine[1] += flat[1];
      }
    }
    const double n = double(samples);
    std::printf("%s: %zu blocks (%llu refined), %llu samples; bits per sample\n", argv[1],
                blocks.size(), static_cast<unsigned long long>(refined),
                static_cast<unsigned long long>(samples));
    std::printf("  %-22s %8s %12s\n", "coding", "entropy", "+ models");
    std::printf("  %-22s %8.3f %12s\n", "stored (whole blobs)", 8.0 * double(stored) / n, "");
    std::printf("  %-22s %8.3f %12s\n", "stored heights", 8.0 * double(heights) / n, "");
    auto row = [&](const char* name, const double(&b)[2]) {
      std::printf("  %-22s %8.3f %12.3f\n", name, b[0] / n, b[1] / n);
    };
    row("planar", t.planar);
    row("MED", t.med);
    row("planar + ctx", t.planar_ctx);
    row("refine + ctx", t.refine);
    std::printf("  decode: %.0f M samples/s (%.0f MB/s of 32-bit heights)\n",
                double(decoded) / seconds / 1e6, 4.0 * double(decoded) / seconds / 1e6);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mblock_entropy: %s: %s\n", argv[1], e.what());
    return 1;
  }
}
