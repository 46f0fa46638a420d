// Flow at every zoom (see flow_pyramid.hpp).
#include "analysis/flow/flow_pyramid.hpp"

#include <algorithm>

namespace globe::flow {

LevelShape level_shape(const FlowGrid& g, int64_t f) {
  LevelShape s;
  s.wraps = g.wraps();
  s.width = g.wraps() ? g.width() / f : (g.width() - 1) / f + 1;
  s.height = (g.height() - 1) / f + 1;
  return s;
}

namespace {

int64_t wrap_delta(int64_t d, const LevelShape& s) {
  if (s.wraps) {
    if (d > 1) d -= s.width;
    if (d < -1) d += s.width;
  }
  return d;
}

}  // namespace

LevelGrid coarsen(const LevelGrid& c, const LevelShape& cs, const LevelShape& ps) {
  LevelGrid p;
  p.x0 = c.x0 / 2, p.y0 = c.y0 / 2;
  p.w = int((c.x0 + c.w - 1) / 2 - p.x0 + 1);
  p.h = int((c.y0 + c.h - 1) / 2 - p.y0 + 1);
  p.area.assign(size_t(p.w) * p.h, 0);
  p.code.assign(size_t(p.w) * p.h, kNoDataCode);
  for (int y = 0; y < p.h; ++y)
    for (int x = 0; x < p.w; ++x) {
      const int64_t px = p.x0 + x, py = p.y0 + y;
      int64_t best = -1, bx = 0, by = 0;
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const int64_t cx = 2 * px + i - c.x0, cy = 2 * py + j - c.y0;
          if (cx >= c.w || cy >= c.h) continue;
          const size_t k = size_t(cy) * c.w + size_t(cx);
          if (c.code[k] == kNoDataCode) continue;
          if (best < 0 || c.area[k] > c.area[size_t(best)]) {
            best = int64_t(k);
            bx = cx + c.x0, by = cy + c.y0;
          }
        }
      if (best < 0) continue;
      const size_t out = size_t(y) * p.w + x;
      p.area[out] = c.area[size_t(best)];
      const uint8_t d = c.code[size_t(best)];
      if (d == kOutlet) {
        p.code[out] = kOutlet;
        continue;
      }
      int64_t rx = bx + kDx[d];
      const int64_t ry = by + kDy[d];
      if (cs.wraps) rx = ((rx % cs.width) + cs.width) % cs.width;
      const int64_t ddx = wrap_delta(rx / 2 - px, ps), ddy = ry / 2 - py;
      p.code[out] = d8_code(int(ddx), int(ddy));  // (0, 0) cannot happen: outlet
    }
  return p;
}

FlowPyramid::FlowPyramid(const FlowGrid& g, int min_zoom, const std::string& prefix, bool in_memory)
    : grid_(g) {
  levels_ = g.zoom() - min_zoom + 1;
  int in_chunks = 1;
  while (in_chunks < levels_ && (int64_t(1) << in_chunks) <= g.chunk_size())
    ++in_chunks;
  in_chunks_ = in_chunks;
  const auto& chunks = g.chunks();
  tops_.resize(chunks.size());
  if (in_memory) {
    held_.assign(size_t(in_chunks_), std::vector<LevelGrid>(chunks.size()));
    return;
  }
  for (int l = 0; l < in_chunks_; ++l) {
    std::vector<uint64_t> off(chunks.size() + 1, 0);
    for (size_t s = 0; s < chunks.size(); ++s) {
      const Part pt = part(l, int(s));
      off[s + 1] = off[s] + uint64_t(pt.w) * pt.h * 9;
    }
    offsets_.push_back(std::move(off));
    files_.push_back(
        std::make_unique<ScratchArrayFile>(prefix + "level" + std::to_string(l) + ".bin"));
  }
}

FlowPyramid::Part FlowPyramid::part(int level, int slot) const {
  const Chunk& c = grid_.chunks()[size_t(slot)];
  const int64_t f = int64_t(1) << level;
  Part p;
  p.x0 = c.x0 / f, p.y0 = c.y0 / f;
  p.w = int((c.x0 + c.w - 1) / f - p.x0 + 1);
  p.h = int((c.y0 + c.h - 1) / f - p.y0 + 1);
  return p;
}

void FlowPyramid::put_chunk(int slot, LevelGrid g) {
  for (int l = 0; l < in_chunks_; ++l) {
    if (l > 0) {
      const LevelGrid& child = held_.empty() ? g : held_[size_t(l - 1)][size_t(slot)];
      g = coarsen(child, level_shape(grid_, int64_t(1) << (l - 1)),
                  level_shape(grid_, int64_t(1) << l));
    }
    if (!held_.empty()) {
      // Kept as they are: no copy (each slot's entry is its own).
      held_[size_t(l)][size_t(slot)] = std::move(g);
      continue;
    }
    const Part p = part(l, slot);
    const size_t n = size_t(p.w) * p.h;
    files_[size_t(l)]->write_array<uint64_t>(offset(l, slot), g.area);
    files_[size_t(l)]->write_array<uint8_t>(offset(l, slot) + n * 8, g.code);
  }
  std::lock_guard lock(mutex_);
  tops_[size_t(slot)] = held_.empty() ? std::move(g) : held_[size_t(in_chunks_ - 1)][size_t(slot)];
}

void FlowPyramid::finish() {
  if (in_chunks_ >= levels_) return;
  // The whole of the coarsest chunk level, then coarser levels from it.
  const LevelShape top = level_shape(grid_, int64_t(1) << (in_chunks_ - 1));
  LevelGrid whole;
  whole.w = int(top.width), whole.h = int(top.height);
  whole.area.assign(size_t(whole.w) * whole.h, 0);
  whole.code.assign(size_t(whole.w) * whole.h, kNoDataCode);
  for (const LevelGrid& t : tops_)
    for (int y = 0; y < t.h; ++y)
      for (int x = 0; x < t.w; ++x) {
        const size_t k = size_t(t.y0 + y) * whole.w + size_t(t.x0 + x);
        whole.area[k] = t.area[size_t(y) * t.w + x];
        whole.code[k] = t.code[size_t(y) * t.w + x];
      }
  tops_.clear();
  for (int l = in_chunks_; l < levels_; ++l) {
    whole = coarsen(whole, level_shape(grid_, int64_t(1) << (l - 1)),
                    level_shape(grid_, int64_t(1) << l));
    coarse_.push_back(whole);
  }
}

void FlowPyramid::block(tileformat::TileId id, int size, std::vector<uint64_t>& area,
                        std::vector<uint8_t>& code) const {
  area.assign(size_t(size) * size, 0);
  code.assign(size_t(size) * size, kNoDataCode);
  const int level = grid_.zoom() - id.z;
  if (level < 0 || level >= levels_) return;
  const int64_t f = int64_t(1) << level;
  const LevelShape shape = level_shape(grid_, f);
  const int64_t steps = size - 1;
  const int64_t bx = int64_t(id.x) * steps, by = int64_t(id.y) * steps;
  if (level >= in_chunks_) {
    const LevelGrid& g = coarse_[size_t(level - in_chunks_)];
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        int64_t gx = bx + x;
        const int64_t gy = by + y;
        if (shape.wraps) gx %= shape.width;
        if (gx >= g.w || gy >= g.h) continue;
        area[size_t(y) * size + x] = g.area[size_t(gy) * g.w + size_t(gx)];
        code[size_t(y) * size + x] = g.code[size_t(gy) * g.w + size_t(gx)];
      }
    return;
  }
  for (int y = 0; y < size; ++y) {
    const int64_t gy = by + y;
    if (gy >= shape.height) break;
    for (int x = 0; x < size;) {
      int64_t gx = bx + x;
      if (shape.wraps) gx %= shape.width;
      if (gx >= shape.width) break;
      const int slot = grid_.slot_of(gx * f, gy * f);
      if (slot < 0) {
        ++x;
        continue;
      }
      const Part p = part(level, slot);
      const int run = int(std::min<int64_t>(size - x, p.x0 + p.w - gx));
      const size_t n = size_t(p.w) * p.h, at = size_t(gy - p.y0) * p.w + size_t(gx - p.x0);
      const size_t out = size_t(y) * size + x;
      if (!held_.empty()) {
        const LevelGrid& held = held_[size_t(level)][size_t(slot)];
        std::copy_n(held.area.begin() + ptrdiff_t(at), run, area.begin() + ptrdiff_t(out));
        std::copy_n(held.code.begin() + ptrdiff_t(at), run, code.begin() + ptrdiff_t(out));
        x += run;
        continue;
      }
      const uint64_t base = offset(level, slot);
      const ScratchArrayFile& file = *files_[size_t(level)];
      file.read_array<uint64_t>(base + at * 8, std::span(area.data() + out, size_t(run)));
      file.read_array<uint8_t>(base + n * 8 + at, std::span(code.data() + out, size_t(run)));
      x += run;
    }
  }
}

}  // namespace globe::flow
