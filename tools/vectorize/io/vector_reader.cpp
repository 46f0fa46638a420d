// OGR feature reader (see vector_reader.hpp).
#include "io/vector_reader.hpp"

#include <cpl_conv.h>
#include <ogr_api.h>

#include <cmath>
#include <cstdio>

#include "runtime/errors.hpp"
#include "tileformat/json.hpp"

namespace globe {

struct VectorReader::LayerHandle {
  OGRLayerH layer = nullptr;
  int class_field = -1;
  std::vector<int> value_fields;  // OGR field index of each VectorReaderOptions::value_fields
  std::vector<int> text_fields;   // and of each text_fields
  std::vector<std::string> field_names;
  std::vector<OGRFieldType> field_types;
};

namespace {

std::string field_list(OGRFeatureDefnH defn) {
  std::string out;
  for (int i = 0; i < OGR_FD_GetFieldCount(defn); ++i)
    out += (i ? ", " : "") + std::string(OGR_Fld_GetNameRef(OGR_FD_GetFieldDefn(defn, i)));
  return out.empty() ? "(none)" : out;
}

void append_points(OGRGeometryH g, std::vector<XY>& out) {
  const int n = OGR_G_GetPointCount(g);
  for (int i = 0; i < n; ++i)
    out.push_back({OGR_G_GetX(g, i), OGR_G_GetY(g, i)});
}

// Flattens any geometry into line parts and points; with `polygons`, a
// polygon's rings stay together in f.polygons instead.
void flatten(OGRGeometryH g, VectorFeature& f, bool polygons) {
  if (!g || OGR_G_IsEmpty(g)) return;
  if (OGR_G_HasCurveGeometry(g, TRUE)) {
    OGRGeometryH lin = OGR_G_GetLinearGeometry(g, 0, nullptr);
    if (lin) {
      flatten(lin, f, polygons);
      OGR_G_DestroyGeometry(lin);
    }
    return;
  }
  const OGRwkbGeometryType type = wkbFlatten(OGR_G_GetGeometryType(g));
  if (polygons && (type == wkbPolygon || type == wkbTriangle)) {
    f.polygons.emplace_back();
    for (int i = 0; i < OGR_G_GetGeometryCount(g); ++i) {
      f.polygons.back().emplace_back();
      append_points(OGR_G_GetGeometryRef(g, i), f.polygons.back().back());
    }
    return;
  }
  switch (type) {
    case wkbPoint:
      f.points.push_back({OGR_G_GetX(g, 0), OGR_G_GetY(g, 0)});
      return;
    case wkbLineString:
    case wkbLinearRing:
      f.lines.emplace_back();
      append_points(g, f.lines.back());
      return;
    default:
      break;  // polygons (rings) and collections: recurse into parts
  }
  for (int i = 0; i < OGR_G_GetGeometryCount(g); ++i)
    flatten(OGR_G_GetGeometryRef(g, i), f, polygons);
}

std::string field_json(OGRFeatureH feat, int i, OGRFieldType type) {
  switch (type) {
    case OFTInteger:
      return std::to_string(OGR_F_GetFieldAsInteger(feat, i));
    case OFTInteger64:
      return std::to_string(OGR_F_GetFieldAsInteger64(feat, i));
    case OFTReal: {
      const double v = OGR_F_GetFieldAsDouble(feat, i);
      if (!std::isfinite(v)) return "null";
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.15g", v);
      return buf;
    }
    default:
      return "\"" + tileformat::json_escape(OGR_F_GetFieldAsString(feat, i)) + "\"";
  }
}

LayerGeometry layer_geometry(OGRLayerH layer) {
  switch (wkbFlatten(OGR_L_GetGeomType(layer))) {
    case wkbPoint:
    case wkbMultiPoint:
      return LayerGeometry::kPoints;
    case wkbLineString:
    case wkbMultiLineString:
    case wkbCircularString:
    case wkbCompoundCurve:
    case wkbMultiCurve:
      return LayerGeometry::kLines;
    case wkbPolygon:
    case wkbMultiPolygon:
    case wkbCurvePolygon:
    case wkbMultiSurface:
      return LayerGeometry::kPolygons;
    default:
      return LayerGeometry::kOther;
  }
}

}  // namespace

VectorReader::VectorReader(const std::vector<std::string>& inputs, const VectorReaderOptions& opt)
    : properties_(opt.properties), polygons_(opt.polygons) {
  gdal_init();
  std::vector<bool> layer_found(opt.layers.size(), false);
  std::string available;
  std::optional<SpatialRef> assigned;
  if (!opt.s_srs.empty()) assigned = SpatialRef::from_user_input(opt.s_srs, "--s_srs");
  // CSV coordinates are longitude/latitude unless --s_srs says otherwise.
  if (opt.xy && !assigned) assigned = SpatialRef::from_user_input("EPSG:4326", opt.xy_option);
  for (const std::string& path : inputs) {
    datasets_.push_back(
        opt.xy ? GdalDataset::open_csv_points(path, opt.xy->first, opt.xy->second, opt.xy_option)
               : GdalDataset::open_vector(path));
    GDALDatasetH ds = datasets_.back().get();
    for (int li = 0; li < GDALDatasetGetLayerCount(ds); ++li) {
      OGRLayerH layer = GDALDatasetGetLayer(ds, li);
      const std::string name = OGR_L_GetName(layer);
      available += (available.empty() ? "" : ", ") + name;
      if (!opt.layers.empty()) {
        bool wanted = false;
        for (size_t k = 0; k < opt.layers.size(); ++k)
          if (opt.layers[k] == name) wanted = layer_found[k] = true;
        if (!wanted) continue;
      }
      const std::string where = path + " layer '" + name + "'";
      // A table without geometry (QGIS keeps styles in one in most
      // GeoPackages): left out, unless asked for by name.
      if (!opt.xy && opt.crs == VectorReaderOptions::Crs::kNeeded &&
          OGR_L_GetGeomType(layer) == wkbNone) {
        if (!opt.layers.empty())
          throw InputError(where +
                           ": a table without geometry (no lines, points or polygons); "
                           "name a layer that has them");
        skipped_.push_back(where);
        continue;
      }
      VectorLayerInfo info;
      info.name = name;
      info.source = path;
      info.geometry = layer_geometry(layer);
      if (opt.xy && info.geometry != LayerGeometry::kPoints)
        throw InputError(
            where + ": no columns '" + opt.xy->first + "' and '" + opt.xy->second +
            "' to read points from (" + opt.xy_option +
            " LONCOL,LATCOL); its columns are: " + field_list(OGR_L_GetLayerDefn(layer)));
      if (assigned) {
        info.crs = assigned;
      } else if (OGRSpatialReferenceH srs = OGR_L_GetSpatialRef(layer)) {
        char* wkt = nullptr;
        const OGRErr err = OSRExportToWkt(srs, &wkt);
        const std::string text = err == OGRERR_NONE && wkt ? wkt : "";
        CPLFree(wkt);
        if (text.empty())
          throw InputError(where + ": its CRS cannot be written as WKT (" + gdal_last_error() +
                           "); pass --s_srs");
        info.crs = SpatialRef::from_wkt(text, where);
      } else if (opt.crs == VectorReaderOptions::Crs::kNeeded) {
        throw InputError(where +
                         ": no CRS (a shapefile without .prj?); pass --s_srs, e.g. --s_srs "
                         "EPSG:4326 for longitude/latitude");
      }
      OGRFeatureDefnH defn = OGR_L_GetLayerDefn(layer);
      auto h = std::make_unique<LayerHandle>();
      h->layer = layer;
      for (int i = 0; i < OGR_FD_GetFieldCount(defn); ++i) {
        OGRFieldDefnH fd = OGR_FD_GetFieldDefn(defn, i);
        h->field_names.push_back(OGR_Fld_GetNameRef(fd));
        info.fields.push_back(h->field_names.back());
        h->field_types.push_back(OGR_Fld_GetType(fd));
      }
      auto named = [&](const std::string& field) {
        auto it = opt.field_options.find(field);
        return (it == opt.field_options.end() ? std::string("field") : it->second) + " '" + field +
               "': " + where;
      };
      auto index = [&](const std::string& field) {
        const int fi = OGR_FD_GetFieldIndex(defn, field.c_str());
        if (fi < 0)
          throw UsageError(named(field) +
                           " has no such field; its fields are: " + field_list(defn));
        return fi;
      };
      for (const std::string& field : opt.value_fields) {
        const int fi = index(field);
        const OGRFieldType type = OGR_Fld_GetType(OGR_FD_GetFieldDefn(defn, fi));
        if (type != OFTInteger && type != OFTInteger64 && type != OFTReal)
          throw UsageError(named(field) + " holds " + OGR_GetFieldTypeName(type) +
                           " values there, not numbers; give numeric fields");
        h->value_fields.push_back(fi);
      }
      for (const std::string& field : opt.text_fields)
        h->text_fields.push_back(index(field));
      if (!opt.class_field.empty()) {
        h->class_field = OGR_FD_GetFieldIndex(defn, opt.class_field.c_str());
        if (h->class_field < 0)
          throw UsageError("--class-field '" + opt.class_field + "': " + where +
                           " has no such field; its fields are: " + field_list(defn));
      }
      CPLErrorReset();
      if (OGR_L_SetAttributeFilter(layer, opt.where.empty() ? nullptr : opt.where.c_str()) !=
          OGRERR_NONE)
        throw UsageError("--where '" + opt.where + "' does not apply to " + where + " (" +
                         gdal_last_error() + "); its fields are: " + field_list(defn));
      if (opt.filter) {
        CoordTransform to_layer(SpatialRef::from_user_input("EPSG:4326", "--bbox"), *info.crs);
        tileformat::Bounds b;
        if (to_layer.transform_bounds(*opt.filter, b))
          OGR_L_SetSpatialFilterRect(layer, b.min_x, b.min_y, b.max_x, b.max_y);
      }
      OGR_L_ResetReading(layer);
      info.feature_count = OGR_L_GetFeatureCount(layer, FALSE);
      layers_.push_back(std::move(info));
      handles_.push_back(std::move(h));
    }
  }
  for (size_t k = 0; k < opt.layers.size(); ++k)
    if (!layer_found[k])
      throw UsageError("--layer '" + opt.layers[k] +
                       "': no such layer; the inputs have: " + available);
  if (layers_.empty())
    throw InputError(inputs.front() + (inputs.size() > 1 ? " (and the other inputs)" : "") +
                     ": no layer with geometry; the inputs have: " + available);
}

VectorReader::~VectorReader() = default;

bool VectorReader::next(VectorFeature& out) {
  while (current_ < handles_.size()) {
    LayerHandle& h = *handles_[current_];
    OGRFeatureH feat = OGR_L_GetNextFeature(h.layer);
    if (!feat) {
      ++current_;
      continue;
    }
    out.layer = static_cast<int>(current_);
    out.fid = OGR_F_GetFID(feat);
    out.lines.clear();
    out.points.clear();
    out.polygons.clear();
    out.values.clear();
    for (int fi : h.value_fields)
      out.values.push_back(OGR_F_IsFieldSetAndNotNull(feat, fi) ? OGR_F_GetFieldAsDouble(feat, fi)
                                                                : std::nan(""));
    out.texts.clear();
    for (int fi : h.text_fields)
      out.texts.push_back(OGR_F_IsFieldSetAndNotNull(feat, fi) ? OGR_F_GetFieldAsString(feat, fi)
                                                               : "");
    out.properties_json = properties_ ? "{" : "";
    bool first = true;
    for (size_t i = 0; properties_ && i < h.field_names.size(); ++i) {
      const int fi = static_cast<int>(i);
      if (!OGR_F_IsFieldSetAndNotNull(feat, fi)) continue;
      out.properties_json += (first ? "\"" : ",\"") + tileformat::json_escape(h.field_names[i]) +
                             "\":" + field_json(feat, fi, h.field_types[i]);
      first = false;
    }
    if (properties_) out.properties_json += "}";
    out.class_value = h.class_field >= 0 && OGR_F_IsFieldSetAndNotNull(feat, h.class_field)
                          ? OGR_F_GetFieldAsString(feat, h.class_field)
                          : "";
    flatten(OGR_F_GetGeometryRef(feat), out, polygons_);
    OGR_F_Destroy(feat);
    return true;
  }
  return false;
}

}  // namespace globe
