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
  struct Shown {
    const LineStyle* style;
    std::string label;
  };
  std::vector<Shown> shown;
  for (auto it = rows.rbegin(); it != rows.rend(); ++it) {  // heaviest on top
    const auto s = std::find_if(styles.begin(), styles.end(),
                                [&](const NamedLineStyle& n) { return n.name == it->class_name; });
    if (s == styles.end() || !s->style.visible) continue;
    shown.push_back({&s->style, short_weight(it->min) + " - " + short_weight(it->max)});
  }
  if (shown.empty()) return;
  // Font pixels of 2 screen pixels on frames 600 px high or more, else 1.
  const int scale = height >= 600 ? 2 : 1;
  const float f = float(scale), pad = 4 * f, row = 10 * f, stroke = 18 * f;
  const std::string title = "flow weight";
  float text_w = TextOverlay::text_width(title, scale);
  for (const Shown& s : shown)
    text_w = std::max(text_w, stroke + pad + TextOverlay::text_width(s.label, scale));
  const float w = pad * 2 + text_w, h = pad * 2 + row * float(shown.size() + 1) - 3 * f;
  const float x = 10, y = float(height) - 10 - h;
  overlay.rect(x - 1, y - 1, w + 2, h + 2, {0.2f, 0.2f, 0.2f, 0.9f});
  overlay.rect(x, y, w, h, {1, 1, 1, 0.88f});
  overlay.text(x + pad, y + pad, title, {0.1f, 0.1f, 0.1f, 1}, scale);
  for (size_t i = 0; i < shown.size(); ++i) {
    const float ry = y + pad + row * float(i + 1);
    const LineStyle& s = *shown[i].style;
    // The stroke as drawn (widths in metres: a thin sample), capped to its row.
    const float lw = s.width_in_m ? 2.0f : std::clamp(float(s.width), 1.0f, row - 2);
    glm::vec4 c = hex_rgba(s.color);
    c.a = static_cast<float>(std::clamp(s.opacity, 0.0, 1.0));
    overlay.rect(x + pad, ry + 3.5f * f - lw / 2, stroke, lw, c);
    overlay.text(x + pad * 2 + stroke, ry, shown[i].label, {0.1f, 0.1f, 0.1f, 1}, scale);
  }
}

}  // namespace globe::viewer
