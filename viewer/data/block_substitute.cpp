// Broken blocks remade from their children or parent (see block_substitute.hpp).
#include "data/block_substitute.hpp"

#include <algorithm>
#include <cmath>

namespace globe::viewer {

using tileformat::TileId;

namespace {

// The grid of `id`, or (broken) its stand-in from its children down to
// `depth` more levels; nullopt where neither has data.
std::optional<SampleGrid> grid_or_children(const SubstituteSource& s, TileId id, int depth);

std::optional<SampleGrid> children_grid(const SubstituteSource& s, TileId id, int depth) {
  if (id.z >= s.max_zoom) return std::nullopt;
  std::optional<SampleGrid> children[2][2];
  bool any = false;
  for (uint32_t cy = 0; cy < 2; ++cy)
    for (uint32_t cx = 0; cx < 2; ++cx) {
      children[cy][cx] = grid_or_children(s, {id.z + 1, 2 * id.x + cx, 2 * id.y + cy}, depth);
      any = any || children[cy][cx].has_value();
    }
  if (!any) return std::nullopt;
  int channels = 1;
  for (const auto& row : children)
    for (const auto& c : row)
      if (c) channels = c->channels;
  return from_children(children, s.block_size, channels);
}

std::optional<SampleGrid> grid_or_children(const SubstituteSource& s, TileId id, int depth) {
  try {
    return s.read(id);
  } catch (const std::exception&) {
    if (depth <= 0) return std::nullopt;
    return children_grid(s, id, depth - 1);
  }
}

// The parent's grid, or (broken) its own parent's, up to the coarsest zoom.
std::optional<SampleGrid> parent_grid(const SubstituteSource& s, TileId id) {
  if (id.z <= s.min_zoom) return std::nullopt;
  const TileId p{id.z - 1, id.x / 2, id.y / 2};
  std::optional<SampleGrid> g;
  try {
    g = s.read(p);
  } catch (const std::exception&) {
    g = parent_grid(s, p);
  }
  if (!g) return std::nullopt;
  return from_parent(*g, int(id.x % 2), int(id.y % 2));
}

}  // namespace

SampleGrid from_children(const std::optional<SampleGrid> (&children)[2][2], int size,
                         int channels) {
  SampleGrid out;
  out.size = size;
  out.channels = channels;
  out.values.assign(size_t(size) * size * channels, 0.0f);
  out.mask.assign(size_t(size) * size, 0);
  const int half = (size - 1) / 2;
  for (int cy = 0; cy < 2; ++cy)
    for (int cx = 0; cx < 2; ++cx) {
      const std::optional<SampleGrid>& c = children[cy][cx];
      if (!c || c->size != size || c->channels != channels) continue;
      // Sample (i, j) of this quadrant is the child's sample (2i, 2j); the
      // quadrants share their middle row and column, which both children hold.
      for (int j = 0; j <= half; ++j)
        for (int i = 0; i <= half; ++i) {
          const size_t to = size_t(cy * half + j) * size + size_t(cx * half + i);
          const size_t from = size_t(2 * j) * size + size_t(2 * i);
          std::copy_n(c->values.begin() + long(from * channels), channels,
                      out.values.begin() + long(to * channels));
          out.mask[to] = std::max(out.mask[to], c->mask[from]);
        }
    }
  return out;
}

SampleGrid from_parent(const SampleGrid& parent, int qx, int qy) {
  const int size = parent.size, half = (size - 1) / 2, c = parent.channels;
  SampleGrid out;
  out.size = size;
  out.channels = c;
  out.values.assign(size_t(size) * size * c, 0.0f);
  out.mask.assign(size_t(size) * size, 0);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      // This sample lies at parent sample (qx half + i/2, qy half + j/2):
      // on a parent sample at even i and j, between two or four otherwise.
      const int x0 = qx * half + i / 2, y0 = qy * half + j / 2;
      const int x1 = std::min(x0 + (i & 1), size - 1), y1 = std::min(y0 + (j & 1), size - 1);
      const size_t a = size_t(y0) * size + x0, b = size_t(y0) * size + x1,
                   d = size_t(y1) * size + x0, e = size_t(y1) * size + x1;
      const size_t to = size_t(j) * size + i;
      out.mask[to] = std::min({parent.mask[a], parent.mask[b], parent.mask[d], parent.mask[e]});
      for (int k = 0; k < c; ++k)
        out.values[to * c + k] = 0.25f * (parent.values[a * c + k] + parent.values[b * c + k] +
                                          parent.values[d * c + k] + parent.values[e * c + k]);
    }
  return out;
}

std::pair<std::optional<SampleGrid>, Stand> substitute_grid(const SubstituteSource& source,
                                                            TileId id) {
  if (auto g = children_grid(source, id, 1)) return {std::move(g), Stand::kChildren};
  if (auto g = parent_grid(source, id)) return {std::move(g), Stand::kParent};
  return {std::nullopt, Stand::kNone};
}

}  // namespace globe::viewer
