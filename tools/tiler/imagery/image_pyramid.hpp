// One pyramid step for image tiles: a parent's pixels from its four
// children, each output pixel the alpha-weighted mean of the 2 x 2 child
// pixels it covers (a box filter, exact because pixel grids nest). Colours
// are weighted by alpha so transparent pixels do not darken edges.
#pragma once

#include <array>

#include "geo/image_codec.hpp"

namespace globe {

// children in TileId::children() order (NW, NE, SW, SE); nullptr = missing
// (transparent).
TilePixels downsample_children(const std::array<const TilePixels*, 4>& children, int size,
                               int colour);

}  // namespace globe
