// Opening area packages (see area_package.hpp).
#include "runtime/area_package.hpp"

#include "runtime/errors.hpp"
#include "runtime/package_open.hpp"

namespace globe {

AreaPackage open_area_package(const std::string& path) {
  AreaPackage p;
  p.reader = open_package_of_kind(path, tileformat::PackageKind::kAreas);
  p.meta =
      read_metadata(path, [&] { return tileformat::read_area_metadata(p.reader->metadata()); });
  p.classes =
      parse_classes_json(p.meta.classes_json, path + ": metadata globe:classes (tileformat §12.3)");
  return p;
}

std::vector<AreaLook> area_looks(const AreaPackage& p, double fill_opacity) {
  std::vector<AreaLook> out;
  const AreaLook outline{"", fill_opacity, "#444444", 0.5, true};
  if (const auto& c = p.meta.choropleth) {
    out.push_back(outline);
    out.back().fill = c->no_data_color;
    for (const tileformat::ChoroplethClass& k : c->classes) {
      out.push_back(outline);
      out.back().fill = k.color;
    }
    return out;
  }
  for (const NamedLineStyle& n : p.classes) {
    AreaLook l = outline;
    l.fill = n.style.color;
    l.opacity = fill_opacity * n.style.opacity;
    l.visible = n.style.visible;
    if (!n.style.casing_color.empty() && n.style.casing_width > 0) {
      l.outline = n.style.casing_color;
      l.outline_px = n.style.casing_width;
    }
    out.push_back(l);
  }
  return out;
}

}  // namespace globe
