// Bundled-flow package builder (see bundle_builder.hpp).
#include "bundle/bundle_builder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "bundle/bundle_curve.hpp"
#include "bundle/bundles.hpp"
#include "bundle/routing.hpp"
#include "bundle/significance.hpp"
#include "geo/geodesic.hpp"
#include "io/geometry_scratch.hpp"
#include "io/vector_reader.hpp"
#include "kit/package_output.hpp"
#include "kit/parallel_batches.hpp"
#include "labels/label_candidates.hpp"
#include "lines/line_classes.hpp"
#include "lines/line_metadata.hpp"
#include "lines/line_plan.hpp"
#include "lines/line_projector.hpp"
#include "lines/line_tiles.hpp"
#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/feature_table.hpp"
#include "tileformat/json.hpp"
#include "tileformat/label_table.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"
#include "tiles/tile_sorter.hpp"

namespace globe {
namespace {

using Clock = std::chrono::steady_clock;
using tileformat::Bounds;

constexpr double kStraightStepM = 10000;  // unrouted lines: a vertex every 10 km at most
constexpr double kSampleStepPx = 2;       // curves: a vertex about every 2 px of their zoom
constexpr int kMinDefaultMaxZoom = 6;     // the default finest zoom is at least this

// Why a connection is not routed ("" = routed).
enum class Reason { kRouted, kUnsnapped, kSameNode, kDisconnected };

const char* reason_text(Reason r) {
  switch (r) {
    case Reason::kUnsnapped:
      return "no network node within --max-snap";
    case Reason::kSameNode:
      return "origin and destination snap to the same node";
    case Reason::kDisconnected:
      return "origin and destination in different network components";
    default:
      return "";
  }
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string lonlat_json(LonLat p) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "[%.7f,%.7f]", p.lon, p.lat);
  return buf;
}

// The YlOrRd ramp the weight classes take their colours from.
std::string ramp_color(double t) {
  static const int stops[][3] = {{254, 217, 118}, {254, 178, 76}, {253, 141, 60},
                                 {240, 59, 32},   {189, 0, 38},   {128, 0, 38}};
  const double x = std::clamp(t, 0.0, 1.0) * 5;
  const int i = std::min(4, static_cast<int>(x));
  const double f = x - i;
  char buf[8];
  int c[3];
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<int>(std::lround(stops[i][k] + f * (stops[i + 1][k] - stops[i][k])));
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c[0], c[1], c[2]);
  return buf;
}

class Builder {
 public:
  Builder(const BundleSettings& s, Progress& progress)
      : s_(s), progress_(progress), threads_(s.worker_threads()) {}

  BundleSummary run() {
    const auto start = Clock::now();
    frame_ = choose_vector_frame(s_.like, s_);
    if (frame_.frame == TargetFrame::kProjected && !frame_.target)
      throw UsageError("--tiling local needs --t_srs (or --like a local package) for bundles");
    if (frame_.frame == TargetFrame::kProjected)
      to_target_ = std::make_unique<CoordTransform>(
          SpatialRef::from_user_input("EPSG:4326", "longitude/latitude"), *frame_.target);

    stage("network", [&] { graph_.emplace(NetworkGraph::read(s_.network, s_.net, progress_)); });
    stage("flows", [&] { flows_ = read_flows(s_.flows, s_.flow); });
    if (flows_.connections.empty())
      throw InputError(s_.flows + ": no usable connection in " + std::to_string(flows_.rows) +
                       " rows" + bad_rows_text() +
                       "; check the flow columns (--from/--to or --from-id/--to-id) and --weight");
    stage("snap", [&] { snap(); });
    stage("reduce", [&] { reduced_ = reduce_graph(*graph_, terminal_); });
    stage("route", [&] { route(); });
    fill_input_summary();
    stage("bundle", [&] {
      std::vector<double> weights;
      for (const Connection& c : flows_.connections)
        weights.push_back(c.weight);
      bundles_ = make_bundles(reduced_, routes_, weights);
    });
    std::unique_ptr<tileformat::PackageWriter> writer = create_package(s_, progress_);
    write_package_tiles(s_.output, [&] {
      GeometryScratch scratch(s_.output + ".scratch-geometry");
      stage("smooth", [&] {
        plan();
        smooth(scratch);
      });
      stage("features", [&] {
        tileformat::FeatureTableWriter features(*writer);
        if (!features.complete()) write_features(features);
        if (!s_.flow.label_field.empty()) {
          tileformat::LabelTableWriter labels(*writer);
          if (!labels.complete()) write_endpoint_labels(labels);
          label_count_ = labels.count();
        }
      });
      writer->checkpoint();  // the features table is committed before any tile
      LineTileOptions tiles;
      tiles.extent = s_.extent;
      tiles.cluster_grid = s_.cluster_grid;
      tiles.simplify_px = s_.simplify_px;
      tiles.threads = threads_;
      TileSorter sorter(s_.output + ".scratch-sort", s_.memory_mb << 20);
      LineTileStats stats;
      stage("tiles", [&] {
        cut_line_tiles(scratch, scratch_features_, plan_, tiles, sorter, stats, progress_);
        encode_line_tiles(sorter, plan_, tiles, *writer, stats, progress_);
      });
    });
    if (writer->tiles_written() == 0)
      throw InputError(s_.flows + ": no bundle or line falls in the requested area" +
                       (s_.bbox ? " (check --bbox)" : "") + "; nothing written");
    tileformat::LineMetadata meta = line_metadata(s_, frame_, plan_, classes_, facts_);
    meta.bundle_json = bundle_json();
    writer->set_metadata(tileformat::to_metadata(meta));
    if (!s_.flow.label_field.empty())
      writer->set_metadata("globe:labels",
                           labels_metadata_json(s_.flow.label_field, "weight", label_count_));
    commit_package(*writer, s_.output, start, sum_);
    return sum_;
  }

 private:
  template <typename Fn>
  void stage(const char* name, Fn&& fn) {
    const auto t0 = Clock::now();
    fn();
    sum_.stage_seconds.emplace_back(name, std::chrono::duration<double>(Clock::now() - t0).count());
  }

  void fill_input_summary() {
    sum_.rows = flows_.rows;
    sum_.connections = flows_.connections.size();
    sum_.bad_rows = flows_.bad_rows();
    sum_.zero_weights = flows_.zero_weights;
    sum_.bad_row_examples = flows_.examples;
    const NetworkStats& n = graph_->stats();
    sum_.network_nodes = n.nodes;
    sum_.network_edges = n.edges;
    sum_.components = n.components;
    sum_.reduced_nodes = reduced_.graph_node.size();
    sum_.reduced_edges = reduced_.edges.size();
  }

  std::string bad_rows_text() const {
    std::string out;
    auto add = [&](uint64_t n, const char* what) {
      if (n) out += (out.empty() ? " (" : ", ") + std::to_string(n) + " " + what;
    };
    add(flows_.bad_coordinates, "without a usable origin or destination");
    add(flows_.unknown_ids, "with an id not in --locations");
    add(flows_.bad_weights, "with a missing or negative weight");
    add(flows_.zero_weights, "of weight 0");
    return out.empty() ? out : out + ")";
  }

  // Each distinct place -> its node within --max-snap (searches in parallel).
  void snap() {
    std::map<std::pair<double, double>, uint32_t> place_ids;
    std::vector<LonLat> places;
    auto place = [&](LonLat p) {
      auto [it, fresh] = place_ids.try_emplace({p.lon, p.lat}, uint32_t(places.size()));
      if (fresh) places.push_back(p);
      return it->second;
    };
    for (const Connection& c : flows_.connections)
      ends_.push_back({place(c.from), place(c.to)});
    place_node_.assign(places.size(), -1);
    progress_.begin("snap places to the network", places.size());
    parallel_batches<NoInputs, int64_t>(
        places.size(), threads_, 256, [](size_t, size_t) { return NoInputs{}; },
        [&](size_t i, int, const NoInputs&) {
          const auto n = graph_->nearest(places[i], s_.max_snap_m);
          return n ? int64_t(*n) : int64_t(-1);
        },
        [&](size_t i, int64_t&& node) {
          place_node_[i] = node;
          progress_.advance();
        },
        [](size_t) {});
    progress_.end();
    places_ = std::move(places);
    terminal_.assign(graph_->nodes().size(), 0);
    uint64_t snapped = 0;
    for (int64_t n : place_node_)
      if (n >= 0) terminal_[size_t(n)] = 1, ++snapped;
    if (snapped == 0) {
      Bounds b{1e300, 1e300, -1e300, -1e300};
      for (const LonLat& p : graph_->nodes())
        b = {std::min(b.min_x, p.lon), std::min(b.min_y, p.lat), std::max(b.max_x, p.lon),
             std::max(b.max_y, p.lat)};
      char area[160];
      std::snprintf(area, sizeof area, "%.3f,%.3f,%.3f,%.3f", b.min_x, b.min_y, b.max_x, b.max_y);
      throw InputError(s_.flows + ": none of its " + std::to_string(places_.size()) +
                       " places lies within --max-snap " + number(s_.max_snap_m) +
                       " m of a node of the network (" + s_.network[0] + ", lon/lat " + area +
                       "); check that flows and network cover the same area, or raise "
                       "--max-snap");
    }
  }

  void route() {
    std::vector<OriginDestination> od;
    std::vector<uint32_t> od_connection;
    reasons_.assign(flows_.connections.size(), Reason::kRouted);
    for (uint32_t c = 0; c < flows_.connections.size(); ++c) {
      const int64_t a = place_node_[ends_[c].first], b = place_node_[ends_[c].second];
      if (a < 0 || b < 0) {
        reasons_[c] = Reason::kUnsnapped;
      } else if (a == b) {
        reasons_[c] = Reason::kSameNode;
      } else if (graph_->component(uint32_t(a)) != graph_->component(uint32_t(b))) {
        reasons_[c] = Reason::kDisconnected;
      } else {
        od.push_back({uint32_t(reduced_.reduced_node[size_t(a)]),
                      uint32_t(reduced_.reduced_node[size_t(b)])});
        od_connection.push_back(c);
      }
    }
    std::vector<std::vector<uint32_t>> found;
    try {
      found = route_connections(reduced_, od, threads_, progress_);
    } catch (const RouteError& e) {
      const Connection& c = flows_.connections[od_connection[e.connection]];
      throw std::logic_error("routing " + s_.flows + " row " + std::to_string(c.row) + " (" +
                             c.origin + " -> " + c.destination + "): " + e.what());
    }
    routes_.assign(flows_.connections.size(), {});
    for (size_t i = 0; i < od.size(); ++i) {
      routes_[od_connection[i]] = std::move(found[i]);
      if (routes_[od_connection[i]].empty()) reasons_[od_connection[i]] = Reason::kDisconnected;
    }
    for (Reason r : reasons_) {
      sum_.routed += r == Reason::kRouted;
      sum_.unsnapped += r == Reason::kUnsnapped;
      sum_.same_node += r == Reason::kSameNode;
      sum_.disconnected += r == Reason::kDisconnected;
    }
    sum_.unrouted = flows_.connections.size() - sum_.routed;
  }

  // A polyline of lon/lat in the frame; longitudes unrolled along it in the
  // global frames (so a bundle across the antimeridian stays one curve).
  std::vector<XY> to_frame(const std::vector<LonLat>& pts) const {
    std::vector<XY> out;
    if (frame_.frame == TargetFrame::kProjected) {
      std::vector<double> x, y;
      for (const LonLat& p : pts)
        x.push_back(p.lon), y.push_back(p.lat);
      std::vector<int> ok;
      to_target_->transform(x, y, ok);
      for (size_t i = 0; i < x.size(); ++i)
        if (ok[i] && std::isfinite(x[i]) && std::isfinite(y[i])) out.push_back({x[i], y[i]});
      return out;
    }
    double lon = 0;
    for (size_t i = 0; i < pts.size(); ++i) {
      lon = i == 0 ? pts[i].lon : lon + std::remainder(pts[i].lon - pts[i - 1].lon, 360.0);
      out.push_back(LineProjector::lonlat_to_frame(frame_.frame, {lon, pts[i].lat}));
    }
    return out;
  }

  // Frame parts of a curve in the (unrolled) frame: cut at the antimeridian.
  std::vector<std::vector<XY>> frame_parts(const std::vector<XY>& curve) const {
    std::vector<std::vector<XY>> out;
    if (frame_.frame == TargetFrame::kProjected) {
      std::vector<XY> part = curve;
      if (clean_part(part) == PartStatus::kOk) out.push_back(std::move(part));
      return out;
    }
    std::vector<XY> lonlat;
    for (const XY& p : curve)
      lonlat.push_back(LineProjector::frame_to_lonlat(frame_.frame, p));
    for (auto& piece : split_antimeridian(lonlat)) {
      for (XY& p : piece)
        p = LineProjector::lonlat_to_frame(frame_.frame, p);
      if (clean_part(piece) == PartStatus::kOk) out.push_back(std::move(piece));
    }
    return out;
  }

  void extend(XY p) {
    facts_.extent = {std::min(facts_.extent.min_x, p.x), std::min(facts_.extent.min_y, p.y),
                     std::max(facts_.extent.max_x, p.x), std::max(facts_.extent.max_y, p.y)};
  }

  // Frame polylines, classes, the zoom plan.
  void plan() {
    const auto& nodes = graph_->nodes();
    LengthHistogram lengths;
    bundle_polys_.resize(bundles_.bundles.size());
    for (size_t b = 0; b < bundles_.bundles.size(); ++b) {
      std::vector<LonLat> pts;
      for (uint32_t n : bundles_.bundles[b].nodes)
        pts.push_back(nodes[n]);
      bundle_polys_[b] = to_frame(pts);
      for (const auto& part : frame_parts(bundle_polys_[b]))
        for (size_t i = 0; i < part.size(); ++i) {
          extend(part[i]);
          if (i) lengths.add(std::hypot(part[i].x - part[i - 1].x, part[i].y - part[i - 1].y));
        }
    }
    if (s_.unrouted == Unrouted::kStraight)
      for (uint32_t c = 0; c < flows_.connections.size(); ++c) {
        if (reasons_[c] == Reason::kRouted) continue;
        const Connection& k = flows_.connections[c];
        const double m = geodesic_distance_m(k.from.lon, k.from.lat, k.to.lon, k.to.lat);
        std::vector<LonLat> pts;
        for (auto [lon, lat] : geodesic_points(k.from.lon, k.from.lat, k.to.lon, k.to.lat,
                                               std::max(kStraightStepM, m / 1000)))
          pts.push_back({lon, lat});
        straight_.push_back({c, frame_parts(to_frame(pts))});
        for (const auto& part : straight_.back().second)
          for (const XY& p : part)
            extend(p);
      }
    std::erase_if(straight_, [](const auto& s) { return s.second.empty(); });
    if (bundles_.bundles.empty() && straight_.empty())
      throw InputError(
          s_.flows + ": nothing to draw: none of its " + std::to_string(flows_.connections.size()) +
          " connections is routed (" + std::to_string(sum_.unsnapped) +
          " with a place beyond --max-snap, " + std::to_string(sum_.same_node) + " on one node, " +
          std::to_string(sum_.disconnected) + " across network components) and --unrouted drop");

    // Weight classes by the square root of a bundle's share of the heaviest
    // (widths then grow about as the square root of weight), wider, darker
    // and more opaque with weight; class ids lightest first, so heavier
    // classes are drawn on top.
    std::vector<std::string> styles;
    const int n = s_.weight_classes;
    styles.push_back("unrouted:color=#8c8c8c,width=" + number(s_.min_width) +
                     ",dash=6+4,opacity=" + number(s_.min_opacity));
    for (int k = 1; k <= n; ++k) {
      const double t = n > 1 ? double(k - 1) / (n - 1) : 1;
      styles.push_back("weight-" + std::to_string(k) + ":color=" + ramp_color(t) + ",width=" +
                       number(s_.min_width + t * (s_.max_width - s_.min_width)) + ",opacity=" +
                       number(s_.min_opacity + t * (s_.max_opacity - s_.min_opacity)));
    }
    styles.insert(styles.end(), s_.styles.begin(), s_.styles.end());
    classes_ = LineClasses("", styles);
    double hi = 0;
    for (const Bundle& b : bundles_.bundles)
      hi = std::max(hi, b.weight);
    class_bounds_.assign(size_t(n), {1e300, 0});
    std::vector<int> weight_class;
    for (const Bundle& b : bundles_.bundles) {
      const double root = hi > 0 ? std::sqrt(b.weight / hi) : 1;
      const int k = std::clamp(static_cast<int>(std::ceil(root * n)), 1, n);
      weight_class.push_back(k);
      auto& [cmin, cmax] = class_bounds_[size_t(k - 1)];
      cmin = std::min(cmin, b.weight), cmax = std::max(cmax, b.weight);
    }
    // Class ids: unrouted first (under every bundle), then the weight
    // classes lightest first, each counting its features.
    unrouted_class_ = straight_.empty() ? 0 : classes_.class_for("unrouted", "unrouted");
    for (size_t i = 1; i < straight_.size(); ++i)
      classes_.class_for("unrouted", "unrouted");
    bundle_class_.assign(bundles_.bundles.size(), 0);
    for (int k = 1; k <= n; ++k)
      for (size_t b = 0; b < bundles_.bundles.size(); ++b)
        if (weight_class[b] == k)
          bundle_class_[b] = classes_.class_for("bundles", "weight-" + std::to_string(k));
    plan_ = plan_lines(s_, frame_, facts_.extent, lengths, classes_);
    if (!s_.max_zoom && plan_.max_zoom < kMinDefaultMaxZoom) {
      // Curves are sampled for their finest zoom: a network of long segments
      // (airways) still gets smooth curves a few zooms in.
      LinesSettings deeper = s_;
      deeper.max_zoom = std::max(kMinDefaultMaxZoom, s_.min_zoom.value_or(0));
      plan_ = plan_lines(deeper, frame_, facts_.extent, lengths, classes_);
    }
    sum_.min_zoom = plan_.min_zoom;
    sum_.max_zoom = plan_.max_zoom;

    std::vector<WeightedFlow> flows;
    for (size_t b = 0; b < bundles_.bundles.size(); ++b)
      flows.push_back({bundles_.bundles[b].weight, frame_parts(bundle_polys_[b])});
    for (const auto& [c, parts] : straight_)
      flows.push_back({flows_.connections[c].weight, parts});
    flow_zooms_ = significant_zooms(flows, plan_.tiling, plan_.min_zoom, plan_.max_zoom,
                                    {s_.significance, s_.min_weight});
    double heaviest = 0;
    for (const WeightedFlow& f : flows)
      heaviest = std::max(heaviest, f.weight);
    for (uint32_t z : flow_zooms_) {
      sum_.hidden_at_min_zoom += !(z >> plan_.min_zoom & 1);
      sum_.never_drawn += z == 0;
    }
    if (sum_.never_drawn == flows.size())
      throw InputError(s_.flows + ": every bundle and line is lighter than --min-weight " +
                       number(s_.min_weight) + " (the heaviest weighs " + number(heaviest) +
                       "); nothing written");
    tangents_.assign(bundles_.bundles.size(), {XY{0, 0}, XY{0, 0}});
    if (s_.smooth_junctions) {
      std::vector<std::pair<uint32_t, uint32_t>> ends;
      std::vector<double> weights;
      for (const Bundle& b : bundles_.bundles) {
        ends.emplace_back(b.nodes.front(), b.nodes.back());
        weights.push_back(b.weight);
      }
      tangents_ = junction_tangents(bundle_polys_, ends, weights);
    }
  }

  // Curves of every bundle (in parallel, consumed in order) and the straight
  // lines, into the scratch file.
  void smooth(GeometryScratch& scratch) {
    std::vector<double> tolerance(size_t(plan_.max_zoom) + 1), step(tolerance.size());
    for (int z = plan_.min_zoom; z <= plan_.max_zoom; ++z) {
      const double px = plan_.tiling.tile_size(z) / kLineTilePx;
      tolerance[size_t(z)] = s_.corridor_px * px;
      step[size_t(z)] = kSampleStepPx * px;
    }
    using Levels = std::vector<ProjectedFeature>;
    progress_.begin("smooth bundles", bundles_.bundles.size());
    parallel_batches<NoInputs, Levels>(
        bundles_.bundles.size(), threads_, 64, [](size_t, size_t) { return NoInputs{}; },
        [&](size_t b, int, const NoInputs&) {
          Levels out;
          for (CurveLevel& level :
               smooth_bundle(bundle_polys_[b], plan_.min_zoom, plan_.max_zoom, tolerance, step,
                             tangents_[b].first, tangents_[b].second)) {
            ProjectedFeature f;
            f.id = b + 1;
            f.class_id = bundle_class_[b];
            f.zooms = level.zooms & flow_zooms_[b];
            if (f.zooms == 0) continue;
            f.lines = frame_parts(level.curve);
            out.push_back(std::move(f));
          }
          return out;
        },
        [&](size_t, Levels&& levels) {
          for (const ProjectedFeature& f : levels) {
            scratch.write(f);
            ++scratch_features_;
            ++sum_.curve_levels;
            for (const auto& part : f.lines)
              sum_.curve_points += part.size();
          }
          progress_.advance();
        },
        [](size_t) {});
    progress_.end();
    for (size_t i = 0; i < straight_.size(); ++i) {
      ProjectedFeature f;
      f.id = bundles_.bundles.size() + i + 1;
      f.class_id = unrouted_class_;
      f.zooms = flow_zooms_[bundles_.bundles.size() + i];
      if (f.zooms == 0) continue;
      f.lines = straight_[i].second;
      scratch.write(f);
      ++scratch_features_;
    }
    scratch.rewind();
    sum_.bundles = bundles_.bundles.size();
  }

  // Bundles, then straight lines, then one row per connection.
  // One label per end of the connections (an airport): its --label-field
  // name (the id where it has none), ranked by the weight that starts or
  // ends there, in id order.
  void write_endpoint_labels(tileformat::LabelTableWriter& labels) {
    struct End {
      LonLat at;
      double weight = 0;
    };
    std::map<std::string, End> ends;
    for (const Connection& c : flows_.connections) {
      for (const auto& [id, at] : {std::pair{&c.origin, c.from}, std::pair{&c.destination, c.to}}) {
        End& e = ends[*id];
        e.at = at;
        e.weight += c.weight;
      }
    }
    for (const auto& [id, e] : ends) {
      tileformat::LabelRecord r;
      r.feature = 0;  // an end is no feature of the package
      const auto name = flows_.names.find(id);
      r.text = name != flows_.names.end() ? name->second : id;
      r.priority = e.weight;
      r.lon = e.at.lon, r.lat = e.at.lat;
      r.placement = tileformat::LabelPlacement::kPoint;
      labels.add(r);
    }
  }

  void write_features(tileformat::FeatureTableWriter& features) {
    const auto& nodes = graph_->nodes();
    int64_t id = 0;
    for (const Bundle& b : bundles_.bundles)
      features.add(++id, "bundles",
                   "{\"weight\":" + number(b.weight) + ",\"count\":" + std::to_string(b.count) +
                       ",\"length_m\":" + number(std::round(b.length_m)) +
                       ",\"from\":" + lonlat_json(nodes[b.nodes.front()]) +
                       ",\"to\":" + lonlat_json(nodes[b.nodes.back()]) + "}");
    std::vector<int64_t> line_of(flows_.connections.size(), 0);
    for (const auto& [c, parts] : straight_) {
      const Connection& k = flows_.connections[c];
      line_of[c] = ++id;
      features.add(id, "unrouted",
                   "{\"origin\":\"" + tileformat::json_escape(k.origin) + "\",\"destination\":\"" +
                       tileformat::json_escape(k.destination) + "\",\"weight\":" +
                       number(k.weight) + ",\"reason\":\"" + reason_text(reasons_[c]) + "\"}");
    }
    double detour_sum = 0, straight_sum = 0, drawn = 0;
    uint64_t detours = 0;
    for (const Bundle& b : bundles_.bundles)
      drawn += b.length_m;
    for (uint32_t c = 0; c < flows_.connections.size(); ++c) {
      const Connection& k = flows_.connections[c];
      const double straight = geodesic_distance_m(k.from.lon, k.from.lat, k.to.lon, k.to.lat);
      straight_sum += straight;
      std::string row = "{\"origin\":\"" + tileformat::json_escape(k.origin) +
                        "\",\"destination\":\"" + tileformat::json_escape(k.destination) +
                        "\",\"weight\":" + number(k.weight) + ",\"row\":" + std::to_string(k.row);
      if (reasons_[c] == Reason::kRouted) {
        double path_m = 0;
        for (uint32_t e : routes_[c])
          path_m += reduced_.edges[e].length_m;
        const auto& a = places_[ends_[c].first];
        const auto& b = places_[ends_[c].second];
        const LonLat na = nodes[size_t(place_node_[ends_[c].first])];
        const LonLat nb = nodes[size_t(place_node_[ends_[c].second])];
        path_m += geodesic_distance_m(a.lon, a.lat, na.lon, na.lat) +
                  geodesic_distance_m(b.lon, b.lat, nb.lon, nb.lat);
        if (straight > 0) {
          detour_sum += path_m / straight;
          ++detours;
        }
        row += ",\"length_m\":" + number(std::round(path_m)) + ",\"bundles\":[";
        for (size_t i = 0; i < bundles_.paths[c].size(); ++i)
          row += (i ? "," : "") + std::to_string(bundles_.paths[c][i] + 1);
        row += "]}";
      } else {
        if (line_of[c]) drawn += straight;
        row += ",\"unrouted\":\"" + std::string(reason_text(reasons_[c])) + "\"";
        row += line_of[c] ? ",\"line\":" + std::to_string(line_of[c]) + "}" : "}";
      }
      features.add(++id, "connections", row);
    }
    sum_.mean_detour = detours ? detour_sum / double(detours) : 0;
    sum_.ink_ratio = straight_sum > 0 ? drawn / straight_sum : 0;
    facts_.features = uint64_t(id);
    facts_.layers.clear();
    facts_.layer_features.clear();
    for (auto [name, count] : {std::pair<const char*, uint64_t>{"bundles", bundles_.bundles.size()},
                               {"unrouted", straight_.size()},
                               {"connections", flows_.connections.size()}}) {
      VectorLayerInfo info;
      info.name = name;
      info.source = std::string(name) == "bundles" ? s_.network[0] : s_.flows;
      facts_.layers.push_back(info);
      facts_.layer_features.push_back(count);
    }
  }

  std::string bundle_json() {
    const NetworkStats& n = graph_->stats();
    std::string classes = "[";
    for (size_t k = 0; k < class_bounds_.size(); ++k) {
      if (class_bounds_[k].second == 0) continue;
      classes += (classes.size() > 1 ? "," : "") + std::string("{\"class\":\"weight-") +
                 std::to_string(k + 1) + "\",\"min\":" + number(class_bounds_[k].first) +
                 ",\"max\":" + number(class_bounds_[k].second) + "}";
    }
    classes += "]";
    const uint64_t b = bundles_.bundles.size(), u = straight_.size();
    return "{\"connections\":" + std::to_string(flows_.connections.size()) +
           ",\"routed\":" + std::to_string(sum_.routed) +
           ",\"unrouted\":" + std::to_string(sum_.unrouted) +
           ",\"unsnapped\":" + std::to_string(sum_.unsnapped) +
           ",\"same_node\":" + std::to_string(sum_.same_node) +
           ",\"disconnected\":" + std::to_string(sum_.disconnected) +
           ",\"bad_rows\":" + std::to_string(flows_.bad_rows()) +
           ",\"bundles\":" + std::to_string(b) + ",\"straight_lines\":" + std::to_string(u) +
           ",\"ids\":{\"bundles\":[1," + std::to_string(b) + "],\"unrouted\":[" +
           std::to_string(b + 1) + "," + std::to_string(b + u) + "],\"connections\":[" +
           std::to_string(b + u + 1) + "," + std::to_string(b + u + flows_.connections.size()) +
           "]},\"mean_detour\":" + number(sum_.mean_detour) +
           ",\"ink_ratio\":" + number(sum_.ink_ratio) +
           ",\"corridor_px\":" + number(s_.corridor_px) +
           ",\"significance\":" + number(s_.significance) +
           ",\"min_weight\":" + number(s_.min_weight) +
           ",\"hidden_at_min_zoom\":" + std::to_string(sum_.hidden_at_min_zoom) +
           ",\"never_drawn\":" + std::to_string(sum_.never_drawn) +
           ",\"max_snap_m\":" + number(s_.max_snap_m) +
           ",\"network\":{\"nodes\":" + std::to_string(n.nodes) +
           ",\"edges\":" + std::to_string(n.edges) +
           ",\"components\":" + std::to_string(n.components) +
           ",\"reduced_nodes\":" + std::to_string(reduced_.graph_node.size()) +
           ",\"reduced_edges\":" + std::to_string(reduced_.edges.size()) +
           "},\"weight_classes\":" + classes + "}";
  }

  const BundleSettings& s_;
  Progress& progress_;
  const int threads_;
  VectorFrame frame_;
  std::unique_ptr<CoordTransform> to_target_;
  std::optional<NetworkGraph> graph_;
  FlowInput flows_;
  std::vector<LonLat> places_;
  std::vector<std::pair<uint32_t, uint32_t>> ends_;  // per connection: its places
  std::vector<int64_t> place_node_;                  // per place: graph node, -1 unsnapped
  std::vector<char> terminal_;
  ReducedGraph reduced_;
  std::vector<Reason> reasons_;
  std::vector<std::vector<uint32_t>> routes_;
  BundleSet bundles_;
  std::vector<std::vector<XY>> bundle_polys_;  // frame, unrolled
  std::vector<uint32_t> bundle_class_;
  std::vector<uint32_t> flow_zooms_;         // bundles, then straight lines: bit z drawn
  std::vector<std::pair<XY, XY>> tangents_;  // per bundle: start and end tangents
  std::vector<std::pair<double, double>> class_bounds_;  // weight range per class
  uint32_t unrouted_class_ = 0;
  std::vector<std::pair<uint32_t, std::vector<std::vector<XY>>>> straight_;  // connection, parts
  LineClasses classes_{"", {}};
  LineFacts facts_;
  LinePlan plan_;
  uint64_t scratch_features_ = 0;
  BundleSummary sum_;
  int64_t label_count_ = 0;
};

}  // namespace

BundleSummary build_bundles(const BundleSettings& settings, Progress& progress) {
  Builder b(settings, progress);
  BundleSummary sum = b.run();
  return sum;
}

}  // namespace globe
