// Common raster package metadata (see raster_metadata.hpp).
#include "raster_metadata.hpp"

#include <filesystem>
#include <sstream>

#include "json_escape.hpp"
#include "tileformat/blob_header.hpp"

namespace globe {

std::string metadata_number(double v, int digits) {
  std::ostringstream o;
  o.precision(digits);
  o << v;
  return o.str();
}

std::map<std::string, std::string> raster_metadata(const RasterMetadata& m) {
  std::map<std::string, std::string> meta;
  m.tiling.to_metadata(meta);
  const auto& ll = m.lonlat;
  auto f = [&](double v) { return metadata_number(v, m.bounds_digits); };
  meta["name"] = std::filesystem::path(m.output).stem().string();
  meta["format"] = m.format;
  meta["type"] = "baselayer";
  meta["version"] = "1";
  meta["description"] =
      m.description + " built by globe-tiler from " +
      std::filesystem::path(m.inputs[0].first).filename().string() +
      (m.inputs.size() > 1 ? " and " + std::to_string(m.inputs.size() - 1) + " more" : "");
  meta["bounds"] = f(ll.min_x) + "," + f(ll.min_y) + "," + f(ll.max_x) + "," + f(ll.max_y);
  meta["center"] = f((ll.min_x + ll.max_x) / 2) + "," + f((ll.min_y + ll.max_y) / 2) + "," +
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
  return meta;
}

}  // namespace globe
