// Where the pixel centres of one destination window fall in a source raster
// (source pixel/line coordinates), for GDAL's warp kernel. Exact transforms
// (PROJ through GDAL's transformer) are taken on a grid of nodes every 16
// pixels; a 16 x 16 cell whose centre the bicubic (Lagrange) interpolation
// of its 4 x 4 surrounding nodes hits within the tolerance is interpolated,
// any other cell (a transform that bends too much, fails, or wraps around
// the antimeridian near it) is transformed pixel by pixel. Cubic, not
// bilinear: Mercator's latitudes bend enough over a cell of a coarse zoom to
// miss a tight tolerance with straight lines. The result is the exact transform to within
// the tolerance at a small fraction of its cost (reprojecting every pixel
// through PROJ costs more than the resampling), and it gives the exact
// source window the kernel will read, wherever the window lies: at the
// antimeridian, over a pole, partly outside a projection's domain.
#pragma once

#include <gdal_alg.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace globe {

class WindowCoordinates {
 public:
  // Bounds of source coordinates (pixel/line).
  struct Extent {
    double min_x = 0, min_y = 0, max_x = -1, max_y = -1;
    bool empty() const { return max_x < min_x || max_y < min_y; }
  };

  // `transform`/`arg`: a GDAL transformer from destination pixel/line to
  // source pixel/line (called with bDstToSrc = TRUE); w x h pixels. `clip`:
  // the source area of interest (the raster and the kernel's reach around
  // it); extent() only counts what falls inside it.
  WindowCoordinates(GDALTransformerFunc transform, void* arg, int w, int h, double tolerance_px,
                    const Extent& clip);

  int width() const { return w_; }
  int height() const { return h_; }

  // Source coordinates of the pixel centres of row y (w values each);
  // ok[i] = 0 where the transform fails.
  void row(int y, double* sx, double* sy, int* ok) const;

  // Bounds of the transformed pixel centres inside `clip` (a cell whose
  // corners straddle it counts with the part of its corners' range inside
  // it); empty() when none.
  const Extent& extent() const { return extent_; }

  // Source pixels per destination pixel along the source's x and y axes,
  // averaged over the window like GDAL's XSCALE=FROM_GRID_SAMPLING (for each
  // point the larger of the changes per destination column and row; cells
  // across a wrap are ignored). 0 when unknown.
  double source_step_x() const { return step_x_; }
  double source_step_y() const { return step_y_; }

  // Cells transformed pixel by pixel (for tests and statistics).
  size_t exact_cells() const { return exact_cells_; }

 private:
  static constexpr int kCell = 16;  // pixels between nodes
  struct Node {
    double x, y;
    int ok;
  };
  // Node (i, j) sits at pixel ((i - 1) * kCell, (j - 1) * kCell).
  const Node& node(int i, int j) const { return nodes_[size_t(j) * nodes_x_ + i]; }
  // Interpolated coordinates of pixel (px, py) of cell (ci, cj).
  void interpolate(int ci, int cj, int px, int py, double& sx, double& sy) const;
  void exact(int x0, int x1, int y, double* sx, double* sy, int* ok) const;

  GDALTransformerFunc transform_;
  void* arg_;
  int w_, h_;
  int cells_x_ = 0, cells_y_ = 0, nodes_x_ = 0;
  std::vector<Node> nodes_;
  std::vector<uint8_t> exact_;                          // per cell: 1 = transform every pixel
  std::array<std::array<double, 4>, kCell> weights_{};  // cubic weights per pixel offset
  Extent extent_;
  double step_x_ = 0, step_y_ = 0;
  size_t exact_cells_ = 0;
};

}  // namespace globe
