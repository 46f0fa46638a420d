// globe-view: renders terrain packages (files or URLs) in a window or headless.
// The only place that turns errors into messages and exit codes (docs/cli.md).
#include <string>
#include <vector>

#include "app/headless_run.hpp"
#include "app/viewer_settings.hpp"
#include "app/window_run.hpp"
#include "data/network.hpp"
#include "runtime/error_report.hpp"
#include "runtime/errors.hpp"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  return globe::run_reporting_errors("globe-view", "globe-view", "", [&]() -> int {
    auto settings = globe::viewer::parse_viewer_settings(args);
    if (!settings) return globe::kExitOk;
    globe::viewer::Network network(settings->network);  // packages may be URLs
    if (settings->headless()) return globe::viewer::run_headless(*settings);
    return globe::viewer::run_window(*settings);
  });
}
