// Preview pages (see preview_pages.hpp).
#include "serve/preview_pages.hpp"

#include <cstdio>

namespace globe::serve {
namespace {

const char* kHead =
    "<!doctype html><html><head><meta charset=\"utf-8\"><link rel=\"icon\" href=\"data:,\">"
    "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">";

// Names are [A-Za-z0-9._-] (url_route.hpp): safe in HTML, URLs and JSON as
// they are; kinds and tilings are the services' own words.
std::string row(const PackageRegistry::Listed& p) {
  char zooms[64];
  std::snprintf(zooms, sizeof zooms, "%d..%d", p.service->min_zoom, p.service->max_zoom);
  const std::string q = "?pkg=" + p.name;
  std::string views;
  if (p.kind != "pmtiles") views += "<a href=\"/view/maplibre.html" + q + "\">MapLibre</a> ";
  if (p.kind != "pmtiles") views += "<a href=\"/view/cesium.html" + q + "\">CesiumJS</a>";
  std::string links = p.kind == "pmtiles"
                          ? "<a href=\"/" + p.name + ".pmtiles\">" + p.name + ".pmtiles</a>"
                          : "<a href=\"/" + p.name + ".json\">TileJSON</a>";
  if (p.kind == "terrain") links += " <a href=\"/" + p.name + "/layer.json\">layer.json</a>";
  if (p.kind == "lines" || p.kind == "points" || p.kind == "areas")
    links += " <a href=\"/" + p.name + "/style.json\">style.json</a>";
  return "<tr><td>" + p.name + "</td><td>" + p.kind + "</td><td>" + p.service->tiling() +
         "</td><td>" + zooms + "</td><td>" + links + "</td><td>" + views + "</td></tr>";
}

// The packages as the pages' JavaScript reads them, in the order given.
std::string packages_json(const std::vector<PackageRegistry::Listed>& packages) {
  std::string out = "[";
  for (const auto& p : packages)
    out += (out.size() > 1 ? "," : "") + std::string("{\"name\":\"") + p.name + "\",\"kind\":\"" +
           p.kind + "\",\"tiling\":\"" + p.service->tiling() + "\"}";
  return out + "]";
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// What both views share: the packages to show (one with ?pkg=NAME, else all),
// their TileJSON, and the union of their bounds. Reports failures to the test
// harness (window.__result, tests/web/README.md).
const char* kCommonScript = R"JS(
const PACKAGES = @PACKAGES@;
const fail = (e) => { window.__result = { ok: false, error: String(e && e.stack || e) }; };
const one = new URLSearchParams(location.search).get('pkg');
const shown = one ? PACKAGES.filter((p) => p.name === one) : PACKAGES;
let bounds = null;
const grow = (b) => {
  bounds = bounds ? [Math.min(bounds[0], b[0]), Math.min(bounds[1], b[1]),
                     Math.max(bounds[2], b[2]), Math.max(bounds[3], b[3])] : b.slice();
};
const tilejson = async (p) => (await fetch('/' + p.name + '.json')).json();
const skipped = [];
)JS";

const char* kMapLibreScript = R"JS(
import * as maplibregl from '@LIB@/maplibre-gl/dist/maplibre-gl.mjs';
try {
  // Background, the images (first given at the bottom), the terrain's
  // hillshade over them, then the vector packages' own styles on top: the
  // area packages' fills (and outlines) under the lines and points, and
  // every package's labels over them all.
  const style = { version: 8, sources: {}, layers: [
    { id: 'background', type: 'background', paint: { 'background-color': '#dde6d5' } }] };
  const images = [], areas = [], vectors = [], labels = [];
  let dem = null;
  for (const p of shown) {
    if (p.kind === 'pmtiles') continue;
    if (p.kind === 'terrain' && (dem || p.tiling === 'local')) {
      skipped.push(p.name + (dem ? ': one terrain at a time' : ': a local tiling'));
      continue;
    }
    if (p.kind !== 'terrain' && p.tiling !== 'webmercator') {
      skipped.push(p.name + ': MapLibre reads web mercator tiles, this is ' + p.tiling);
      continue;
    }
    const tj = await tilejson(p);
    grow(tj.bounds);
    if (p.kind === 'terrain') {
      dem = p.name;
      style.sources.dem = { type: 'raster-dem', url: '/' + p.name + '.json?encoding=terrarium',
                            encoding: 'terrarium' };
    } else if (p.kind === 'images') {
      style.sources[p.name] = { type: 'raster', tiles: tj.tiles, tileSize: tj.tileSize || 256,
                                minzoom: tj.minzoom, maxzoom: tj.maxzoom };
      images.push({ id: p.name, type: 'raster', source: p.name });
    } else {
      const own = await (await fetch('/' + p.name + '/style.json')).json();
      for (const [id, source] of Object.entries(own.sources))
        style.sources[p.name + '/' + id] = source;
      if (own.glyphs) style.glyphs = own.glyphs;  // the one /fonts of this server
      for (const layer of own.layers)
        (layer.type === 'symbol' ? labels : p.kind === 'areas' ? areas : vectors).push(
          { ...layer, id: p.name + '/' + layer.id, source: p.name + '/' + layer.source });
    }
  }
  style.layers.push(...images);
  if (dem) {
    style.layers.push({ id: 'hillshade', type: 'hillshade', source: 'dem',
                        paint: { 'hillshade-exaggeration': images.length ? 0.35 : 0.5 } });
    style.terrain = { source: 'dem' };
  }
  style.layers.push(...areas, ...vectors, ...labels);
  for (const s of skipped) console.log('not shown: ' + s);
  const map = new maplibregl.Map({ container: 'map', style,
    bounds: bounds ? [[bounds[0], bounds[1]], [bounds[2], bounds[3]]] : [[-180, -80], [180, 80]],
    fadeDuration: 0, canvasContextAttributes: { preserveDrawingBuffer: true } });
  map.addControl(new maplibregl.NavigationControl());
  map.on('error', (e) => fail(e.error || e));
  map.once('idle', () => { window.__result = { ok: true, loaded: map.loaded(),
    layers: map.getStyle().layers.map((l) => l.id), terrain: dem, skipped,
    features: map.queryRenderedFeatures().length }; });
} catch (e) { fail(e); }
)JS";

const char* kCesiumScript = R"JS(
(async () => {
  // The terrain, the images draped in the order given (first at the bottom),
  // then the area, line and point packages as images the server draws (the
  // areas under the lines and points, as in the MapLibre view).
  const terrain = shown.find((p) => p.kind === 'terrain' && p.tiling !== 'local');
  const options = { baseLayer: false, animation: false, timeline: false,
    baseLayerPicker: false, geocoder: false, sceneModePicker: false,
    navigationHelpButton: false, msaaSamples: 1,
    contextOptions: { webgl: { preserveDrawingBuffer: true } } };
  if (terrain) options.terrainProvider =
    await Cesium.CesiumTerrainProvider.fromUrl('/' + terrain.name + '/',
                                               { requestVertexNormals: true });
  const viewer = new Cesium.Viewer('globe', options);
  viewer.scene.globe.enableLighting = !!terrain;
  viewer.scene.globe.baseColor = Cesium.Color.fromCssColorString('#c8c0a8');
  const draped = [];
  const rank = (p) => (p.kind === 'areas' ? 1 : p.kind === 'lines' || p.kind === 'points' ? 2 : 0);
  for (const p of [...shown].sort((a, b) => rank(a) - rank(b))) {
    if (p.kind === 'pmtiles') continue;
    if (p.tiling === 'local') { skipped.push(p.name + ': a local tiling'); continue; }
    if (p.kind === 'terrain' && p !== terrain) { skipped.push(p.name + ': one terrain at a time'); continue; }
    const tj = await tilejson(p);
    grow(tj.bounds);
    if (p.kind === 'terrain') continue;
    const url = p.kind === 'images' ? tj.tiles[0]
                                    : location.origin + '/' + p.name + '/{z}/{x}/{y}.png';
    viewer.imageryLayers.addImageryProvider(new Cesium.UrlTemplateImageryProvider({ url,
      tilingScheme: p.tiling === 'geodetic' ? new Cesium.GeographicTilingScheme()
                                            : new Cesium.WebMercatorTilingScheme(),
      minimumLevel: tj.minzoom, maximumLevel: tj.maxzoom,
      rectangle: Cesium.Rectangle.fromDegrees(...tj.bounds) }));
    draped.push(p.name);
  }
  for (const s of skipped) console.log('not shown: ' + s);
  const b = bounds || [-180, -80, 180, 80];
  // Light from the north-west, whatever the time of day.
  const lon = (b[0] + b[2]) / 2, lat = (b[1] + b[3]) / 2, C3 = Cesium.Cartesian3;
  viewer.scene.light = new Cesium.DirectionalLight({ direction: C3.normalize(C3.subtract(
    C3.fromDegrees(lon, lat, 0), C3.fromDegrees(lon - 30, lat + 30, 8e6), new C3()), new C3()) });
  viewer.camera.flyTo({ destination: Cesium.Rectangle.fromDegrees(...b), duration: 0 });
  const remove = viewer.scene.postRender.addEventListener(() => {
    if (!viewer.scene.globe.tilesLoaded) return;
    remove();
    window.__result = { ok: true, terrain: terrain ? terrain.name : null, draped, skipped };
  });
})().catch(fail);
)JS";

}  // namespace

std::string index_page(const std::vector<PackageRegistry::Listed>& packages) {
  std::string rows;
  for (const auto& p : packages)
    rows += row(p);
  return std::string(kHead) +
         "<title>globe-serve</title><style>body{font:14px sans-serif;margin:2em}"
         "td,th{padding:4px 12px;text-align:left}</style></head><body><h1>globe-serve</h1>"
         "<p>All packages together: <a href=\"/view/maplibre.html\">MapLibre</a> "
         "<a href=\"/view/cesium.html\">CesiumJS</a></p>"
         "<table><tr><th>package</th><th>kind</th><th>tiling</th><th>zooms</th><th>data</th>"
         "<th>views</th></tr>" +
         rows + "</table></body></html>\n";
}

std::string maplibre_page(const std::string& lib,
                          const std::vector<PackageRegistry::Listed>& packages) {
  const std::string script =
      replace_all(replace_all(std::string(kCommonScript) + kMapLibreScript, "@LIB@", lib),
                  "@PACKAGES@", packages_json(packages));
  return std::string(kHead) +
         "<title>globe-serve: MapLibre</title><link rel=\"stylesheet\" href=\"" + lib +
         "/maplibre-gl/dist/maplibre-gl.css\">" +
         "<style>html,body,#map{margin:0;width:100%;height:100%}</style></head><body>"
         "<div id=\"map\"></div><script type=\"module\">" +
         script + "</script></body></html>\n";
}

std::string cesium_page(const std::string& lib,
                        const std::vector<PackageRegistry::Listed>& packages) {
  const std::string script = replace_all(std::string(kCommonScript) + kCesiumScript, "@PACKAGES@",
                                         packages_json(packages));
  return std::string(kHead) +
         "<title>globe-serve: CesiumJS</title><link rel=\"stylesheet\" href=\"" + lib +
         "/cesium/Build/Cesium/Widgets/widgets.css\"><script>window.CESIUM_BASE_URL = '" + lib +
         "/cesium/Build/Cesium/';</script><script src=\"" + lib +
         "/cesium/Build/Cesium/Cesium.js\"></script>"
         "<style>html,body,#globe{margin:0;width:100%;height:100%;overflow:hidden}</style>"
         "</head><body><div id=\"globe\"></div><script>" +
         script + "</script></body></html>\n";
}

}  // namespace globe::serve
