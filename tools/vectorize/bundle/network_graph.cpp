// The reference network (see network_graph.hpp).
#include "bundle/network_graph.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "geo/geodesic.hpp"
#include "geo/spatial_ref.hpp"
#include "io/vector_reader.hpp"
#include "runtime/errors.hpp"

namespace globe {

namespace {

constexpr double kMetresPerDegree = 111319.49;         // along the equator
constexpr double kMinCellDeg = 1e-4, kMaxCellDeg = 1;  // nearest(): grid cells
// A great-circle distance on the mean sphere is at least this fraction of
// the geodesic one on WGS84 (the two differ by under 0.6 %).
constexpr double kSphereShortfall = 0.99;

double sphere_distance_m(LonLat a, LonLat b) {
  constexpr double kR = 6371008.8, d = std::numbers::pi / 180;
  const double h =
      std::pow(std::sin((b.lat - a.lat) * d / 2), 2) +
      std::cos(a.lat * d) * std::cos(b.lat * d) * std::pow(std::sin((b.lon - a.lon) * d / 2), 2);
  return 2 * kR * std::asin(std::min(1.0, std::sqrt(h)));
}

uint64_t cell_key(int64_t cx, int64_t cy) {
  return (static_cast<uint64_t>(cx) << 32) ^ (static_cast<uint64_t>(cy) & 0xffffffffu);
}

struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(uint32_t a, uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

struct NetworkGraph::Builder::State {
  double eps = 0;  // the snapping grid, in degrees
  NetworkGraph g;
  std::unordered_map<uint64_t, uint32_t> node_at;
  std::unordered_map<uint64_t, size_t> edge_at;  // node pair -> edge
  std::vector<double> seg_m;

  // Longitudes wrap: a line split at the antimeridian (as GeoJSON asks)
  // joins its other half at -180 = 180.
  uint32_t node(LonLat p) {
    p.lon = std::remainder(p.lon, 360.0);
    if (p.lon >= 180) p.lon -= 360;
    const int64_t columns = std::llround(360 / eps);
    const int64_t column = std::llround(p.lon / eps);
    const auto key = cell_key(((column % columns) + columns) % columns, std::llround(p.lat / eps));
    auto [it, fresh] = node_at.try_emplace(key, static_cast<uint32_t>(g.nodes_.size()));
    if (fresh) g.nodes_.push_back(p);
    return it->second;
  }
};

NetworkGraph::Builder::Builder(double snap_m) : st_(std::make_unique<State>()) {
  st_->eps = std::max(snap_m, 1e-6) / kMetresPerDegree;
}

NetworkGraph::Builder::~Builder() = default;

void NetworkGraph::Builder::add_line(const std::vector<std::vector<LonLat>>& parts, double cost) {
  State& s = *st_;
  NetworkGraph& g = s.g;
  s.seg_m.clear();
  double line_m = 0;
  for (const auto& part : parts)
    for (size_t i = 1; i < part.size(); ++i) {
      s.seg_m.push_back(
          geodesic_distance_m(part[i - 1].lon, part[i - 1].lat, part[i].lon, part[i].lat));
      line_m += s.seg_m.back();
    }
  ++g.stats_.lines;
  // A cost field is the whole line's cost, shared out along it by length.
  double per_m = 1;
  if (!std::isnan(cost)) {
    if (!(cost >= 0) || !std::isfinite(cost) || line_m <= 0) return;
    per_m = cost / line_m;
  }
  size_t k = 0;
  for (const auto& part : parts)
    for (size_t i = 1; i < part.size(); ++i, ++k) {
      ++g.stats_.vertices;
      uint32_t a = s.node(part[i - 1]), b = s.node(part[i]);
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      // Snapped nodes moved the ends (by under the tolerance): the length
      // of the input segment stands.
      const double m = s.seg_m[k];
      auto [it, fresh] = s.edge_at.try_emplace(uint64_t{a} << 32 | b, g.edges_.size());
      if (fresh) {
        g.edges_.push_back({a, b, m * per_m, m});
      } else {
        ++g.stats_.parallel;
        Edge& e = g.edges_[it->second];
        if (m * per_m < e.cost) e = {a, b, m * per_m, m};
      }
    }
}

NetworkGraph NetworkGraph::Builder::finish() {
  NetworkGraph g = std::move(st_->g);
  st_ = std::make_unique<State>();
  g.stats_.nodes = g.nodes_.size();
  g.stats_.edges = g.edges_.size();
  g.find_components();
  g.index_nodes();
  return g;
}

NetworkGraph NetworkGraph::read(const std::vector<std::string>& inputs, const NetworkOptions& o,
                                Progress& progress) {
  VectorReaderOptions ro;
  ro.layers = o.layers;
  ro.s_srs = o.s_srs;
  ro.properties = false;
  if (!o.cost_field.empty()) {
    ro.value_fields = {o.cost_field};
    ro.field_options[o.cost_field] = "--cost-field";
  }
  VectorReader reader(inputs, ro);
  const SpatialRef lonlat = SpatialRef::from_user_input("EPSG:4326", "the network");
  std::vector<std::unique_ptr<CoordTransform>> to_lonlat;
  int64_t total = 0;
  for (const VectorLayerInfo& l : reader.layers()) {
    if (l.geometry == LayerGeometry::kPoints)
      throw InputError(l.source + " layer '" + l.name +
                       "' holds points; a network is lines (roads, rails, airways) that "
                       "connections are routed along");
    to_lonlat.push_back(std::make_unique<CoordTransform>(*l.crs, lonlat));
    total += std::max<int64_t>(0, l.feature_count);
  }
  Builder builder(o.snap_m);
  progress.begin("read the network", static_cast<uint64_t>(total));
  VectorFeature vf;
  std::vector<double> xs, ys;
  std::vector<int> ok;
  std::vector<std::vector<LonLat>> parts;
  while (reader.next(vf)) {
    progress.advance();
    if (vf.lines.empty()) continue;
    parts.clear();
    for (const auto& part : vf.lines) {
      xs.clear(), ys.clear();
      for (const XY& p : part)
        xs.push_back(p.x), ys.push_back(p.y);
      to_lonlat[vf.layer]->transform(xs, ys, ok);
      parts.emplace_back();
      for (size_t i = 0; i < xs.size(); ++i)
        if (ok[i] && std::isfinite(xs[i]) && std::isfinite(ys[i]) && std::abs(ys[i]) <= 90)
          parts.back().push_back({xs[i], ys[i]});
    }
    // A line without a cost (null) is left out, as one with a negative cost.
    const double cost = o.cost_field.empty()       ? std::nan("")
                        : std::isnan(vf.values[0]) ? -1.0
                                                   : vf.values[0];
    builder.add_line(parts, cost);
  }
  progress.end();
  NetworkGraph g = builder.finish();
  if (g.edges_.empty())
    throw InputError(inputs[0] + ": no line with two distinct vertices in the network" +
                     (o.layers.empty() ? "" : " (check --network-layer)"));
  return g;
}

void NetworkGraph::find_components() {
  UnionFind uf(nodes_.size());
  for (const Edge& e : edges_)
    uf.join(e.a, e.b);
  component_.resize(nodes_.size());
  std::unordered_map<uint32_t, uint64_t> sizes;
  for (uint32_t n = 0; n < nodes_.size(); ++n) {
    component_[n] = uf.find(n);
    ++sizes[component_[n]];
  }
  stats_.components = sizes.size();
  for (const auto& [root, size] : sizes)
    stats_.largest_component = std::max(stats_.largest_component, size);
}

void NetworkGraph::index_nodes() {
  // Cells of about four nodes on average over the nodes' extent (a whole
  // number of cells around the globe, so columns wrap).
  double w = 0, s = 0, e = 0, n = 0;
  for (size_t i = 0; i < nodes_.size(); ++i) {
    const LonLat p = nodes_[i];
    w = i ? std::min(w, p.lon) : p.lon, e = i ? std::max(e, p.lon) : p.lon;
    s = i ? std::min(s, p.lat) : p.lat, n = i ? std::max(n, p.lat) : p.lat;
  }
  const double area = std::max((e - w) * (n - s), 1e-6);
  const double want = std::clamp(std::sqrt(4 * area / double(std::max<size_t>(nodes_.size(), 1))),
                                 kMinCellDeg, kMaxCellDeg);
  columns_ = 2 * std::max<int64_t>(1, std::llround(180 / want));  // even: cells -c/2 .. c/2 - 1
  cell_deg_ = 360.0 / double(columns_);
  for (uint32_t i = 0; i < nodes_.size(); ++i)
    cells_[cell_key(static_cast<int64_t>(std::floor(nodes_[i].lon / cell_deg_)),
                    static_cast<int64_t>(std::floor(nodes_[i].lat / cell_deg_)))]
        .push_back(i);
}

std::optional<uint32_t> NetworkGraph::nearest(LonLat p, double max_m) const {
  // Rings of cells around p, outwards, until a ring starts beyond the best
  // distance found (or max_m). A spherical distance, a little short of any
  // geodesic one, skips most nodes before the ellipsoid is asked.
  const int64_t cx = static_cast<int64_t>(std::floor(p.lon / cell_deg_)),
                cy = static_cast<int64_t>(std::floor(p.lat / cell_deg_));
  const double cos_lat =
      std::max(std::cos(std::min(89.0, std::abs(p.lat)) * std::numbers::pi / 180), 0.01);
  const double ring_m = cell_deg_ * kMetresPerDegree * cos_lat;  // the narrower side
  std::optional<uint32_t> best;
  double best_m = max_m;
  for (int64_t r = 0;; ++r) {
    if ((r - 1) * ring_m > best_m || r > columns_) break;
    for (int64_t dy = -r; dy <= r; ++dy)
      for (int64_t dx = -r; dx <= r; ++dx) {
        if (std::max(std::abs(dx), std::abs(dy)) != r) continue;  // the ring only
        // Columns wrap at the antimeridian: cells are -columns/2 .. columns/2 - 1.
        const int64_t x =
            ((cx + dx + columns_ / 2) % columns_ + columns_) % columns_ - columns_ / 2;
        auto it = cells_.find(cell_key(x, cy + dy));
        if (it == cells_.end()) continue;
        for (uint32_t i : it->second) {
          if (kSphereShortfall * sphere_distance_m(p, nodes_[i]) > best_m) continue;
          const double m = geodesic_distance_m(p.lon, p.lat, nodes_[i].lon, nodes_[i].lat);
          if (m < best_m || (m == best_m && best && i < *best)) best = i, best_m = m;
        }
      }
  }
  return best;
}

ReducedGraph reduce_graph(const NetworkGraph& g, const std::vector<char>& terminal) {
  const size_t n = g.nodes().size();
  const auto& edges = g.edges();
  // Graph adjacency (CSR) of edge indices.
  std::vector<uint32_t> degree(n, 0);
  for (const auto& e : edges)
    ++degree[e.a], ++degree[e.b];
  std::vector<uint32_t> off(n + 1, 0);
  for (size_t i = 0; i < n; ++i)
    off[i + 1] = off[i] + degree[i];
  std::vector<uint32_t> adj(off[n]), fill(off.begin(), off.end() - 1);
  for (uint32_t e = 0; e < edges.size(); ++e) {
    adj[fill[edges[e].a]++] = e;
    adj[fill[edges[e].b]++] = e;
  }
  ReducedGraph r;
  r.reduced_node.assign(n, -1);
  auto keep = [&](uint32_t v) { return degree[v] != 2 || terminal[v]; };
  for (uint32_t v = 0; v < n; ++v)
    if (keep(v) && degree[v] > 0) {
      r.reduced_node[v] = static_cast<int32_t>(r.graph_node.size());
      r.graph_node.push_back(v);
    }
  std::vector<char> used(edges.size(), 0);
  auto other = [&](uint32_t e, uint32_t v) { return edges[e].a == v ? edges[e].b : edges[e].a; };
  // Walks the chain leaving `start` by edge `e` until a kept node.
  auto walk = [&](uint32_t start, uint32_t e) {
    ReducedGraph::Edge out;
    out.first = static_cast<uint32_t>(r.path.size());
    r.path.push_back(start);
    uint32_t v = start;
    for (;;) {
      used[e] = 1;
      out.cost += edges[e].cost;
      out.length_m += edges[e].length_m;
      v = other(e, v);
      r.path.push_back(v);
      if (r.reduced_node[v] >= 0) break;
      // An interior node: degree 2, go on by its other edge.
      const uint32_t e0 = adj[off[v]], e1 = adj[off[v] + 1];
      e = e0 == e ? e1 : e0;
      if (used[e]) break;  // a loop of interior nodes only (handled below)
    }
    out.count = static_cast<uint32_t>(r.path.size()) - out.first;
    out.a = static_cast<uint32_t>(r.reduced_node[start]);
    out.b = static_cast<uint32_t>(r.reduced_node[v]);
    r.edges.push_back(out);
  };
  for (uint32_t k = 0; k < r.graph_node.size(); ++k) {
    const uint32_t v = r.graph_node[k];
    for (uint32_t i = off[v]; i < off[v + 1]; ++i)
      if (!used[adj[i]]) walk(v, adj[i]);
  }
  // Loops of interior nodes only (no junction): their smallest node is kept.
  for (uint32_t e = 0; e < edges.size(); ++e) {
    if (used[e]) continue;
    const uint32_t v = edges[e].a;
    r.reduced_node[v] = static_cast<int32_t>(r.graph_node.size());
    r.graph_node.push_back(v);
    walk(v, e);
  }
  // Reduced adjacency (CSR). A loop (a == b: a lasso off a junction, or a
  // ring of interior nodes) is listed once at its node: counting it twice
  // left a slot unfilled, read as edge 0 by the router, whose path
  // reconstruction then followed an edge that does not touch the node.
  const size_t m = r.graph_node.size();
  r.offsets.assign(m + 1, 0);
  for (const auto& e : r.edges) {
    ++r.offsets[e.a + 1];
    if (e.b != e.a) ++r.offsets[e.b + 1];
  }
  for (size_t i = 0; i < m; ++i)
    r.offsets[i + 1] += r.offsets[i];
  r.incident.resize(r.offsets[m]);
  std::vector<uint32_t> at(r.offsets.begin(), r.offsets.end() - 1);
  for (uint32_t e = 0; e < r.edges.size(); ++e) {
    r.incident[at[r.edges[e].a]++] = e;
    if (r.edges[e].b != r.edges[e].a) r.incident[at[r.edges[e].b]++] = e;
  }
  return r;
}

}  // namespace globe
