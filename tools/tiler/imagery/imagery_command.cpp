// `globe-tiler imagery`: parses options into ImageSettings, plans, builds,
// and prints the summary.
#include <cstdio>
#include <sstream>

#include "imagery/image_builder.hpp"
#include "imagery/image_plan.hpp"
#include "raster/raster_warper.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "tiler_commands.hpp"

namespace globe {
namespace {

std::vector<int> parse_bands(const std::string& v) {
  std::vector<int> bands;
  std::stringstream in(v);
  for (std::string item; std::getline(in, item, ',');)
    bands.push_back(CliArgs::to_int("--bands", item, 1, 65535));
  if (bands.size() < 1 || bands.size() > 4 || v.empty() || v.back() == ',')
    throw UsageError("--bands '" + v +
                     "': give 1 (gray) or 3 (RGB) band numbers, optionally followed by an alpha "
                     "band, e.g. 3,2,1");
  return bands;
}

}  // namespace

int run_imagery(const std::vector<std::string>& args) {
  ImageSettings s;
  CliArgs cli(
      "globe-tiler imagery",
      "globe-tiler imagery INPUT... -o OUT.mbtiles [options]\n\n"
      "Turns rasters that GDAL reads (GeoTIFF, JPEG/PNG with a world file, ...; any CRS; several\n"
      "inputs form one mosaic, later inputs on top) into an image package: PNG/JPEG/WebP tiles\n"
      "on the same tiles as globe-tiler terrain. In webmercator it is a plain MBTiles file.\n"
      "Pixels without data (nodata, mask or alpha band, outside the inputs) are transparent.");
  declare_area_options(cli, s, "CRS of the inputs, for files without one or with a wrong one",
                       "finest zoom (default: where a tile pixel reaches the source pixel size)");
  cli.option("--like", "PACKAGE",
             "adopt the tiling of this package (e.g. a local terrain), so tile ids match",
             [&](const std::string& v) { s.like = v; });
  cli.option(
      "--tile-size", "PX", "pixels per tile edge: 256 (default) or 512",
      [&](const std::string& v) { s.tile_size = CliArgs::to_int("--tile-size", v, 1, 4096); });
  cli.option("--format", "FMT",
             "png (default, lossless), jpg (tiles with transparent pixels stay PNG) or webp",
             [&](const std::string& v) {
               auto f = tileformat::parse_image_format(v);
               if (!f) throw UsageError("--format: '" + v + "' is not png, jpg or webp");
               s.format = *f;
             });
  cli.option("--quality", "Q", "JPEG/WebP quality 1..100 (default 85; WebP 100 = lossless)",
             [&](const std::string& v) { s.quality = CliArgs::to_int("--quality", v, 1, 100); });
  cli.option("--png-level", "N",
             "PNG effort: 1 (default) = Paeth prediction and run-length deflate, the fastest "
             "and on photographs the smallest; 2..9 = adaptive filters and deflate at that "
             "level, smaller for graphics with repeated patterns (maps, scans)",
             [&](const std::string& v) { s.png_level = CliArgs::to_int("--png-level", v, 1, 9); });
  cli.option("--bands", "LIST",
             "source bands: 1 (gray) or 3 (RGB), then optionally an alpha band; e.g. 3,2,1 "
             "for Landsat true colour (default: RGB(A) by colour interpretation, else 1,2,3 or 1)",
             [&](const std::string& v) { s.bands = parse_bands(v); });
  cli.option("--nodata", "VALUE",
             "source value meaning 'no data' (transparent) in every colour band, overriding the "
             "files' own",
             [&](const std::string& v) { s.nodata = CliArgs::to_double("--nodata", v); });
  cli.option("--scale", "MIN,MAX",
             "map source values MIN..MAX to 0..255 (default for non-8-bit inputs: their range)",
             [&](const std::string& v) {
               auto d = CliArgs::to_doubles("--scale", v, 2);
               s.scale = std::pair{d[0], d[1]};
             });
  cli.option("--resampling", "METHOD",
             std::string("finest zoom: ") + kResamplingNames +
                 " (default bilinear); coarser zooms average their children",
             [&](const std::string& v) { s.resampling = v; });
  cli.option("--transform-error", "PX",
             "reprojection approximation error in pixels (default 0.125, as gdalwarp -et; 0 = "
             "exact)",
             [&](const std::string& v) {
               s.transform_error = CliArgs::to_double("--transform-error", v);
             });
  declare_run_options(cli, s);
  declare_shard_options(cli, s);
  if (!parse_build_command(cli, s, args, "globe-tiler imagery", "input raster (see --help)"))
    return kExitOk;

  Progress progress(s.progress);
  ImagePlan plan = plan_imagery(s);
  {
    std::ostringstream o;
    o << "globe-tiler: " << plan.sources.size() << " input(s), tiling "
      << tileformat::scheme_name(plan.tiling.scheme) << ", zoom " << plan.min_zoom << ".."
      << plan.max_zoom << ", " << s.tile_size << " px " << tileformat::image_format_name(s.format)
      << " tiles, " << (plan.colour == 1 ? "gray" : "RGB") << " + alpha, source pixel "
      << plan.source_resolution << " (tiling units)";
    if (!plan.left_out.empty()) o << "\nglobe-tiler: left out: " << plan.left_out;
    if (plan.scale_derived)
      o << "\nglobe-tiler: inputs are not 8-bit: values " << plan.scale->first << ".."
        << plan.scale->second << " map to 0..255 (set with --scale)";
    progress.note(o.str());
  }
  const ImageSummary sum = build_imagery(plan, s, progress);
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << "globe-tiler: wrote " << s.output << ": " << sum.tiles << " tiles ("
    << sum.unique_blobs << " unique; " << sum.png << " png, " << sum.jpeg << " jpg, " << sum.webp
    << " webp), " << sum.file_bytes << " bytes, " << sum.seconds << " s";
  progress.note(o.str());
  return kExitOk;
}

}  // namespace globe
