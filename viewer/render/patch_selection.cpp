// KPatch selection over the global 4-8 hierarchy (see patch_selection.hpp).
#include "render/patch_selection.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "camera/ellipsoid.hpp"
#include "tileformat/package.hpp"

namespace globe::viewer {

using tileformat::TileId;

namespace {

int ceil_half(int v) {
  return v >= 0 ? (v + 1) / 2 : -((-v) / 2);
}

// Radius of a sphere around a split vertex holding every descendant's sphere:
// r(G) = r(G+1) + hyp(G+1)/2 summed over all finer levels = hyp(G) / (2 (sqrt2 - 1)).
constexpr double kNestingRadius = 1.2072;

// A node much larger than its distance from the eye is split even where its
// error is zero: a triangle reaching thousands of kilometres past a nearby
// eye loses float precision in clipping (llvmpipe dropped half of one over a
// flat geodetic package). Both sides shrink together down the hierarchy, so
// the rule stays nested like the error rule.
constexpr double kMaxSpanPerDistance = 4.0;

}  // namespace

PatchSelector::PatchSelector(const TerrainPackage& package)
    : layout_(package.block_size - 1, package.lattice, 0),
      steps_(package.block_size - 1),
      lattice_(package.lattice),
      depth_(layout_.depth()),
      min_zoom_(package.min_zoom),
      max_zoom_(package.max_zoom),
      step_m_(package.step_m) {
  extent_x_ = (int64_t{steps_} << max_zoom_) * package.tiling.roots_x;
  extent_y_ = (int64_t{steps_} << max_zoom_) * package.tiling.roots_y;
  roots_ = package.reader->tile_ids(min_zoom_);
}

int PatchSelector::canonical_zoom(int level) const {
  return std::max(min_zoom_, ceil_half(level - depth_));
}

int PatchSelector::error_zoom(int level) const {
  return std::max(min_zoom_, ceil_half(level - depth_ + 1));
}

TileId PatchSelector::tile_at(int z, int64_t kx, int64_t ky) const {
  const int64_t t = int64_t{steps_} << (max_zoom_ - z);
  return {z, static_cast<uint32_t>(kx / t), static_cast<uint32_t>(ky / t)};
}

bool PatchSelector::in_extent(const KeyPoint& p) const {
  return p.x >= 0 && p.y >= 0 && p.x <= extent_x_ && p.y <= extent_y_;
}

void PatchSelector::parents(const KeyPoint& v, int level, KeyPoint out[2], int& count) const {
  const auto p = tileformat::vertex_parents({v.x, v.y}, level, int64_t{steps_} << max_zoom_);
  count = 0;
  for (const tileformat::LatticePoint& q : p)
    if (in_extent({q.x, q.y})) out[count++] = {q.x, q.y};
}

bool PatchSelector::active(const KeyPoint& v, int level) {
  if (level < 2 * min_zoom_) return true;  // above the roots: always split
  if (auto it = memo_.find(v); it != memo_.end()) return it->second;
  ++stats_.vertices_evaluated;
  bool result = false;
  const int z = error_zoom(level);
  if (z <= max_zoom_) {
    const int d = level - 2 * z;
    const int shift = max_zoom_ - z;
    const int64_t t = int64_t{steps_} << shift;
    // A vertex on a tile border is stored identically in both blocks.
    int64_t xs[2] = {v.x / t, -1}, ys[2] = {v.y / t, -1};
    if (v.x % t == 0 && v.x > 0) xs[1] = xs[0] - 1;
    if (v.y % t == 0 && v.y > 0) ys[1] = ys[0] - 1;
    const ResidentBlock* block = nullptr;
    int64_t bx = 0, by = 0;
    bool exists = false;
    std::vector<TileId> missing;
    for (int64_t tx : xs)
      for (int64_t ty : ys) {
        if (tx < 0 || ty < 0 || block) continue;
        const TileId id{z, static_cast<uint32_t>(tx), static_cast<uint32_t>(ty)};
        const BlockState st = cache_->state(id);
        if (st == BlockState::kAbsent) continue;
        exists = true;
        if (st == BlockState::kResident) {
          block = cache_->use(id);
          bx = tx, by = ty;
        } else if (st == BlockState::kNotLoaded) {
          missing.push_back(id);
        }
      }
    if (block) {
      const int lx = static_cast<int>((v.x - bx * t) >> shift);
      const int ly = static_cast<int>((v.y - by * t) >> shift);
      const size_t index = layout_.vertex_at(d, {lx, ly});
      const double error = block->vertex_error.at(index) * error_scale_;
      const glm::dvec3 w = frame_->key_to_world(double(v.x), double(v.y), 0, view_->origin);
      const int64_t root = int64_t{steps_} << max_zoom_;
      const double side = double(root >> (level >> 1)) * metres_per_key_;
      const double hyp = level % 2 == 0 ? side * std::sqrt(2.0) : side;
      double dist, geometric = 0;
      if (frame_->globe()) {
        // A sphere around v holding its descendants and their heights; the
        // flat triangles of a node stand below the curved surface by up to
        // their sagitta, an error that shrinks down the hierarchy.
        dist = std::max(0.0, glm::length(w - view_->eye) - kNestingRadius * hyp - height_pad_);
        geometric = hyp * hyp / (8 * wgs84::kB);
      } else {
        const double dh = std::max(
            0.0, std::hypot(w.x - view_->eye.x, w.y - view_->eye.y) - kNestingRadius * hyp);
        const double dv = std::max(0.0, view_->eye.z - z_top_world_);
        dist = std::hypot(dh, dv);
      }
      result =
          dist <= 0 ||
          std::max(error, geometric) * view_->pixels_per_radian / dist > settings_.max_error_px ||
          hyp > kMaxSpanPerDistance * dist || block->split_through;
    } else if (exists) {
      ++stats_.waiting;
      for (const TileId& id : missing)
        cache_->request(id, z);
    } else {
      result = true;  // no data under this diamond: splitting drops empty triangles
    }
  }
  if (result) {
    KeyPoint p[2];
    int count = 0;
    parents(v, level, p, count);
    for (int i = 0; i < count && result; ++i)
      result = active(p[i], level - 1);
  }
  memo_[v] = result;
  return result;
}

void PatchSelector::visit(const Node& n) {
  ++stats_.nodes_visited;
  const int z = canonical_zoom(n.level);
  const KeyPoint centroid{(n.apex.x + n.b.x + n.c.x) / 3, (n.apex.y + n.b.y + n.c.y) / 3};
  const TileId tile = tile_at(z, centroid.x, centroid.y);
  const BlockState st = cache_->state(tile);
  if (st == BlockState::kAbsent) return;
  const ResidentBlock* block = cache_->use(tile);
  if (!block) {
    if (st == BlockState::kNotLoaded) cache_->request(tile, z - 1);
    ++stats_.waiting;
    return;
  }
  if (settings_.cull && frame_->globe()) {
    if (!globe_visible(n, *block)) {
      ++stats_.culled;
      return;
    }
  } else if (settings_.cull) {
    const double z0 = block->min_h * frame_->height_scale() * settings_.exaggeration;
    const double z1 = block->max_h * frame_->height_scale() * settings_.exaggeration;
    glm::dvec3 corners[6];
    const KeyPoint pts[3] = {n.apex, n.b, n.c};
    for (int i = 0; i < 3; ++i) {
      corners[2 * i] = frame_->key_to_world(double(pts[i].x), double(pts[i].y), 0, view_->origin);
      corners[2 * i].z = z0;
      corners[2 * i + 1] = corners[2 * i];
      corners[2 * i + 1].z = z1;
    }
    for (const glm::dvec4& pl : view_->planes) {
      bool all_out = true;
      for (const glm::dvec3& c : corners)
        if (glm::dot(glm::dvec3(pl), c) + pl.w >= 0) {
          all_out = false;
          break;
        }
      if (all_out) {
        ++stats_.culled;
        return;
      }
    }
  }
  const KeyPoint mid{(n.b.x + n.c.x) / 2, (n.b.y + n.c.y) / 2};
  if (active(mid, n.level)) {
    visit({n.level + 1, mid, n.apex, n.b});
    visit({n.level + 1, mid, n.c, n.apex});
    return;
  }
  const int shift = max_zoom_ - z;
  const int64_t t = int64_t{steps_} << shift;
  const int64_t ox = int64_t{tile.x} * t, oy = int64_t{tile.y} * t;
  const int64_t step = int64_t{lattice_} << shift;
  Patch p;
  p.tile = tile;
  p.slot = block->slot;
  p.level = n.level;
  p.apex = {static_cast<int>((n.apex.x - ox) >> shift), static_cast<int>((n.apex.y - oy) >> shift)};
  p.u = {static_cast<int>((n.b.x - n.apex.x) / step), static_cast<int>((n.b.y - n.apex.y) / step)};
  p.v = {static_cast<int>((n.c.x - n.apex.x) / step), static_cast<int>((n.c.y - n.apex.y) / step)};
  out_.push_back(p);
}

bool PatchSelector::globe_visible(const Node& n, const ResidentBlock& block) const {
  const double z0 = block.min_h * settings_.exaggeration, z1 = block.max_h * settings_.exaggeration;
  const KeyPoint pts[3] = {n.apex, n.b, n.c};
  // Bounding sphere: the corners at both heights, widened by the sagitta of
  // the node's longest side (the surface bulges above its chords).
  glm::dvec3 corners[6];
  glm::dvec3 centre(0);
  for (int i = 0; i < 3; ++i) {
    corners[2 * i] = frame_->key_to_world(double(pts[i].x), double(pts[i].y), z0, view_->origin);
    corners[2 * i + 1] =
        frame_->key_to_world(double(pts[i].x), double(pts[i].y), z1, view_->origin);
    centre += corners[2 * i] + corners[2 * i + 1];
  }
  centre /= 6.0;
  double side = 0, radius = 0;
  for (int i = 0; i < 3; ++i)
    side = std::max(side, glm::length(corners[2 * i] - corners[2 * ((i + 1) % 3)]));
  for (const glm::dvec3& c : corners)
    radius = std::max(radius, glm::length(c - centre));
  radius += side * side / (8 * wgs84::kB) + 1;
  for (const glm::dvec4& pl : view_->planes)
    if (glm::dot(glm::dvec3(pl), centre) + pl.w < -radius) return false;
  // Horizon: seen from the eye, the ellipsoid (inside the sphere of the
  // polar radius less the deepest trench) hides whatever lies past its
  // horizon by more than the highest terrain can rise above it.
  const double r_min = wgs84::kB - 11000;
  const glm::dvec3 e = view_->eye - earth_centre_, s = centre - earth_centre_;
  const double de = glm::length(e), ds = glm::length(s);
  if (de <= r_min || ds <= radius) return true;
  const double beyond = std::acos(std::clamp(glm::dot(e, s) / (de * ds), -1.0, 1.0));
  const double horizon = std::acos(r_min / de) +
                         std::acos(r_min / (wgs84::kA + std::max(z1, 0.0))) +
                         std::asin(std::min(1.0, radius / ds));
  return beyond <= horizon;
}

std::pair<double, double> PatchSelector::height_bounds_m(BlockCache& cache) const {
  double bottom = 1e30, top = -1e30;
  for (const TileId& id : roots_)
    if (cache.state(id) == BlockState::kResident)
      if (const ResidentBlock* b = cache.use(id)) {
        const uint32_t e = b->vertex_error.empty()
                               ? 0
                               : *std::max_element(b->vertex_error.begin(), b->vertex_error.end());
        bottom = std::min(bottom, b->min_h - e * step_m_);
        top = std::max(top, b->max_h + e * step_m_);
      }
  return top >= bottom ? std::pair{bottom, top} : std::pair{0.0, 0.0};
}

std::vector<Patch> PatchSelector::select(const View& view, const WorldFrame& frame,
                                         BlockCache& cache, const SelectionSettings& settings,
                                         SelectionStats* stats) {
  view_ = &view;
  frame_ = &frame;
  cache_ = &cache;
  settings_ = settings;
  stats_ = {};
  memo_.clear();
  out_.clear();
  z_top_world_ = top_height_m(cache) * frame.height_scale() * settings.exaggeration;
  error_scale_ = step_m_ * frame.height_scale() * settings.exaggeration;
  metres_per_key_ =
      frame.crs_per_key() * std::max(frame.metres_per_crs_x(), frame.metres_per_crs_y());
  if (frame.globe()) {
    const auto [bottom, top] = height_bounds_m(cache);
    height_pad_ = std::max(std::abs(bottom), std::abs(top)) * settings.exaggeration;
    const GlobeAnchor& a = frame.anchor(view.origin);
    earth_centre_ = a.enu * -a.ecef;
  }
  const int64_t t = int64_t{steps_} << (max_zoom_ - min_zoom_);
  for (const TileId& id : roots_) {
    const KeyPoint tl{id.x * t, id.y * t}, tr{tl.x + t, tl.y}, bl{tl.x, tl.y + t},
        br{tl.x + t, tl.y + t};
    const int g = 2 * min_zoom_;
    if (id.diagonal() == 0) {
      visit({g, tr, tl, br});
      visit({g, bl, br, tl});
    } else {
      visit({g, tl, tr, bl});
      visit({g, br, bl, tr});
    }
  }
  if (stats) *stats = stats_;
  std::vector<Patch> result;
  result.swap(out_);
  return result;
}

}  // namespace globe::viewer
