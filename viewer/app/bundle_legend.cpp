// The legend of a bundled-flows package (see bundle_legend.hpp).
#include "app/bundle_legend.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/color.hpp"
#include "tileformat/json.hpp"

namespace globe::viewer {

std::vector<LegendRow> bundle_legend_rows(const std::string& bundle_json) {
  std::vector<LegendRow> rows;
  try {
    const tileformat::JsonValue root = tileformat::JsonValue::parse(bundle_json);
    const tileformat::JsonValue* classes = root.find("weight_classes");
    if (!classes || !classes->is_array()) return rows;
    for (const tileformat::JsonValue& c : classes->array()) {
      const tileformat::JsonValue *name = c.find("class"), *lo = c.find("min"), *hi = c.find("max");
      if (name && name->is_string() && lo && lo->is_number() && hi && hi->is_number())
        rows.push_back({name->string(), lo->number(), hi->number()});
    }
  } catch (const tileformat::JsonError&) {
    rows.clear();  // a package without a readable legend draws none
  }
  return rows;
}

std::string short_weight(double w) {
  char buf[32];
  const double a = std::fabs(w);
  if (a >= 1e9)
    std::snprintf(buf, sizeof buf, "%.3gG", w / 1e9);
  else if (a >= 1e6)
    std::snprintf(buf, sizeof buf, "%.3gM", w / 1e6);
  else if (a >= 1e4)
    std::snprintf(buf, sizeof buf, "%.3gk", w / 1e3);
  else
    std::snprintf(buf, sizeof buf, "%.4g", w);
  return buf;
}

void queue_bundle_legend(const std::vector<LegendRow>& rows,
                         const std::vector<NamedLineStyle>& styles, int height,
                         TextOverlay& overlay) {
  std::vector<LegendEntry> entries;
  for (auto it = rows.rbegin(); it != rows.rend(); ++it) {  // heaviest on top
    const auto n = std::find_if(styles.begin(), styles.end(),
                                [&](const NamedLineStyle& c) { return c.name == it->class_name; });
    if (n == styles.end() || !n->style.visible) continue;
    const LineStyle& s = n->style;
    glm::vec4 c = hex_rgba(s.color);
    c.a = static_cast<float>(std::clamp(s.opacity, 0.0, 1.0));
    // The stroke as drawn (widths in metres: a thin sample), capped to its row.
    entries.push_back({c, s.width_in_m ? 2.0f : std::max(float(s.width), 1.0f),
                       short_weight(it->min) + " - " + short_weight(it->max)});
  }
  queue_legend_box("flow weight", entries, 18, height, overlay);
}

void queue_legend_box(const std::string& title, const std::vector<LegendEntry>& entries,
                      float mark_units, int height, TextOverlay& overlay) {
  if (entries.empty()) return;
  // Font pixels of 2 screen pixels on frames 600 px high or more, else 1.
  const int scale = height >= 600 ? 2 : 1;
  const float f = float(scale), pad = 4 * f, row = 10 * f, mark = mark_units * f;
  float text_w = overlay.text_width(title, scale);
  for (const LegendEntry& e : entries)
    text_w = std::max(text_w, mark + pad + overlay.text_width(e.label, scale));
  const float w = pad * 2 + text_w, h = pad * 2 + row * float(entries.size() + 1) - 3 * f;
  const float x = 10, y = float(height) - 10 - h;
  overlay.rect(x - 1, y - 1, w + 2, h + 2, {0.2f, 0.2f, 0.2f, 0.9f});
  overlay.rect(x, y, w, h, {1, 1, 1, 0.88f});
  overlay.text(x + pad, y + pad, title, {0.1f, 0.1f, 0.1f, 1}, scale);
  for (size_t i = 0; i < entries.size(); ++i) {
    const float ry = y + pad + row * float(i + 1);
    const LegendEntry& e = entries[i];
    if (e.line_px > 0) {
      const float lw = std::min(e.line_px, row - 2);
      overlay.rect(x + pad, ry + 3.5f * f - lw / 2, mark, lw, e.color);
    } else {
      overlay.rect(x + pad, ry, mark, 7 * f, e.color);
    }
    overlay.text(x + pad * 2 + mark, ry, e.label, {0.1f, 0.1f, 0.1f, 1}, scale);
  }
}

}  // namespace globe::viewer
