// The interactive session: a GLFW window, an orbit camera driven by mouse and
// keys, frames that never wait for I/O, statistics in the title bar.
#pragma once

#include "app/viewer_settings.hpp"

namespace globe::viewer {

int run_window(const ViewerSettings& settings);

}  // namespace globe::viewer
