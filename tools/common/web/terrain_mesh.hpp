// A terrain tile as a triangulated irregular network (docs/web.md
// "Quantized-mesh"): the right-triangle (4-8) hierarchy over the tile's
// (steps+1)^2 samples, each split vertex carrying the largest vertical
// distance between any sample and the plane of the hierarchy triangle over
// it, for every triangle of the vertex's diamond and below. A tile keeps the
// triangles whose split vertex errs by at most the threshold, so every kept
// triangle is within it of every sample under it.
//
// A flat triangle also leaves the curved Earth: each triangle's error is at
// least the sagitta of its hypotenuse, d^2 / (8 R), with d measured at the
// tile's widest (`sample_metres` per sample step, the same for every tile of
// a zoom so that neighbours agree) -- without it a tile of a coarse level,
// whose geometric error exceeds any relief, would be two flat triangles.
//
// Neighbouring tiles must agree on the vertices of their shared edge: an
// edge vertex's diamond lies half in each tile, so its error is the larger of
// the two tiles' half errors (edge_halves of one, join_neighbour of the
// other), after which the tile's inner vertices are saturated again. With
// the errors of one global 4-8 hierarchy (square diagonals alternate with the
// parity of their global cell index) both tiles then cut the same edge
// vertices: no cracks, with or without skirts.
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

enum class TileEdge { kNorth = 0, kEast = 1, kSouth = 2, kWest = 3 };

// Errors (metres) of the split vertices of one tile, at their grid positions.
class MeshErrors {
 public:
  // The tile's own half: every triangle inside the tile (NaN samples must not
  // occur inside the tile). `sample_metres`: ground length of a sample step.
  MeshErrors(const TileGrid& grid, double sample_metres);

  // The half errors of the vertices on one edge, indexed by the position along
  // the edge (i for north/south, j for east/west), steps + 1 values.
  std::vector<float> edge_halves(TileEdge edge) const;
  // Raises the vertices of `edge` to the neighbour's half errors there (its
  // edge_halves of the opposite edge, same indexing). Call finish() after.
  void join_neighbour(TileEdge edge, const std::vector<float>& neighbour_halves);
  // Saturates the inner vertices again over the joined edges.
  void finish();

  float at(int i, int j) const { return e_[size_t(j) * (steps_ + 1) + size_t(i)]; }
  int steps() const { return steps_; }
  int diagonal() const { return diagonal_; }

 private:
  float& ref(int i, int j) { return e_[size_t(j) * (steps_ + 1) + size_t(i)]; }
  void saturate(bool with_own);

  int steps_, diagonal_;
  double sample_metres_;
  const TileGrid* grid_;
  std::vector<float> e_;
};

struct GridPoint {
  int i = 0, j = 0;
};

// The triangles of the hierarchy kept at `threshold`: three grid points
// each, counter-clockwise with i east and j south seen from above (north up).
std::vector<std::array<GridPoint, 3>> cut_mesh(const MeshErrors& errors, double threshold);

}  // namespace globe::web
