// A terrain tile as a triangulated irregular network (docs/web.md
// "Quantized-mesh"): the right-triangle (4-8) hierarchy over the tile's
// (steps+1)^2 samples, each split vertex carrying the largest vertical
// distance between any sample and the plane of the hierarchy triangle over
// it, for every triangle of the vertex's diamond and of its descendants'. A
// tile keeps the triangles whose split vertex errs by at most the threshold,
// so every kept triangle is within it of every sample under it.
//
// A flat triangle also leaves the curved Earth: each triangle's error is at
// least the sagitta of its hypotenuse, d^2 / (8 R), with d measured at the
// tile's widest (`sample_metres` per sample step, the same for every tile of
// a zoom so that neighbours agree) -- without it a tile of a coarse level,
// whose geometric error exceeds any relief, would be two flat triangles.
//
// Neighbouring tiles must cut the same vertices along their shared edge, so
// the errors are those of one hierarchy over the whole zoom (square
// diagonals alternate with the parity of their global cell index). A
// vertex's descendants reach at most its own scale away from it, so the
// errors of a tile's vertices depend on the tile and the eight around it
// only: each tile's own triangle errors (`own_errors`, computed once per tile)
// are assembled for the 3 x 3 tiles and saturated there (`MeshErrors`). Both
// tiles of an edge then see the same errors on it: no cracks, with or
// without skirts, and no state shared between tiles (a server can cut any
// tile alone).
//
// Grid coordinates: i east (column), j south (row), 0..steps; heights in
// metres, NaN where the package has none (only in the apron).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace globe::web {

// A tile's samples with a one-sample apron from its neighbours (for normals).
struct TileGrid {
  int steps = 0;          // a power of two
  int diagonal = 0;       // (tile x + tile y) & 1: 0 splits the tile TL-BR, 1 TR-BL
  std::vector<double> h;  // (steps + 3)^2, from (-1, -1), row-major
  double at(int i, int j) const { return h[size_t(j + 1) * (steps + 3) + size_t(i + 1)]; }
  double& at(int i, int j) { return h[size_t(j + 1) * (steps + 3) + size_t(i + 1)]; }
  explicit TileGrid(int steps_ = 0, int diagonal_ = 0)
      : steps(steps_), diagonal(diagonal_), h(size_t(steps_ + 3) * (steps_ + 3), NAN) {}
};

// Per split vertex of a tile ((steps+1)^2, row-major; 0 where none), the
// largest error of the triangles of its diamond that lie inside the tile
// (both for inner vertices, one for edge vertices), the sagitta included.
// With a finite `limit`, each value only decides the cut at that threshold
// as the exact errors would: an error within it may be reported as any
// bound of it that is within it too (from the triangle's children, without
// scanning its samples), and one past it as anything past it (the scan stops
// at the first sample past it; a scale whose sagitta passes it is not
// scanned). An export or server, which cuts each zoom at one threshold,
// gives it as the limit and skips most of the work.
std::vector<float> own_errors(const TileGrid& grid, double sample_metres, double limit = INFINITY);

// The saturated errors of one tile's vertices, from the own errors of the
// tile and its eight neighbours (row-major from the north-west, the tile at
// index 4; nullptr for a neighbour that does not exist).
class MeshErrors {
 public:
  MeshErrors(int steps, int diagonal, const std::array<const std::vector<float>*, 9>& own);
  float at(int i, int j) const { return e_[size_t(j) * (steps_ + 1) + size_t(i)]; }
  int steps() const { return steps_; }
  int diagonal() const { return diagonal_; }

 private:
  int steps_, diagonal_;
  std::vector<float> e_;  // the centre tile's (steps+1)^2
};

struct GridPoint {
  int i = 0, j = 0;
};

// The triangles of the hierarchy kept at `threshold`: three grid points
// each, counter-clockwise with i east and j south seen from above (north up).
std::vector<std::array<GridPoint, 3>> cut_mesh(const MeshErrors& errors, double threshold);

}  // namespace globe::web
