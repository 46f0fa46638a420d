// `globe-tiler export PACKAGE -o OUT [--format F]`: packages to the formats
// web clients read (docs/web.md). Parses options, picks the exporter by the
// package's kind and --format.
#include <sstream>

#include "export/dem_export.hpp"
#include "export/image_export.hpp"
#include "export/mesh_export.hpp"
#include "kit/build_options.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"
#include "runtime/package_open.hpp"
#include "tiler_commands.hpp"

namespace globe {

namespace {

// The terrain options of `export`.
struct TerrainExport {
  std::string format;  // terrarium, terrain-rgb or quantized-mesh
  int tile_size = 256;
  bool gzip = false, normals = true;
  int gzip_level = 6;
  double mesh_error = 1.0, finest_error = 2.0;
  std::string watermask;
};

// A terrain package to raster-DEM tiles or quantized-mesh.
ExportSummary export_terrain(const std::string& input, const BuildOptions& o,
                             const TerrainExport& t, Progress& progress) {
  if (t.format.empty())
    throw UsageError(input +
                     " is a terrain package: give --format terrarium, terrain-rgb or "
                     "quantized-mesh");
  if (!t.watermask.empty() && t.format != "quantized-mesh")
    throw UsageError("--watermask is for --format quantized-mesh");
  if (t.gzip && t.format != "quantized-mesh")
    throw UsageError(
        "--gzip and --gzip-level are for --format quantized-mesh (PNG tiles are "
        "compressed already)");
  if (t.format == "quantized-mesh") {
    MeshExportSettings m;
    m.input = input, m.output = o.output, m.force = o.force;
    m.threads = o.worker_threads();
    m.gzip = t.gzip, m.gzip_level = t.gzip_level;
    m.normals = t.normals, m.error_scale = t.mesh_error;
    m.finest_error = t.finest_error;
    m.watermask = t.watermask;
    return export_quantized_mesh(m, progress);
  }
  DemExportSettings s;
  s.input = input, s.output = o.output, s.force = o.force;
  s.encoding =
      t.format == "terrarium" ? web::DemEncoding::kTerrarium : web::DemEncoding::kTerrainRgb;
  s.tile_size = t.tile_size;
  s.threads = o.worker_threads();
  return export_raster_dem(s, progress);
}

}  // namespace

int run_export(const std::vector<std::string>& args) {
  BuildOptions o;
  TerrainExport t;
  std::string& format = t.format;
  CliArgs cli(
      "globe-tiler export",
      "globe-tiler export PACKAGE --format FORMAT -o OUT.pmtiles|OUT.mbtiles|DIR\n\n"
      "Converts a package to a format web maps read, into one PMTiles file (static hosting:\n"
      "any HTTP server with range requests), an MBTiles file (for tile servers) or a folder\n"
      "DIR/{z}/{x}/{y}.EXT with DIR/metadata.json (TileJSON). Nothing appears under OUT\n"
      "until the export is complete.\n"
      "  terrain, --format terrarium|terrain-rgb: raster-DEM PNG tiles in web mercator XYZ\n"
      "    for MapLibre GL (raster-dem source, encoding \"terrarium\" or \"mapbox\"): each\n"
      "    pixel the package's height at the pixel's centre, bilinear between its samples;\n"
      "    a geodetic package is resampled to web mercator. Terrarium keeps 1/256 m,\n"
      "    Terrain-RGB 0.1 m.\n"
      "  terrain, --format quantized-mesh: CesiumJS terrain, -o DIR (DIR/layer.json and\n"
      "    DIR/{z}/{x}/{y}.terrain, rows from the south) or -o OUT.mbtiles for a server.\n"
      "    Each tile a TIN within Cesium's geometric error for its level, neighbours\n"
      "    sharing their border vertices, with vertex normals (octvertexnormals).\n"
      "    Geodetic packages become EPSG:4326 terrain (Cesium's default), webmercator\n"
      "    ones EPSG:3857.\n"
      "  images (no --format): the image tiles as stored (web mercator packages).\n"
      "docs/web.md says how to host the outputs and shows a MapLibre page for each.");
  cli.option(
      "--format", "FORMAT", "terrarium, terrain-rgb or quantized-mesh (terrain packages)",
      [&](const std::string& v) {
        if (v != "terrarium" && v != "terrain-rgb" && v != "quantized-mesh")
          throw UsageError("--format: '" + v + "' is not terrarium, terrain-rgb or quantized-mesh");
        format = v;
      });
  cli.flag("--gzip",
           "quantized-mesh: gzip each tile (the server must then send them with "
           "Content-Encoding: gzip)",
           [&] { t.gzip = true; });
  cli.option("--gzip-level", "N",
             "quantized-mesh: gzip each tile at deflate level N, 1-9 (implies --gzip; default 6; "
             "3 took 0.55-0.6x the export's time for 11 % more bytes)",
             [&](const std::string& v) {
               t.gzip_level = CliArgs::to_int("--gzip-level", v, 1, 9);
               t.gzip = true;
             });
  cli.option("--watermask", "POLYGONS",
             "quantized-mesh: water polygons (any OGR source) as each tile's water mask "
             "(extension watermask: CesiumJS draws water there)",
             [&](const std::string& v) { t.watermask = v; });
  cli.flag("--no-normals", "quantized-mesh: leave out the vertex normals",
           [&] { t.normals = false; });
  cli.option("--mesh-error", "F",
             "quantized-mesh: TIN error as a fraction of Cesium's geometric error per level "
             "(default 1; smaller: more triangles)",
             [&](const std::string& v) {
               t.mesh_error = CliArgs::to_double("--mesh-error", v);
               if (!(t.mesh_error > 0 && t.mesh_error <= 16))
                 throw UsageError("--mesh-error: a fraction above 0 and at most 16");
             });
  cli.option("--finest-error", "M",
             "quantized-mesh: TIN error in metres at the package's finest zoom, which CesiumJS "
             "shows however close the camera comes (default 2: below the vertical accuracy of SRTM "
             "and Copernicus GLO-30)",
             [&](const std::string& v) {
               t.finest_error = CliArgs::to_double("--finest-error", v);
               if (!(t.finest_error >= 0)) throw UsageError("--finest-error: metres, 0 or more");
             });
  cli.option("--tile-size", "PX", "raster-DEM tiles of 256 (default) or 512 pixels",
             [&](const std::string& v) {
               t.tile_size = CliArgs::to_int("--tile-size", v, 256, 512);
               if (t.tile_size != 256 && t.tile_size != 512)
                 throw UsageError("--tile-size: 256 or 512");
             });
  cli.option("-o,--output", "OUT", "OUT.pmtiles, OUT.mbtiles or a folder",
             [&](const std::string& v) { o.output = CliArgs::to_output_path(v); });
  declare_run_options(cli, o, ResumeOption::kNotOffered);
  if (!parse_build_command(cli, o, args, "globe-tiler export", "PACKAGE")) return kExitOk;
  if (o.inputs.size() != 1) throw UsageError("give exactly one package to export");
  const std::string& input = o.inputs[0];
  const std::optional<tileformat::PackageKind> kind = package_kind(input);
  Progress progress(o.progress);
  ExportSummary sum;
  if (kind == tileformat::PackageKind::kTerrain) {
    sum = export_terrain(input, o, t, progress);
  } else if (kind == tileformat::PackageKind::kImage) {
    if (!format.empty())
      throw UsageError(input +
                       " is an image package: its tiles are exported as stored; drop "
                       "--format " +
                       format);
    ImageExportSettings s;
    s.input = input, s.output = o.output, s.force = o.force;
    sum = export_images(s, progress);
  } else {
    throw UsageError(input +
                     ": globe-tiler export takes terrain and image packages; line, point and "
                     "bundle packages are exported by globe-vectorize");
  }
  std::ostringstream msg;
  msg.precision(3);
  msg << std::fixed << "globe-tiler: wrote " << o.output << ": " << sum.tiles << " tiles, zoom "
      << sum.min_zoom << ".." << sum.max_zoom << ", " << sum.bytes << " bytes, " << sum.seconds
      << " s";
  if (sum.pixels_without_data)
    msg << "; " << sum.pixels_without_data
        << " pixels of tiles at the data's edge had no block under them and hold 0 m";
  progress.note(msg.str());
  return kExitOk;
}

}  // namespace globe
