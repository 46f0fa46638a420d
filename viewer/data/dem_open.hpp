// Elevation from foreign servers as terrain readers: raster-DEM tiles
// (Terrarium, Terrain-RGB) through raster_dem_reader.hpp, and quantized-mesh
// tilesets through quantized_mesh_reader.hpp; both synthesize MBlock blobs
// (block_synthesizer.hpp) so the terrain goes through the same KPatch LOD as
// a package's.
#pragma once

#include <memory>
#include <string>

#include "data/raster_tile_fetcher.hpp"
#include "net/http_client.hpp"
#include "tileformat/tile_reader.hpp"

namespace globe::viewer {

// `encoding`: "terrarium" or "terrain-rgb" (else InputError).
std::unique_ptr<tileformat::TileReader> open_raster_dem(std::unique_ptr<RasterTileFetcher> fetcher,
                                                        const std::string& encoding);
// A quantized-mesh layer.json URL.
std::unique_ptr<tileformat::TileReader> open_quantized_mesh(const std::string& url,
                                                            net::HttpClient& client);

}  // namespace globe::viewer
