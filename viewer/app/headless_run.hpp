// The headless session: --snapshot, --stats, --export-mesh (and --camera-path)
// on an OSMesa or EGL context, then exit.
#pragma once

#include "app/viewer_settings.hpp"

namespace globe::viewer {

int run_headless(const ViewerSettings& settings);

}  // namespace globe::viewer
