// The lines of one view (see line_layer.hpp).
#include "app/line_layer.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "errors.hpp"

namespace globe::viewer {

LineLayer::LineLayer(const std::string& path, LinePackage package,
                     std::optional<std::string> style_path, LineMode mode, uint64_t budget_bytes,
                     int width, int height)
    : path_(path),
      style_path_(std::move(style_path)),
      package_styles_(package.classes),
      mode_(mode),
      cache_(path, std::move(package), budget_bytes),
      renderer_(cache_.arena_words(), width, height) {
  renderer_.set_styles(read_styles());
  if (style_path_) {
    std::error_code ec;
    style_time_ = std::filesystem::last_write_time(*style_path_, ec);
  }
}

std::vector<NamedLineStyle> LineLayer::read_styles() const {
  std::vector<NamedLineStyle> styles = package_styles_;
  if (!style_path_) return styles;
  std::ifstream in(*style_path_);
  if (!in) throw InputError(*style_path_ + ": cannot read the style file");
  std::stringstream text;
  text << in.rdbuf();
  apply_style_json(text.str(), *style_path_, styles);
  return styles;
}

void LineLayer::reload_style(Reload when) {
  if (!style_path_) return;
  std::error_code ec;
  const auto t = std::filesystem::last_write_time(*style_path_, ec);
  if (when == Reload::kIfChanged && (ec || t == style_time_)) return;
  style_time_ = t;
  try {
    renderer_.set_styles(read_styles());
    std::fprintf(stderr, "globe-view: styles reloaded from %s\n", style_path_->c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "globe-view: %s; keeping the previous styles\n", e.what());
  }
}

size_t LineLayer::upload_loaded() {
  const std::vector<uint32_t> loaded = cache_.take_loaded();
  for (uint32_t r : loaded) {
    renderer_.upload(cache_.records()[r]);
    cache_.drop_words(r);
  }
  return loaded.size();
}

double LineLayer::draw(const GBuffer& g, const View& view, const WorldFrame& world,
                       double exaggeration, const TerrainHeights& terrain, Loading loading) {
  double ms = 0;
  int idle_rounds = 0;
  for (int round = 0;; ++round) {
    cache_.begin_frame();
    const size_t loaded = upload_loaded();
    LineFeedback fb;
    ms = renderer_.draw(g, view, world, exaggeration, cache_, terrain, mode_, ++frame_, fb);
    tiles_used_ = fb.used.size();
    for (uint32_t r : fb.used)
      cache_.mark_used(r);
    bool news = false;
    for (const tileformat::TileId& id : fb.requests)
      news = cache_.request(id) || news;
    cache_.flush_requests();
    if (loading == Loading::kAsReady || (!news && !cache_.loader_busy())) break;
    // Tiles that cannot get room in the budget are asked for again and again.
    idle_rounds = loaded == 0 ? idle_rounds + 1 : 0;
    if (idle_rounds > 3 || round > 200) break;
    if (cache_.loader_busy()) cache_.wait_for_loader();
  }
  return ms;
}

}  // namespace globe::viewer
