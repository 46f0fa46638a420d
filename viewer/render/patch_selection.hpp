// KPatch selection (../docs/viewer.md "Selection"): which bintree nodes of
// which resident blocks to draw for a view, so that the projected vertical
// error stays <= tau pixels and the mesh is conforming (no cracks, no
// T-junctions) across patch, block and zoom borders.
//
// All blocks form one 4-8 hierarchy (tileformat §6.1). A split vertex v of
// level G is *active* when
//   - its error block is resident and its projected error exceeds tau, or
//     its diamond lies in tiles the package does not have (no data: splitting
//     only removes empty triangles), and
//   - both of its 4-8 parents are active.
// A node is split iff its split vertex is active. A block standing in for a
// broken tile with its children's samples (data/block_substitute.hpp) has
// no errors of its own: its vertices are active, so the selection reaches
// the children wherever the closure lets it, and draws the stand-in only
// where it does not. The closure under parents
// makes the mesh conforming by construction; saturated errors and nested
// bounding spheres make the rule reach tau where data is resident. A block
// that is not resident yet simply keeps its region coarser.
//
// Pure CPU code over the BlockCache; the renderer draws the result.
#pragma once

#include <array>

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "camera/camera.hpp"
#include "camera/world_frame.hpp"
#include "data/block_cache.hpp"
#include "tileformat/kpatch.hpp"

namespace globe::viewer {

// One patch to draw: the node's right-angle corner and lattice step vectors
// in samples of its block (the lattice point (i, j) is apex + i*u + j*v).
struct Patch {
  tileformat::TileId tile;
  int slot = -1;
  // Slots of the resident blocks of the same zoom west, east, north and south
  // (-1: none), for normals across block edges; filled after the selection.
  std::array<int, 4> neighbours{-1, -1, -1, -1};
  int level = 0;  // global 4-8 level: 2 * zoom + depth
  tileformat::Point apex, u, v;
};

struct SelectionSettings {
  double max_error_px = 1.5;
  double exaggeration = 1.0;
  bool cull = true;  // frustum culling (off for mesh checks)
};

struct SelectionStats {
  size_t vertices_evaluated = 0;
  size_t nodes_visited = 0;
  size_t culled = 0;
  size_t waiting = 0;  // refinements held back by a block not resident yet
};

class PatchSelector {
 public:
  explicit PatchSelector(const TerrainPackage& package);

  // Requests missing blocks from `cache` as a side effect (flush them after).
  std::vector<Patch> select(const View& view, const WorldFrame& frame, BlockCache& cache,
                            const SelectionSettings& settings, SelectionStats* stats = nullptr);

  // Lowest and highest terrain (metres) over the resident root blocks, widened
  // by their largest error: bounds of the finest data.
  std::pair<double, double> height_bounds_m(BlockCache& cache) const;
  double top_height_m(BlockCache& cache) const { return height_bounds_m(cache).second; }
  double bottom_height_m(BlockCache& cache) const { return height_bounds_m(cache).first; }
  std::vector<tileformat::TileId> root_tiles() const { return roots_; }

 private:
  struct Node {
    int level;
    KeyPoint apex, b, c;
  };
  struct KeyHash {
    size_t operator()(const KeyPoint& k) const {
      return size_t(k.x) * 0x9E3779B97F4A7C15ULL ^ (size_t(k.y) + 0x632BE59BD9B4E019ULL);
    }
  };

  // Globe: whether the node can be seen (frustum and horizon).
  bool globe_visible(const Node& n, const ResidentBlock& block) const;
  int canonical_zoom(int level) const;  // block that draws nodes of this level
  int error_zoom(int level) const;      // block that stores this level's vertex errors
  bool active(const KeyPoint& v, int level);
  void visit(const Node& n);
  void parents(const KeyPoint& v, int level, KeyPoint out[2], int& count) const;
  bool in_extent(const KeyPoint& p) const;
  tileformat::TileId tile_at(int z, int64_t kx, int64_t ky) const;

  tileformat::KPatchLayout layout_;
  int steps_, lattice_, depth_, min_zoom_, max_zoom_;
  int64_t extent_x_, extent_y_;  // key units
  double step_m_;
  std::vector<tileformat::TileId> roots_;

  // Per-call state.
  const View* view_ = nullptr;
  const WorldFrame* frame_ = nullptr;
  BlockCache* cache_ = nullptr;
  SelectionSettings settings_;
  SelectionStats stats_;
  double z_top_world_ = 0, error_scale_ = 1, metres_per_key_ = 1;
  double height_pad_ = 0;       // globe: the largest |height| (metres)
  glm::dvec3 earth_centre_{0};  // globe: the ellipsoid's centre in world metres
  std::unordered_map<KeyPoint, bool, KeyHash> memo_;
  std::vector<Patch> out_;
};

}  // namespace globe::viewer
