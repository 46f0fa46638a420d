// Where vector features go (docs/lines.md "Tiling and zooms"), for every
// vector builder (lines, points): the frame features are projected into and
// the tiling, from --like, --tiling and --t_srs (before reading); a local
// tiling placed on the data, and the part of the tiling --bbox keeps (after).
#pragma once

#include <optional>
#include <string>
#include "tileformat/metadata.hpp"

#include "geo/spatial_ref.hpp"
#include "kit/build_options.hpp"
#include "lines/line_projector.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

struct VectorFrame {
  TargetFrame frame = TargetFrame::kWebMercator;
  // kProjected: the tiling CRS (--like, --t_srs, or the first input's CRS,
  // filled in by the builder once the inputs are open).
  std::optional<SpatialRef> target;
  // Known before reading for --like and the global schemes; a local tiling
  // is placed on the data by frame_tiling().
  std::optional<tileformat::Tiling> tiling;
};

// From `like` (a package whose tiling to adopt, "" for none), o.tiling and
// o.t_srs; throws UsageError for conflicting ones.
VectorFrame choose_vector_frame(const std::string& like, const BuildOptions& o);

// The tiling: the frame's, or a local one whose square power-of-two root
// has its top-left corner at the data's (`extent`: the data in the frame).
tileformat::Tiling frame_tiling(const VectorFrame& frame, const tileformat::Bounds& extent);

// The part of `tiling` to keep: its extent, within o.bbox (lon/lat) if
// given. Throws UsageError for a --bbox outside the tiling CRS.
tileformat::Bounds frame_area(const VectorFrame& frame, const tileformat::Tiling& tiling,
                              const BuildOptions& o);

// The common metadata (§3.2) of a vector package of `format` ("WHAT built
// by globe-vectorize from ..."): name, inputs, bounds and center of the data
// `extent` (frame CRS) within `area`, zooms, tiling and command line.
tileformat::CommonMetadata vector_common_metadata(const BuildOptions& o, const char* what,
                                                  const char* format, const VectorFrame& frame,
                                                  const tileformat::Tiling& tiling,
                                                  const tileformat::Bounds& extent,
                                                  const tileformat::Bounds& area, int min_zoom,
                                                  int max_zoom);

}  // namespace globe
