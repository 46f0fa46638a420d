// globe-view command-line parsing (see viewer_settings.hpp).
#include "app/viewer_settings.hpp"

#include <cstdio>
#include <fstream>

#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"

namespace globe::viewer {

namespace {

// --shading's help, from the modes' table.
std::string shading_help() {
  std::string help;
  for (const ShadingMode& m : shading_modes()) {
    help += std::string(m.name) + " (" + m.help + "), ";
    if (m.id == Shading::kHillshade) help += "imagery (imagery unlit), ";
  }
  help.resize(help.size() - 2);
  help += "; ";
  std::string need;
  for (const ShadingMode& m : shading_modes())
    if (m.needs) need += std::string(need.empty() ? "" : ", ") + m.name;
  return help + need + " need an analysis package (globe-tiler analyze)";
}

// "1-7 hillshade/elevation/...": the modes' window keys.
std::string shading_keys_help() {
  const auto modes = shading_modes();
  std::string names;
  for (const ShadingMode& m : modes)
    names += std::string(names.empty() ? "" : "/") + m.name;
  return std::string(1, modes.front().key) + "-" + modes.back().key + " " + names;
}

// Where the camera is, what is drawn at which detail: --snapshot … --cache-mb.
void declare_view_options(CliArgs& cli, ViewerSettings& s) {
  cli.option("--snapshot", "OUT.png", "render headless, write the image, exit",
             [&](const std::string& v) { s.snapshot = v; });
  cli.option("--size", "WxH", "image / window size in pixels (default 1280x720)",
             [&](const std::string& v) {
               const auto x = v.find('x');
               if (x == std::string::npos)
                 throw UsageError("--size: expected WxH, got '" + v + "'");
               s.width = CliArgs::to_int("--size", v.substr(0, x), 16, 16384);
               s.height = CliArgs::to_int("--size", v.substr(x + 1), 16, 16384);
             });
  cli.option("--camera", "LON,LAT,H,HEADING,PITCH",
             "eye at lon/lat (degrees) and height H (metres above the ellipsoid, not the ground; "
             "below the ground it is raised 20 m above it); heading 0 = north; pitch 0 looks "
             "straight down, 90 horizontal",
             [&](const std::string& v) {
               try {
                 s.camera = CameraPose::parse(v);
               } catch (const std::exception& e) {
                 throw UsageError(std::string("--camera: ") + e.what());
               }
             });
  cli.flag("--globe",
           "draw a geodetic or webmercator package on the WGS84 ellipsoid, a virtual globe "
           "(the default where the data spans more than 30 degrees; --fit of a global package "
           "shows the whole disc)",
           [&] { s.globe = true; });
  cli.flag("--flat",
           "draw on the flat map frame (the default for local packages and areas "
           "under 30 degrees)",
           [&] { s.globe = false; });
  cli.flag("--fit", "frame the whole package, looking straight down (the default without --camera)",
           [&] { s.camera.reset(); });
  cli.option(
      "--camera-path", "FILE",
      "fly through the poses of FILE (one LON,LAT,H,HEADING,PITCH per line); stats cover "
      "the whole flight, the snapshot shows the last pose",
      [&](const std::string& v) {
        std::ifstream in(v);
        if (!in) throw UsageError("--camera-path: cannot read " + v);
        std::string line;
        int n = 0;
        while (std::getline(in, line)) {
          ++n;
          if (line.empty() || line[0] == '#') continue;
          try {
            s.camera_path.push_back(CameraPose::parse(line));
          } catch (const std::exception& e) {
            throw UsageError("--camera-path: " + v + ":" + std::to_string(n) + ": " + e.what());
          }
        }
        if (s.camera_path.empty()) throw UsageError("--camera-path: " + v + " has no pose");
      });
  cli.option("--fov", "DEG", "vertical field of view (default 45)", [&](const std::string& v) {
    s.fov_y_deg = CliArgs::to_double("--fov", v);
    if (s.fov_y_deg < 5 || s.fov_y_deg > 120) throw UsageError("--fov: must be within 5..120");
  });
  cli.option("--max-error-px", "TAU", "screen-space error bound of the terrain LOD (default 1.5)",
             [&](const std::string& v) {
               s.max_error_px = CliArgs::to_double("--max-error-px", v);
               if (s.max_error_px <= 0) throw UsageError("--max-error-px: must be > 0");
             });
  cli.option(
      "--cache-mb", "MB",
      "memory budget for resident terrain blocks and line tiles (default 512; a quarter goes "
      "to line tiles when there are lines)",
      [&](const std::string& v) { s.cache_mb = CliArgs::to_int("--cache-mb", v, 4, 1 << 20); });
}

// How the terrain is shaded: --shading … --exaggeration.
void declare_shading_options(CliArgs& cli, ViewerSettings& s) {
  cli.option("--shading", "MODE", shading_help(), [&](const std::string& v) {
    if (const ShadingMode* m = find_shading_mode(v))
      s.shading.mode = m->id;
    else if (v == "imagery")
      s.imagery_unlit = true;
    else
      throw UsageError("--shading: unknown mode '" + v + "'");
  });
  cli.flag("--flow-animate",
           "flow shading: pulses run downstream along the rivers, 8 samples apart (the window "
           "animates them, a cycle every 2 s; a snapshot draws them at --flow-phase)",
           [&] {
             s.flow_animate = true;
             if (!s.shading.flow_phase) s.shading.flow_phase = 0;
           });
  cli.option("--flow-phase", "P",
             "flow shading: draw the pulses at phase P (0 <= P < 1 of the spacing between "
             "crests; default 0); implies the pulses",
             [&](const std::string& v) {
               const double p = CliArgs::to_double("--flow-phase", v);
               if (!(p >= 0 && p < 1)) throw UsageError("--flow-phase: must be in [0, 1)");
               s.shading.flow_phase = p;
             });
  cli.flag("--ambient-occlusion",
           "darken by the sky-view factor of an analysis package (any shading, and imagery lit "
           "by it)",
           [&] { s.shading.ambient_occlusion = true; });
  cli.option("--colormap", "NAME|FILE",
             "the colour ramp: hypsometric (default: bathymetry below 0 m, land above), "
             "gray, or a gdaldem color-relief file (VALUE R G B [A] per line; VALUE in the "
             "layer's unit, a percentage of its range, or nv); the window reloads the file when "
             "it changes. Elevation always uses it; given, it also colours slope (0..90 "
             "degrees), skyview (0..1), flow (upstream area in m^2, log scale), aspect (0..360 "
             "degrees from north) and edges (curvature stretched to -1 valleys .. 1 ridges)",
             [&](const std::string& v) {
               s.shading.colormap = v;
               s.shading.colormap_given = true;
             });
  cli.option("--height-range", "MIN,MAX",
             "heights in metres the elevation ramp spans (default: the data's own heights, "
             "from the coarsest blocks)",
             [&](const std::string& v) {
               const auto d = CliArgs::to_doubles("--height-range", v, 2);
               if (!(d[1] > d[0])) throw UsageError("--height-range: MAX must be above MIN");
               s.shading.height_range = std::pair{d[0], d[1]};
             });
  cli.option("--height-percentile", "P",
             "clip the data's height range to its P-th and (100-P)-th percentiles "
             "(default 0: minimum to maximum)",
             [&](const std::string& v) {
               s.shading.height_percentile = CliArgs::to_double("--height-percentile", v);
               if (s.shading.height_percentile < 0 || s.shading.height_percentile >= 50)
                 throw UsageError("--height-percentile: must be within 0..50");
             });
  cli.option("--image-opacity", "A[,B...]",
             "opacity of each image layer, bottom first, 0..1 (default 1; the last value "
             "applies to the layers after it)",
             [&](const std::string& v) {
               s.image_opacity.clear();
               size_t start = 0;
               for (;;) {
                 const size_t comma = v.find(',', start);
                 const double a =
                     CliArgs::to_double("--image-opacity", v.substr(start, comma - start));
                 if (a < 0 || a > 1) throw UsageError("--image-opacity: must be within 0..1");
                 s.image_opacity.push_back(a);
                 if (comma == std::string::npos) break;
                 start = comma + 1;
               }
             });
  cli.option("--area-opacity", "A",
             "opacity of the area fills over the terrain, 0..1 (default 0.75; a style class's "
             "own opacity multiplies it)",
             [&](const std::string& v) {
               s.area_opacity = CliArgs::to_double("--area-opacity", v);
               if (!(s.area_opacity >= 0 && s.area_opacity <= 1))
                 throw UsageError("--area-opacity: must be within 0..1");
             });
  cli.option("--labels", "auto|off|FIELD",
             "the names the vector packages store (globe-vectorize --label-field), placed per "
             "frame: never overlapping, never through terrain (default auto: shown when stored; "
             "FIELD: that attribute of each labelled feature instead)",
             [&](const std::string& v) {
               s.labels.enabled = v != "off";
               s.labels.field = v == "auto" || v == "off" ? "" : v;
             });
  cli.option("--label-size", "PX", "label text size in pixels at the view's centre (default 13)",
             [&](const std::string& v) {
               s.labels.size_px = CliArgs::to_double("--label-size", v);
               if (!(s.labels.size_px >= 4 && s.labels.size_px <= 96))
                 throw UsageError("--label-size: must be within 4..96 pixels");
             });
  cli.option("--label-font", "FILE",
             "a TrueType/OpenType font tried before Debian's Noto and DejaVu fonts",
             [&](const std::string& v) { s.labels.font = v; });
  cli.option("--labels-json", "FILE",
             "write the labels placed in each frame as JSON (text, source, anchor, screen box, "
             "alpha, line labels' glyphs; headless)",
             [&](const std::string& v) { s.labels_json = v; });
  cli.option("--sun", "AZ,ALT", "sun azimuth and altitude in degrees (default 315,45)",
             [&](const std::string& v) {
               const auto d = CliArgs::to_doubles("--sun", v, 2);
               s.shading.sun_azimuth_deg = d[0];
               s.shading.sun_altitude_deg = d[1];
             });
  cli.option("--exaggeration", "K",
             "vertical exaggeration (default 1; without it the hillshade stretches the slopes of "
             "coarse grids for the light, docs/viewer.md)",
             [&](const std::string& v) {
               s.shading.exaggeration = CliArgs::to_double("--exaggeration", v);
               s.shading.exaggeration_given = true;
               if (s.shading.exaggeration <= 0 || s.shading.exaggeration > 100)
                 throw UsageError("--exaggeration: must be within (0, 100]");
             });
}

// The deferred map's per-pixel extras over the terrain: --lens, --isolines,
// --isolines-of, --isoline-color.
void declare_map_options(CliArgs& cli, ViewerSettings& s) {
  cli.option("--lens", "X,Y,R[:WHAT]",
             "a magic lens: inside the circle of radius R pixels around X,Y (from the top-left) "
             "the terrain is shaded in another mode (WHAT a --shading name; default: elevation, "
             "or hillshade when that is the shading), or shows isolines=M (isolines every M), "
             "lines (the line package only there) or images (the image layers only there); the "
             "window's K key moves it with the mouse",
             [&](const std::string& v) {
               using Shows = ShadingSettings::LensShows;
               const size_t colon = v.find(':');
               const auto d = CliArgs::to_doubles("--lens", v.substr(0, colon), 3);
               if (!(d[2] > 0)) throw UsageError("--lens: the radius must be > 0 pixels");
               s.shading.lens_x = d[0], s.shading.lens_y = d[1], s.shading.lens_radius = d[2];
               if (colon == std::string::npos) return;
               const std::string what = v.substr(colon + 1);
               if (what == "lines") {
                 s.shading.lens_shows = Shows::kLines;
               } else if (what == "images") {
                 s.shading.lens_shows = Shows::kImages;
               } else if (what.rfind("isolines=", 0) == 0) {
                 s.shading.lens_shows = Shows::kIsolines;
                 s.shading.lens_isoline_interval = CliArgs::to_double("--lens", what.substr(9));
                 if (!(s.shading.lens_isoline_interval > 0))
                   throw UsageError("--lens: isolines=M needs an interval > 0");
               } else if (const ShadingMode* m = find_shading_mode(what)) {
                 s.lens_mode_given = true;
                 s.shading.lens_mode = m->id;
               } else {
                 throw UsageError("--lens: unknown mode '" + what +
                                  "' (a --shading name, isolines=M, lines or images)");
               }
             });
  cli.option("--isolines", "M[,N]",
             "isolines of the terrain every M metres, drawn per pixel (constant width), every "
             "N-th one bold (e.g. 50,5); under image layers",
             [&](const std::string& v) {
               const size_t comma = v.find(',');
               s.shading.isoline_interval = CliArgs::to_double("--isolines", v.substr(0, comma));
               if (!(s.shading.isoline_interval > 0))
                 throw UsageError("--isolines: the interval must be > 0 metres");
               if (comma != std::string::npos)
                 s.shading.isoline_index =
                     CliArgs::to_int("--isolines", v.substr(comma + 1), 1, 1000);
             });
  cli.option("--isolines-of", "FIELD",
             "what --isolines follows: height (default, metres), slope (degrees) or flow (the "
             "analysis package's upstream area, every M doublings)",
             [&](const std::string& v) {
               using Of = ShadingSettings::IsolinesOf;
               if (v == "height")
                 s.shading.isolines_of = Of::kHeight;
               else if (v == "slope")
                 s.shading.isolines_of = Of::kSlope;
               else if (v == "flow")
                 s.shading.isolines_of = Of::kFlow;
               else
                 throw UsageError("--isolines-of: unknown field '" + v + "' (height, slope, flow)");
             });
  cli.option("--isoline-color", "#RRGGBB", "the isolines' colour (default #5c3317)",
             [&](const std::string& v) {
               unsigned rgb = 0;
               if (v.size() != 7 || v[0] != '#' || std::sscanf(v.c_str() + 1, "%6x", &rgb) != 1)
                 throw UsageError("--isoline-color: expected #RRGGBB, got '" + v + "'");
               s.shading.isoline_rgb = {float((rgb >> 16) & 255) / 255,
                                        float((rgb >> 8) & 255) / 255, float(rgb & 255) / 255};
             });
}

// Line, bundle and chart layers: --style … --chart-thinning (heatmaps below).
void declare_layer_options(CliArgs& cli, ViewerSettings& s) {
  cli.option("--style", "FILE.json",
             "line styles by class name, over the package's own (docs/viewer.md); the window "
             "reloads the file when it changes, or on F5",
             [&](const std::string& v) { s.style = v; });
  cli.option(
      "--lines", "MODE",
      "deferred (default: per-pixel shading from the G-buffer), geometry (the baseline: "
      "draped quads), lifted (curves above the terrain, see --lift) or off",
      [&](const std::string& v) {
        if (v == "deferred")
          s.line_mode = LineMode::kDeferred;
        else if (v == "geometry")
          s.line_mode = LineMode::kGeometry;
        else if (v == "lifted")
          s.line_mode = LineMode::kLifted;
        else if (v == "off")
          s.lines = false;
        else
          throw UsageError("--lines: unknown mode '" + v + "' (deferred, geometry, lifted, off)");
      });
  cli.option("--bundles", "MODE",
             "bundled flows: flat (default: draped per pixel, as --lines deferred) or 3d (lifted "
             "above the terrain, as --lines lifted)",
             [&](const std::string& v) {
               if (v == "flat")
                 s.line_mode = LineMode::kDeferred;
               else if (v == "3d")
                 s.line_mode = LineMode::kLifted;
               else
                 throw UsageError("--bundles: unknown mode '" + v + "' (flat, 3d)");
             });
  cli.option("--lift", "M",
             "lifted lines: metres above the highest terrain near each point (default: 3% of "
             "the camera's distance, so curves clear the relief at any zoom); PageUp/PageDown "
             "in the window",
             [&](const std::string& v) {
               s.lift_m = CliArgs::to_double("--lift", v);
               if (!(*s.lift_m >= 0 && *s.lift_m <= 1e8))
                 throw UsageError("--lift: expected metres from 0 to 1e8, got '" + v + "'");
             });
  cli.option("--chart", "KIND",
             "with a point package: pie (default), bar, stacked (one bar of the values) or "
             "column (3D columns standing on the terrain)",
             [&](const std::string& v) {
               s.charts_given = true;
               if (v == "pie")
                 s.charts.kind = ChartKind::kPie;
               else if (v == "bar")
                 s.charts.kind = ChartKind::kBar;
               else if (v == "stacked")
                 s.charts.kind = ChartKind::kStacked;
               else if (v == "column")
                 s.charts.kind = ChartKind::kColumn;
               else
                 throw UsageError("--chart: unknown kind '" + v + "' (pie, bar, stacked, column)");
             });
  cli.option("--chart-style", "FILE.json",
             "chart colours per field, sizes, outline, opacity, legend (docs/viewer.md); the "
             "window reloads the file when it changes, or on F5",
             [&](const std::string& v) {
               s.charts_given = true;
               s.charts.style = v;
             });
  cli.option("--chart-depth", "MODE",
             "terrain (default: hills in front hide charts) or top (charts over everything)",
             [&](const std::string& v) {
               s.charts_given = true;
               if (v == "terrain")
                 s.charts.depth = ChartDepth::kTerrain;
               else if (v == "top")
                 s.charts.depth = ChartDepth::kOnTop;
               else
                 throw UsageError("--chart-depth: unknown mode '" + v + "' (terrain, top)");
             });
  cli.flag("--chart-thinning",
           "drop charts that fall on a larger one (default: draw all, nearer ones on top)", [&] {
             s.charts_given = true;
             s.charts.thinning = ChartThinning::kOn;
           });
}

// Heatmaps of a point or line package: --heatmap … --heatmap-opacity.
void declare_heatmap_options(CliArgs& cli, ViewerSettings& s) {
  cli.option("--heatmap", "count|FIELD",
             "a heatmap of the places instead of charts: their kernel density per pixel over "
             "the terrain, weighted by the source places each stands for (count) or by a field; "
             "it integrates to the weight over the ground. Without a point package, of a line "
             "package's length (bundled flows: weighted by their weight classes)",
             [&](const std::string& v) {
               s.charts_given = true;
               s.charts.heatmap = true;
               s.charts.heat_field = v;
             });
  cli.option("--heatmap-radius", "R[px|m|km]",
             "the kernel's radius: on screen (default 30px) or on the ground",
             [&](const std::string& v) {
               s.charts_given = true;
               double scale = 1;
               std::string n = v;
               auto cut = [&](const char* unit, double factor) {
                 const std::string u(unit);
                 if (n.size() > u.size() && n.compare(n.size() - u.size(), u.size(), u) == 0) {
                   n.resize(n.size() - u.size());
                   scale = factor;
                   return true;
                 }
                 return false;
               };
               const bool px = cut("px", 1);
               const bool metres = !px && (cut("km", 1000) || cut("m", 1));
               s.charts.heat_radius = CliArgs::to_double("--heatmap-radius", n) * scale;
               s.charts.heat_radius_m = metres;
               if (!(s.charts.heat_radius > 0))
                 throw UsageError("--heatmap-radius: '" + v + "' is not a positive length");
             });
  cli.option("--heatmap-colormap", "FILE",
             "the heatmap's colours: a gdaldem color-relief file (VALUE R G B [A]) whose values "
             "are percentages of the frame's largest density (default: yellow-orange-red, "
             "transparent where there is none)",
             [&](const std::string& v) {
               s.charts_given = true;
               s.charts.heat_colormap = v;
             });
  cli.option("--heatmap-opacity", "A", "the heatmap's opacity at its densest (default 0.75)",
             [&](const std::string& v) {
               s.charts_given = true;
               s.charts.heat_opacity = CliArgs::to_double("--heatmap-opacity", v);
               if (!(s.charts.heat_opacity >= 0 && s.charts.heat_opacity <= 1))
                 throw UsageError("--heatmap-opacity: '" + v + "' is not between 0 and 1");
             });
}

// Remote sources: --cache-dir … --max-connections (docs/viewer.md "Remote sources").
void declare_network_options(CliArgs& cli, ViewerSettings& s) {
  cli.option("--cache-dir", "DIR",
             "where tiles read from URLs are kept between runs (one SQLite file; default "
             "$XDG_CACHE_HOME/globe-view or ~/.cache/globe-view; 'none': keep nothing)",
             [&](const std::string& v) {
               if (v == "none")
                 s.network.no_cache = true;
               else
                 s.network.cache_dir = v;
             });
  cli.option("--http-cache-mb", "MB",
             "size of that cache; the least recently used tiles go first (default 1024)",
             [&](const std::string& v) {
               s.network.cache_mb = uint64_t(CliArgs::to_int("--http-cache-mb", v, 1, 1 << 22));
             });
  cli.flag("--offline", "read URLs from the cache only: no request leaves the machine",
           [&] { s.network.offline = true; });
  cli.option("--dem-encoding", "terrarium|terrain-rgb",
             "read an XYZ template or .pmtiles URL of PNG/WebP tiles as elevation in this "
             "encoding (Terrarium: h = R*256 + G + B/256 - 32768; Mapbox Terrain-RGB: "
             "h = -10000 + (R*65536 + G*256 + B) * 0.1); without it such URLs are imagery",
             [&](const std::string& v) {
               if (v != "terrarium" && v != "terrain-rgb")
                 throw UsageError("--dem-encoding: '" + v + "' is not terrarium or terrain-rgb");
               s.network.remote.dem_encoding = v;
             });
  cli.option("--source-zooms", "MIN-MAX",
             "the zooms an XYZ template URL has tiles at (default 0-19 for imagery, 0-15 for "
             "elevation)",
             [&](const std::string& v) {
               const size_t dash = v.find('-');
               if (dash == std::string::npos)
                 throw UsageError("--source-zooms: MIN-MAX, e.g. 0-14");
               const int a = CliArgs::to_int("--source-zooms", v.substr(0, dash), 0, 30);
               const int b = CliArgs::to_int("--source-zooms", v.substr(dash + 1), 0, 30);
               if (b < a) throw UsageError("--source-zooms: MAX below MIN");
               s.network.remote.source_zooms = std::pair{a, b};
             });
  cli.option("--max-connections", "N", "connections per server at most (default 6)",
             [&](const std::string& v) {
               s.network.max_connections_per_host = CliArgs::to_int("--max-connections", v, 1, 64);
             });
}

// What a headless run writes or prints, and the platform.
void declare_output_options(CliArgs& cli, ViewerSettings& s) {
  cli.flag("--stats", "print frame statistics as JSON on stdout (headless)",
           [&] { s.stats = true; });
  cli.option("--pick", "X,Y|@LON,LAT",
             "print what is at pixel X,Y (from the top-left), or where the point LON,LAT at "
             "height 0 lands, on stdout, one line (empty: nothing): the place whose chart covers "
             "it and its values, or else the line feature drawn on top there, which the snapshot "
             "then highlights (in bundled flows: the bundle, with every connection through it), "
             "or else the area filled there; "
             "repeatable: one line per pick, all in the same frame, the last one highlighted "
             "(headless)",
             [&](const std::string& v) {
               const bool geographic = !v.empty() && v[0] == '@';
               const auto d = CliArgs::to_doubles("--pick", geographic ? v.substr(1) : v, 2);
               s.picks.push_back({geographic, d[0], d[1]});
             });
  cli.option("--pick-format", "text|json",
             "how --pick prints: text (default: one line of the topmost layer that picks) or "
             "json: one object per pick with x, y, the ground's lon, lat and height there (null "
             "off the globe) and the topmost area, line and chart there (each with its id and "
             "attributes, or null)",
             [&](const std::string& v) {
               if (v != "text" && v != "json")
                 throw UsageError("--pick-format: '" + v + "' is not text or json");
               s.pick_json = v == "json";
             });
  cli.option("--frames", "N", "frames measured for --stats (default 5)",
             [&](const std::string& v) { s.frames = CliArgs::to_int("--frames", v, 1, 10000); });
  cli.option("--export-mesh", "FILE.ply",
             "write the triangles drawn for the view (tiling CRS x/y, height in metres)",
             [&](const std::string& v) { s.export_mesh = v; });
  cli.flag("--no-cull", "select without frustum culling (whole-package meshes)",
           [&] { s.cull = false; });
  cli.option("--platform", "NAME",
             "auto (default: window, or OSMesa then EGL when headless), glfw, osmesa, egl",
             [&](const std::string& v) {
               if (v != "auto" && v != "glfw" && v != "osmesa" && v != "egl")
                 throw UsageError("--platform: unknown '" + v + "' (auto, glfw, osmesa, egl)");
               s.platform = v;
             });
}

}  // namespace

std::optional<ViewerSettings> parse_viewer_settings(const std::vector<std::string>& args) {
  ViewerSettings s;
  CliArgs cli("globe-view",
              "globe-view [TERRAIN.mbtiles] [IMAGE.mbtiles ...] [AREAS.mbtiles] [LINES.mbtiles]\n"
              "           [POINTS.mbtiles] [options]\n"
              "Renders a terrain package with image packages draped over it (bottom first),\n"
              "the polygons of an area package filled per pixel over them, the lines of a\n"
              "line-cluster package shaded per pixel over those, and a chart per place of a\n"
              "point package on top: in a window, or headless with --snapshot,\n"
              "--stats or --export-mesh (OSMesa or EGL; no display needed). Packages are told\n"
              "apart by their format; layers may be tiled geodetic over a webmercator terrain\n"
              "or the other way round. Without a terrain, layers lie on zero heights (the\n"
              "ellipsoid on the globe, a flat base on the map frame).\n"
              "A package may be a URL: http(s)://HOST/NAME.json, the TileJSON globe-serve\n"
              "publishes for it; an XYZ template …/{z}/{x}/{y}.png ({-y}: TMS rows) or a\n"
              "…/FILE.pmtiles of imagery (elevation with --dem-encoding); a quantized-mesh\n"
              "…/layer.json. Tiles are streamed and kept in a disk cache (--cache-dir).");
  cli.epilogue(
      "window: drag to orbit, right-drag to pan, wheel or W/S to zoom, arrows to pan,\n"
      "  R home view, P screenshot (globe-view-N.png), Esc quit;\n"
      "  " +
      shading_keys_help() +
      ", O ambient occlusion on/off,\n"
      "  K the lens (--lens) on/off, following the mouse, Shift+wheel resizes it;\n"
      "  +/- exaggeration;\n"
      "  , and . shift the elevation ramp down/up, ; and ' narrow/widen it, 0 reset;\n"
      "  I select the next image layer, V show/hide it, [ and ] its opacity -/+ 0.1,\n"
      "  U imagery unlit/lit; L line mode, F5 reload the style and colour files;\n"
      "  C next chart kind; the title names the place under the cursor; N labels on/off;\n"
      "  PageUp/PageDown raise/lower lifted lines (--bundles 3d);\n"
      "  click a line to highlight it (a bundle: every connection through it), click\n"
      "  elsewhere to clear; the title names it.\n");
  declare_view_options(cli, s);
  declare_shading_options(cli, s);
  declare_map_options(cli, s);
  declare_layer_options(cli, s);
  declare_heatmap_options(cli, s);
  declare_network_options(cli, s);
  declare_output_options(cli, s);
  auto positional = cli.parse_command(args, 1, 11, "package");
  if (!positional) return std::nullopt;
  s.packages = *positional;
  if (s.platform == "glfw" && (s.snapshot || s.export_mesh || s.stats || !s.picks.empty()))
    throw UsageError(
        "--platform glfw opens a window; --snapshot/--stats/--export-mesh/--pick are headless");
  if (s.imagery_unlit) s.shading.mode = Shading::kHillshade;
  if (!s.lens_mode_given && s.shading.mode == Shading::kElevation)
    s.shading.lens_mode = Shading::kHillshade;
  for (CameraPose& p : s.camera_path)
    p.fov_y_deg = s.fov_y_deg;
  if (s.camera) s.camera->fov_y_deg = s.fov_y_deg;
  return s;
}

}  // namespace globe::viewer
