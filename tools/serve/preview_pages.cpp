// Preview pages (see preview_pages.hpp).
#include "serve/preview_pages.hpp"

#include <cstdio>

namespace globe::serve {
namespace {

const char* kHead =
    "<!doctype html><html><head><meta charset=\"utf-8\"><link rel=\"icon\" href=\"data:,\">"
    "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">";

// Names are [A-Za-z0-9._-] (url_route.hpp): safe in HTML and URLs as they are.
std::string row(const PackageRegistry::Listed& p) {
  char zooms[64];
  std::snprintf(zooms, sizeof zooms, "%d..%d", p.service->min_zoom, p.service->max_zoom);
  const std::string q = "?pkg=" + p.name + "&kind=" + p.kind;
  std::string views;
  if (p.kind != "pmtiles") views += "<a href=\"/view/maplibre.html" + q + "\">MapLibre</a> ";
  if (p.kind == "terrain" || p.kind == "images")
    views += "<a href=\"/view/cesium.html" + q + "\">CesiumJS</a>";
  std::string links = p.kind == "pmtiles"
                          ? "<a href=\"/" + p.name + ".pmtiles\">" + p.name + ".pmtiles</a>"
                          : "<a href=\"/" + p.name + ".json\">TileJSON</a>";
  if (p.kind == "terrain") links += " <a href=\"/" + p.name + "/layer.json\">layer.json</a>";
  if (p.kind == "lines" || p.kind == "points")
    links += " <a href=\"/" + p.name + "/style.json\">style.json</a>";
  return "<tr><td>" + p.name + "</td><td>" + p.kind + "</td><td>" + zooms + "</td><td>" + links +
         "</td><td>" + views + "</td></tr>";
}

}  // namespace

std::string index_page(const std::vector<PackageRegistry::Listed>& packages) {
  std::string rows;
  for (const auto& p : packages)
    rows += row(p);
  return std::string(kHead) +
         "<title>globe-serve</title><style>body{font:14px sans-serif;margin:2em}"
         "td,th{padding:4px 12px;text-align:left}</style></head><body><h1>globe-serve</h1>"
         "<table><tr><th>package</th><th>kind</th><th>zooms</th><th>data</th><th>views</th></tr>" +
         rows + "</table></body></html>\n";
}

std::string maplibre_page(const std::string& lib) {
  return std::string(kHead) +
         "<title>globe-serve: MapLibre</title><link rel=\"stylesheet\" href=\"" + lib +
         "/maplibre-gl/dist/maplibre-gl.css\">"
         "<style>html,body,#map{margin:0;width:100%;height:100%}</style></head><body>"
         "<div id=\"map\"></div><script type=\"module\">\n"
         "import * as maplibregl from '" +
         lib +
         "/maplibre-gl/dist/maplibre-gl.mjs';\n"
         "const fail = (e) => { window.__result = { ok: false, error: String(e && e.stack || e) }; "
         "};\n"
         "try {\n"
         "  const q = new URLSearchParams(location.search);\n"
         "  const name = q.get('pkg'), kind = q.get('kind');\n"
         "  const tj = await (await fetch('/' + name + '.json')).json();\n"
         "  let style;\n"
         "  if (kind === 'terrain') style = { version: 8, sources: { dem: { type: 'raster-dem',\n"
         "      url: '/' + name + '.json?encoding=terrarium', encoding: 'terrarium' } },\n"
         "    layers: [{ id: 'bg', type: 'background', paint: { 'background-color': '#dde6d5' } "
         "},\n"
         "      { id: 'shade', type: 'hillshade', source: 'dem' }], terrain: { source: 'dem' } };\n"
         "  else if (kind === 'images') style = { version: 8, sources: { img: { type: 'raster',\n"
         "      tiles: tj.tiles, tileSize: tj.tileSize || 256, minzoom: tj.minzoom,\n"
         "      maxzoom: tj.maxzoom } }, layers: [{ id: 'img', type: 'raster', source: 'img' }] "
         "};\n"
         "  else style = '/' + name + '/style.json';\n"
         "  const map = new maplibregl.Map({ container: 'map', style, bounds: [[tj.bounds[0],\n"
         "    tj.bounds[1]], [tj.bounds[2], tj.bounds[3]]], fadeDuration: 0,\n"
         "    canvasContextAttributes: { preserveDrawingBuffer: true } });\n"
         "  map.addControl(new maplibregl.NavigationControl());\n"
         "  map.on('error', (e) => fail(e.error || e));\n"
         "  map.once('idle', () => { window.__result = { ok: true, loaded: map.loaded(),\n"
         "    tiles: map.queryRenderedFeatures().length }; });\n"
         "} catch (e) { fail(e); }\n"
         "</script></body></html>\n";
}

std::string cesium_page(const std::string& lib) {
  return std::string(kHead) +
         "<title>globe-serve: CesiumJS</title><link rel=\"stylesheet\" href=\"" + lib +
         "/cesium/Build/Cesium/Widgets/widgets.css\"><script>window.CESIUM_BASE_URL = '" + lib +
         "/cesium/Build/Cesium/';</script><script src=\"" + lib +
         "/cesium/Build/Cesium/Cesium.js\"></script>"
         "<style>html,body,#globe{margin:0;width:100%;height:100%;overflow:hidden}</style>"
         "</head><body><div id=\"globe\"></div><script>\n"
         "(async () => {\n"
         "  const q = new URLSearchParams(location.search);\n"
         "  const name = q.get('pkg'), kind = q.get('kind');\n"
         "  const tj = await (await fetch('/' + name + '.json')).json();\n"
         "  const options = { baseLayer: false, animation: false, timeline: false,\n"
         "    baseLayerPicker: false, geocoder: false, sceneModePicker: false,\n"
         "    navigationHelpButton: false,\n"
         "    contextOptions: { webgl: { preserveDrawingBuffer: true } } };\n"
         "  if (kind === 'terrain') options.terrainProvider =\n"
         "    await Cesium.CesiumTerrainProvider.fromUrl('/' + name + '/',\n"
         "                                               { requestVertexNormals: true });\n"
         "  const viewer = new Cesium.Viewer('globe', options);\n"
         "  viewer.scene.globe.enableLighting = kind === 'terrain';\n"
         "  if (kind === 'images') viewer.imageryLayers.addImageryProvider(\n"
         "    new Cesium.UrlTemplateImageryProvider({ url: tj.tiles[0], maximumLevel: tj.maxzoom,\n"
         "      minimumLevel: tj.minzoom }));\n"
         "  viewer.scene.globe.baseColor = Cesium.Color.fromCssColorString('#c8c0a8');\n"
         "  // Light from the north-west, whatever the time of day.\n"
         "  const lon = (tj.bounds[0] + tj.bounds[2]) / 2, lat = (tj.bounds[1] + tj.bounds[3]) / "
         "2;\n"
         "  const C3 = Cesium.Cartesian3;\n"
         "  viewer.scene.light = new Cesium.DirectionalLight({ direction: "
         "C3.normalize(C3.subtract(\n"
         "    C3.fromDegrees(lon, lat, 0), C3.fromDegrees(lon - 30, lat + 30, 8e6), new C3()),\n"
         "    new C3()) });\n"
         "  viewer.camera.flyTo({ destination: Cesium.Rectangle.fromDegrees(...tj.bounds),\n"
         "    duration: 0 });\n"
         "  const remove = viewer.scene.postRender.addEventListener(() => {\n"
         "    if (!viewer.scene.globe.tilesLoaded) return;\n"
         "    remove();\n"
         "    window.__result = { ok: true };\n"
         "  });\n"
         "})().catch((e) => { window.__result = { ok: false, error: String(e) }; });\n"
         "</script></body></html>\n";
}

}  // namespace globe::serve
