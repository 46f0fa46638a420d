// globe-view: renders terrain packages in a window or headless.
// The only place that turns errors into messages and exit codes (docs/cli.md).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/headless_run.hpp"
#include "app/viewer_settings.hpp"
#include "app/window_run.hpp"
#include "errors.hpp"
#include "tileformat/error.hpp"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  auto report = [](const std::exception& e, int code) {
    std::fprintf(stderr, "globe-view: %s\n", e.what());
    return code;
  };
  try {
    auto settings = globe::viewer::parse_viewer_settings(args);
    if (!settings) return globe::kExitOk;
    if (settings->headless()) return globe::viewer::run_headless(*settings);
    return globe::viewer::run_window(*settings);
  } catch (const globe::UsageError& e) {
    std::fprintf(stderr, "globe-view: %s (see globe-view --help)\n", e.what());
    return globe::kExitUsage;
  } catch (const globe::OutputError& e) {
    return report(e, globe::kExitOutputError);
  } catch (const globe::InputError& e) {
    return report(e, globe::kExitDataError);
  } catch (const tileformat::FormatError& e) {
    return report(e, globe::kExitDataError);
  } catch (const tileformat::PackageError& e) {
    return report(e, globe::kExitDataError);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "globe-view: internal error: %s\n", e.what());
    return globe::kExitInternal;
  }
}
