// The frame loop of a layer whose pass reads vector tiles per pixel (lines,
// areas): upload what the loader finished, draw, hand the GPU's feedback to
// the cache (tiles used, tiles wanted), and with Loading::kSettle go round
// again until no visible tile is missing (headless snapshots).
#pragma once

#include <cstddef>
#include <functional>

#include "app/scene_layer.hpp"
#include "render/vector_pixel_glsl.hpp"

namespace globe::viewer {

// `upload()` places the loaded tiles and returns how many; `draw(feedback)`
// draws once and returns its GPU ms. Returns the last draw's ms.
template <class Cache>
double draw_settled(Cache& cache, Loading loading, const std::function<size_t()>& upload,
                    const std::function<double(VectorFeedback&)>& draw,
                    const std::function<void(const VectorFeedback&)>& seen = {}) {
  double ms = 0;
  int idle_rounds = 0;
  for (int round = 0;; ++round) {
    cache.begin_frame();
    const size_t loaded = upload();
    VectorFeedback fb;
    ms = draw(fb);
    if (seen) seen(fb);
    for (uint32_t r : fb.used)
      cache.mark_used(r);
    bool news = false;
    for (const tileformat::TileId& id : fb.requests)
      news = cache.request(id) || news;
    cache.flush_requests();
    if (loading == Loading::kAsReady || (!news && !cache.loader_busy())) break;
    // Tiles that cannot get room in the budget are asked for again and again.
    idle_rounds = loaded == 0 ? idle_rounds + 1 : 0;
    if (idle_rounds > 3 || round > 200) break;
    if (cache.loader_busy()) cache.wait_for_loader();
  }
  return ms;
}

}  // namespace globe::viewer
