// Mapbox Vector Tile encoding (see mvt_encoder.hpp).
#include "web/mvt_encoder.hpp"

#include <cmath>
#include <cstring>
#include <tuple>

#include "tileformat/json.hpp"

namespace globe::web {
namespace {

// Protobuf wire format: varints, field keys, length-delimited fields.
void varint(std::string& out, uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<char>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<char>(v));
}
void key(std::string& out, int field, int wire) {
  varint(out, uint64_t(field) << 3 | uint64_t(wire));
}
void bytes_field(std::string& out, int field, const std::string& bytes) {
  key(out, field, 2);
  varint(out, bytes.size());
  out += bytes;
}
void varint_field(std::string& out, int field, uint64_t v) {
  key(out, field, 0);
  varint(out, v);
}
uint32_t zigzag(int32_t v) {
  return (static_cast<uint32_t>(v) << 1) ^ static_cast<uint32_t>(v >> 31);
}
uint64_t zigzag64(int64_t v) {
  return (static_cast<uint64_t>(v) << 1) ^ static_cast<uint64_t>(v >> 63);
}
// Geometry commands (spec 4.3): id in the low 3 bits, count above.
constexpr uint32_t kMoveTo = 1, kLineTo = 2, kClosePath = 7;
uint32_t command(uint32_t id, uint32_t count) {
  return (id & 7) | (count << 3);
}
constexpr int kPoint = 1, kLineString = 2, kPolygon = 3;

}  // namespace

bool MvtValue::operator<(const MvtValue& o) const {
  return std::tie(kind, text, number, integer, flag) <
         std::tie(o.kind, o.text, o.number, o.integer, o.flag);
}

uint32_t MvtLayer::tag_key(const std::string& k) {
  auto [it, fresh] = key_index_.try_emplace(k, static_cast<uint32_t>(keys_.size()));
  if (fresh) keys_.push_back(k);
  return it->second;
}

uint32_t MvtLayer::tag_value(const MvtValue& v) {
  auto [it, fresh] = value_index_.try_emplace(v, static_cast<uint32_t>(values_.size()));
  if (fresh) values_.push_back(v);
  return it->second;
}

MvtValue MvtValue::from_json(const tileformat::JsonValue& v) {
  MvtValue m;
  if (v.is_number()) {
    const double d = v.number();
    if (d == std::floor(d) && std::fabs(d) < 9e15) {
      m.kind = MvtValue::Kind::kInt;
      m.integer = static_cast<int64_t>(d);
    } else {
      m.kind = MvtValue::Kind::kDouble;
      m.number = d;
    }
  } else if (v.is_bool()) {
    m.kind = MvtValue::Kind::kBool;
    m.flag = v.boolean();
  } else if (v.is_string()) {
    m.text = v.string();
  } else {
    m.text = v.text();  // arrays and objects as JSON text
  }
  return m;
}

void MvtLayer::add(uint64_t id, int type, std::vector<uint32_t> geometry,
                   const std::vector<std::pair<std::string, MvtValue>>& tags) {
  std::string f, packed;
  varint_field(f, 1, id);
  for (const auto& [k, v] : tags) {
    varint(packed, tag_key(k));
    varint(packed, tag_value(v));
  }
  if (!packed.empty()) bytes_field(f, 2, packed);
  varint_field(f, 3, uint64_t(type));
  packed.clear();
  for (uint32_t g : geometry)
    varint(packed, g);
  bytes_field(f, 4, packed);
  features_.push_back(std::move(f));
}

bool MvtLayer::add_line(uint64_t id, std::span<const MvtPoint> line,
                        const std::vector<std::pair<std::string, MvtValue>>& tags) {
  std::vector<MvtPoint> pts;
  for (const MvtPoint& p : line)
    if (pts.empty() || !(pts.back() == p)) pts.push_back(p);
  if (pts.size() < 2) {
    auto flagged = tags;
    MvtValue yes;
    yes.kind = MvtValue::Kind::kBool;
    yes.flag = true;
    flagged.emplace_back("zero_length", yes);
    if (!pts.empty()) add_point(id, pts[0], flagged);
    return false;
  }
  std::vector<uint32_t> g{command(kMoveTo, 1), zigzag(pts[0].x), zigzag(pts[0].y),
                          command(kLineTo, static_cast<uint32_t>(pts.size() - 1))};
  for (size_t i = 1; i < pts.size(); ++i) {
    g.push_back(zigzag(pts[i].x - pts[i - 1].x));
    g.push_back(zigzag(pts[i].y - pts[i - 1].y));
  }
  add(id, kLineString, std::move(g), tags);
  return true;
}

void MvtLayer::add_point(uint64_t id, MvtPoint at,
                         const std::vector<std::pair<std::string, MvtValue>>& tags) {
  add(id, kPoint, {command(kMoveTo, 1), zigzag(at.x), zigzag(at.y)}, tags);
}

void MvtLayer::add_polygon(uint64_t id, const std::vector<std::vector<MvtPoint>>& rings,
                           const std::vector<std::pair<std::string, MvtValue>>& tags) {
  std::vector<uint32_t> g;
  MvtPoint cursor;
  for (const std::vector<MvtPoint>& r : rings) {
    if (r.size() < 3) continue;
    g.push_back(command(kMoveTo, 1));
    g.push_back(zigzag(r[0].x - cursor.x));
    g.push_back(zigzag(r[0].y - cursor.y));
    g.push_back(command(kLineTo, static_cast<uint32_t>(r.size() - 1)));
    for (size_t i = 1; i < r.size(); ++i) {
      g.push_back(zigzag(r[i].x - r[i - 1].x));
      g.push_back(zigzag(r[i].y - r[i - 1].y));
    }
    g.push_back(command(kClosePath, 1));
    cursor = r.back();
  }
  if (!g.empty()) add(id, kPolygon, std::move(g), tags);
}

std::string MvtLayer::encode() const {
  std::string out;
  varint_field(out, 15, 2);  // version
  bytes_field(out, 1, name_);
  for (const std::string& f : features_)
    bytes_field(out, 2, f);
  for (const std::string& k : keys_)
    bytes_field(out, 3, k);
  for (const MvtValue& v : values_) {
    std::string m;
    switch (v.kind) {
      case MvtValue::Kind::kString:
        bytes_field(m, 1, v.text);
        break;
      case MvtValue::Kind::kDouble: {
        key(m, 3, 1);
        uint64_t bits;
        std::memcpy(&bits, &v.number, 8);
        for (int i = 0; i < 8; ++i)
          m.push_back(static_cast<char>(bits >> (8 * i)));
        break;
      }
      case MvtValue::Kind::kInt:
        varint_field(m, 6, zigzag64(v.integer));
        break;
      case MvtValue::Kind::kBool:
        varint_field(m, 7, v.flag ? 1 : 0);
        break;
    }
    bytes_field(out, 4, m);
  }
  varint_field(out, 5, extent_);
  return out;
}

std::vector<uint8_t> encode_mvt(const std::vector<MvtLayer>& layers) {
  std::string tile;
  for (const MvtLayer& l : layers)
    if (!l.empty()) bytes_field(tile, 3, l.encode());
  return std::vector<uint8_t>(tile.begin(), tile.end());
}

std::string vector_layers_json(
    const std::map<std::string, std::map<std::string, std::string>>& layers) {
  std::string out = "[";
  bool first_layer = true;
  for (const auto& [id, fields] : layers) {
    out += (first_layer ? "" : ",") + std::string("{\"id\":\"") + tileformat::json_escape(id) +
           "\",\"fields\":{";
    first_layer = false;
    bool first = true;
    for (const auto& [k, type] : fields) {
      out += (first ? "\"" : ",\"") + tileformat::json_escape(k) + "\":\"" + type + "\"";
      first = false;
    }
    out += "}}";
  }
  return out + "]";
}

}  // namespace globe::web
