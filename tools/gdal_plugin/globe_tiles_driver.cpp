// GDAL plugin driver "GlobeTiles" (docs/gdal.md): lets gdalinfo,
// gdal_translate, gdalwarp and QGIS read a terrain package as the DEM it is —
// one Float32 band in the tiling CRS at the finest zoom, the coarser zooms as
// overviews — and makes them decline the package kinds that are no raster
// (lines, bundles, points, analysis, imagery in a non-web-mercator tiling)
// with a message naming the command that extracts them. Loaded before GDAL's
// own drivers (GDAL_DRIVER_PATH or GDAL's plugin folder), so the MBTiles
// driver no longer decodes MBlocks as broken PNGs.
#include <gdal_pam.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <list>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tileformat/error.hpp"
#include "tileformat/mblock.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace {

constexpr float kNoData = -99999.0f;
constexpr int kBlock = 256;  // GDAL block side, every level

// The package a dataset reads, with its decoded blocks (a few, recent first).
struct Package {
  std::unique_ptr<tileformat::PackageReader> reader;
  tileformat::TerrainMetadata meta;
  int steps = 0;  // block samples per tile side, minus one
  std::list<std::pair<tileformat::TileId, std::optional<tileformat::MBlock>>> recent;

  const tileformat::MBlock* block(tileformat::TileId id) {
    for (auto it = recent.begin(); it != recent.end(); ++it)
      if (it->first == id) {
        recent.splice(recent.begin(), recent, it);
        return recent.front().second ? &*recent.front().second : nullptr;
      }
    std::optional<tileformat::MBlock> b;
    if (const auto blob = reader->tile(id)) {
      try {
        b = tileformat::decode_mblock(*blob);
        if (b->steps() != steps) b.reset();
      } catch (const tileformat::FormatError& e) {
        CPLError(CE_Warning, CPLE_AppDefined, "tile %s: %s; left as no data", id.str().c_str(),
                 e.what());
      }
    }
    if (recent.size() >= 32) recent.pop_back();
    recent.emplace_front(id, std::move(b));
    return recent.front().second ? &*recent.front().second : nullptr;
  }
};

// One level: zoom `zoom`, sample (0, 0) = global sample (gx0, gy0) of that zoom.
struct Level {
  int zoom = 0;
  int64_t gx0 = 0, gy0 = 0;
  int width = 0, height = 0;
};

class GlobeTilesBand;

class GlobeTilesDataset final : public GDALPamDataset {
 public:
  static int Identify(GDALOpenInfo* info);
  static GDALDataset* Open(GDALOpenInfo* info);

  CPLErr GetGeoTransform(double* gt) override {
    std::copy(gt_, gt_ + 6, gt);
    return CE_None;
  }
  const OGRSpatialReference* GetSpatialRef() const override { return &srs_; }

 private:
  friend class GlobeTilesBand;
  std::shared_ptr<Package> package_;
  double gt_[6] = {0, 1, 0, 0, 0, 1};
  OGRSpatialReference srs_;
};

class GlobeTilesBand final : public GDALPamRasterBand {
 public:
  GlobeTilesBand(GDALDataset* ds, std::shared_ptr<Package> package, Level level, bool overview)
      : package_(std::move(package)), level_(level) {
    poDS = overview ? nullptr : ds;
    nBand = 1;
    eDataType = GDT_Float32;
    nBlockXSize = kBlock;
    nBlockYSize = kBlock;
    nRasterXSize = level.width;
    nRasterYSize = level.height;
    eAccess = GA_ReadOnly;
  }
  void add_overview(std::unique_ptr<GlobeTilesBand> o) { overviews_.push_back(std::move(o)); }

  CPLErr IReadBlock(int bx, int by, void* out) override {
    float* px = static_cast<float*>(out);
    const int steps = package_->steps;
    for (int j = 0; j < kBlock; ++j)
      for (int i = 0; i < kBlock; ++i) {
        const int x = bx * kBlock + i, y = by * kBlock + j;
        px[size_t(j) * kBlock + i] = x < nRasterXSize && y < nRasterYSize
                                         ? sample(level_.gx0 + x, level_.gy0 + y, steps)
                                         : kNoData;
      }
    return CE_None;
  }
  double GetNoDataValue(int* ok) override {
    if (ok) *ok = TRUE;
    return kNoData;
  }
  const char* GetUnitType() override { return "m"; }
  int GetOverviewCount() override { return int(overviews_.size()); }
  GDALRasterBand* GetOverview(int i) override {
    return i >= 0 && i < int(overviews_.size()) ? overviews_[i].get() : nullptr;
  }

 private:
  // Global sample (gx, gy) of the level's zoom: from the tile holding it, or
  // on a tile edge from the neighbour west or north (edges are shared).
  float sample(int64_t gx, int64_t gy, int steps) {
    const int64_t tx = gx / steps, ty = gy / steps;
    const int sx = int(gx % steps), sy = int(gy % steps);
    for (int dy = 0; dy <= (sy == 0 && ty > 0); ++dy)
      for (int dx = 0; dx <= (sx == 0 && tx > 0); ++dx) {
        const tileformat::TileId id{level_.zoom, uint32_t(tx - dx), uint32_t(ty - dy)};
        const tileformat::MBlock* b = package_->block(id);
        if (!b) continue;
        const int x = dx ? steps : sx, y = dy ? steps : sy;
        if (!b->is_valid(x, y)) return kNoData;
        return static_cast<float>(b->height(x, y));
      }
    return kNoData;
  }

  std::shared_ptr<Package> package_;
  Level level_;
  std::vector<std::unique_ptr<GlobeTilesBand>> overviews_;
};

int GlobeTilesDataset::Identify(GDALOpenInfo* info) {
  return info->nHeaderBytes >= 16 && info->pabyHeader &&
         std::memcmp(info->pabyHeader, "SQLite format 3", 16) == 0 &&
         EQUAL(CPLGetExtension(info->pszFilename), "mbtiles");
}

GDALDataset* GlobeTilesDataset::Open(GDALOpenInfo* info) {
  if (!Identify(info) || info->eAccess == GA_Update) return nullptr;
  std::unique_ptr<tileformat::PackageReader> reader;
  std::optional<tileformat::PackageKind> kind;
  try {
    reader = std::make_unique<tileformat::PackageReader>(info->pszFilename);
    const auto format = reader->meta("format");
    if (!format) return nullptr;  // no package of ours: GDAL's MBTiles driver may know it
    kind = tileformat::package_kind_of_format(*format);
    const auto scheme = reader->meta("globe:scheme");
    if (!kind || (*kind == tileformat::PackageKind::kImage && scheme == "webmercator") ||
        (*kind == tileformat::PackageKind::kImage && !scheme))
      return nullptr;  // a web-mercator image package is plain MBTiles
  } catch (const std::exception&) {
    return nullptr;
  }
  if (*kind != tileformat::PackageKind::kTerrain) {
    CPLError(CE_Failure, CPLE_OpenFailed,
             "%s: a GlobeEngine %s package%s, not a raster GDAL can read; to get %s",
             info->pszFilename, tileformat::package_kind_name(*kind),
             *kind == tileformat::PackageKind::kImage ? " in a tiling other than web mercator" : "",
             tileformat::describe(*kind).extract);
    return nullptr;
  }
  auto package = std::make_shared<Package>();
  try {
    package->meta = tileformat::read_terrain_metadata(reader->metadata());
    package->steps = package->meta.block_size - 1;
    std::vector<tileformat::ZoomSummary> zooms = reader->zoom_summaries();
    package->reader = std::move(reader);
    if (zooms.empty()) {
      CPLError(CE_Failure, CPLE_OpenFailed, "%s: a terrain package without tiles",
               info->pszFilename);
      return nullptr;
    }
    const tileformat::ZoomSummary& finest = zooms.back();
    const tileformat::Tiling& t = package->meta.common.tiling;
    const int steps = package->steps;
    auto ds = std::make_unique<GlobeTilesDataset>();
    ds->package_ = package;
    const Level top{finest.zoom, int64_t(finest.min_x) * steps, int64_t(finest.min_y) * steps,
                    int((finest.max_x - finest.min_x + 1) * steps + 1),
                    int((finest.max_y - finest.min_y + 1) * steps + 1)};
    const double d = t.sample_spacing(finest.zoom, steps);
    ds->gt_[0] = t.origin_x + finest.min_x * t.tile_size(finest.zoom) - d / 2;
    ds->gt_[1] = d;
    ds->gt_[3] = t.origin_y - finest.min_y * t.tile_size(finest.zoom) + d / 2;
    ds->gt_[5] = -d;
    ds->srs_.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (ds->srs_.SetFromUserInput(t.crs.c_str()) != OGRERR_NONE)
      CPLError(CE_Warning, CPLE_AppDefined, "%s: globe:crs is not a CRS GDAL reads",
               info->pszFilename);
    ds->nRasterXSize = top.width;
    ds->nRasterYSize = top.height;
    auto band = std::make_unique<GlobeTilesBand>(ds.get(), package, top, false);
    // Coarser zooms as overviews of the same extent: every 2^k-th sample of
    // the finest zoom is a sample of zoom - k (tile grids nest).
    for (int k = 1; finest.zoom - k >= package->meta.common.min_zoom && (1 << k) <= steps; ++k) {
      const Level o{finest.zoom - k, top.gx0 >> k, top.gy0 >> k, (top.width - 1) / (1 << k) + 1,
                    (top.height - 1) / (1 << k) + 1};
      band->add_overview(std::make_unique<GlobeTilesBand>(ds.get(), package, o, true));
      if (o.width < 256 && o.height < 256) break;
    }
    ds->SetBand(1, band.release());
    ds->SetMetadataItem("AREA_OR_POINT", "Point");
    for (const auto& [k, v] : package->reader->metadata())
      if (k != "globe:crs") ds->SetMetadataItem(k.c_str(), v.c_str());
    ds->SetDescription(info->pszFilename);
    ds->TryLoadXML();
    return ds.release();
  } catch (const std::exception& e) {
    CPLError(CE_Failure, CPLE_OpenFailed, "%s: %s", info->pszFilename, e.what());
    return nullptr;
  }
}

}  // namespace

extern "C" void GDALRegister_GlobeTiles() {
  if (!GDAL_CHECK_VERSION("GlobeTiles")) return;
  if (GDALGetDriverByName("GlobeTiles") != nullptr) return;
  auto* driver = new GDALDriver();
  driver->SetDescription("GlobeTiles");
  driver->SetMetadataItem(GDAL_DCAP_RASTER, "YES");
  driver->SetMetadataItem(GDAL_DMD_LONGNAME, "GlobeEngine terrain package (MBlock/KPatch)");
  driver->SetMetadataItem(GDAL_DMD_EXTENSION, "mbtiles");
  driver->SetMetadataItem(GDAL_DCAP_VIRTUALIO, "NO");
  driver->pfnIdentify = GlobeTilesDataset::Identify;
  driver->pfnOpen = GlobeTilesDataset::Open;
  GetGDALDriverManager()->RegisterDriver(driver);
}
