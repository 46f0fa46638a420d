// Common raster package metadata (see raster_metadata.hpp).
#include "raster_metadata.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "json_escape.hpp"
#include "metadata_text.hpp"
#include "tileformat/blob_header.hpp"

namespace globe {

std::map<std::string, std::string> raster_metadata(const RasterMetadata& m) {
  std::map<std::string, std::string> meta;
  m.tiling.to_metadata(meta);
  // Inside the range readers accept: the data's bounds computed from the
  // tiling's extent can overshoot it by a rounding error (-180.00000000000003).
  const tileformat::Bounds lim = m.tiling.lonlat_limits();
  const tileformat::Bounds ll{std::clamp(m.lonlat.min_x, lim.min_x, lim.max_x),
                              std::clamp(m.lonlat.min_y, lim.min_y, lim.max_y),
                              std::clamp(m.lonlat.max_x, lim.min_x, lim.max_x),
                              std::clamp(m.lonlat.max_y, lim.min_y, lim.max_y)};
  auto g = [&](double v) { return metadata_number(v, 10); };
  meta["name"] = std::filesystem::path(m.output).stem().string();
  meta["format"] = m.format;
  meta["type"] = "baselayer";
  meta["version"] = "1";
  meta["description"] =
      m.description + " built by globe-tiler from " +
      std::filesystem::path(m.inputs[0].first).filename().string() +
      (m.inputs.size() > 1 ? " and " + std::to_string(m.inputs.size() - 1) + " more" : "");
  meta["bounds"] = metadata_bounds(ll, lim, m.bounds_digits);
  meta["center"] = g((ll.min_x + ll.max_x) / 2) + "," + g((ll.min_y + ll.max_y) / 2) + "," +
                   std::to_string(m.max_zoom);
  // A dataset smaller than one pixel of the coarsest zooms leaves them empty
  // (empty tiles are not written): minzoom says what is there.
  meta["minzoom"] = std::to_string(m.min_zoom);
  meta["maxzoom"] = std::to_string(m.max_zoom);
  meta["globe:format_version"] = std::to_string(tileformat::kFormatVersion);
  meta["globe:resampling"] = m.resampling;
  meta["globe:generator"] = "globe-tiler " GLOBE_VERSION;
  meta["globe:command_line"] = m.command_line;
  std::string inputs = "[";
  for (size_t i = 0; i < m.inputs.size(); ++i)
    inputs += (i ? "," : "") + std::string("{\"name\":\"") + json_escape(m.inputs[i].first) +
              "\",\"bytes\":" + std::to_string(m.inputs[i].second) + "}";
  meta["globe:inputs"] = inputs + "]";
  if (!m.left_out.empty()) meta["globe:left_out"] = m.left_out;
  return meta;
}

}  // namespace globe
