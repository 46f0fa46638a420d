// Elevation from foreign servers (see dem_open.hpp).
#include "data/dem_open.hpp"

#include "data/quantized_mesh_reader.hpp"
#include "data/raster_dem_reader.hpp"
#include "runtime/errors.hpp"

namespace globe::viewer {

std::unique_ptr<tileformat::TileReader> open_raster_dem(std::unique_ptr<RasterTileFetcher> fetcher,
                                                        const std::string& encoding) {
  if (encoding == "terrarium")
    return std::make_unique<RasterDemReader>(std::move(fetcher), DemEncoding::kTerrarium);
  if (encoding == "terrain-rgb" || encoding == "mapbox")
    return std::make_unique<RasterDemReader>(std::move(fetcher), DemEncoding::kTerrainRgb);
  throw InputError(fetcher->name() + ": elevation encoded as '" + encoding +
                   "', where globe-view reads terrarium and terrain-rgb");
}

std::unique_ptr<tileformat::TileReader> open_quantized_mesh(const std::string& url,
                                                            net::HttpClient& client) {
  return std::make_unique<QuantizedMeshReader>(url, client);
}

}  // namespace globe::viewer
