// globe-serve: packages over HTTP for CesiumJS, MapLibre GL and any tile
// client (docs/serve.md). Parses the command line, opens the packages, serves
// until SIGINT or SIGTERM. stdout: the server's URL once it listens; stderr:
// one line per request (unless -q) and errors.
#include <pthread.h>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "kit/heap_tuning.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/error_report.hpp"
#include "runtime/errors.hpp"
#include "serve/http_server.hpp"
#include "serve/package_registry.hpp"
#include "serve/request_handler.hpp"
#include "web/glyphs.hpp"

namespace {

std::string default_web_libs() {
  const char* cache = std::getenv("GLOBE_WEB_CACHE");
  const char* home = std::getenv("HOME");
  const std::string dir =
      cache ? std::string(cache) : std::string(home ? home : "") + "/.cache/globe-web";
  return dir + "/node_modules";
}

int serve(const std::vector<std::string>& args) {
  using namespace globe;
  serve::HttpServerOptions http;
  serve::HandlerOptions handler;
  serve::ServiceOptions services;
  handler.lib_dir = default_web_libs();
  http.threads = int(std::max(4u, 2 * std::thread::hardware_concurrency()));
  CliArgs cli("globe-serve",
              "globe-serve PACKAGE... [--bind ADDR] [--port N] [-j N]\n\n"
              "Serves packages over HTTP, each under its file stem NAME (docs/serve.md):\n"
              "  terrain   /NAME/layer.json and /NAME/{z}/{x}/{y}.terrain (quantized-mesh for\n"
              "            CesiumJS, cut on the fly; rows from the south), and\n"
              "            /NAME/{z}/{x}/{y}.png?encoding=terrarium|terrain-rgb (raster-DEM)\n"
              "  images    /NAME/{z}/{x}/{y}.png|jpg|webp as stored\n"
              "  lines, bundles, points, areas  /NAME/{z}/{x}/{y}.pbf (Mapbox Vector Tiles),\n"
              "            /NAME/style.json (a MapLibre style) and /NAME/{z}/{x}/{y}.png (drawn)\n"
              "  X.pmtiles /X.pmtiles with byte ranges (for the pmtiles:// protocol)\n"
              "and /NAME.json (TileJSON 3.0.0) for each; / lists them with a MapLibre and a\n"
              "CesiumJS view. Labelled packages' styles write the names with the glyphs of\n"
              "/fonts/{fontstack}/{start}-{end}.pbf (Debian's Noto fonts, made on first ask).\n"
              "Packages are read only and reopened when replaced on disk.\n"
              "Listens on 127.0.0.1 unless --bind says otherwise; prints its URL on stdout.");
  cli.option("--bind", "ADDR", "address to listen on (default 127.0.0.1; 0.0.0.0: every interface)",
             [&](const std::string& v) { http.bind = v; });
  cli.option("--port", "N", "port (default 8080; 0: any free port, printed on stdout)",
             [&](const std::string& v) { http.port = CliArgs::to_int("--port", v, 0, 65535); });
  cli.option("-j,--threads", "N",
             "worker threads, each serving its share of the connections (default: 2 per core, at "
             "least 4); tiles are cut on at most one thread per core whatever this is",
             [&](const std::string& v) { http.threads = CliArgs::to_int("-j", v, 1, 1024); });
  cli.option(
      "--timeout", "S",
      "seconds a client may take to send a request or read the answer "
      "(default 10)",
      [&](const std::string& v) { http.timeout_s = CliArgs::to_int("--timeout", v, 1, 3600); });
  cli.option("--web-libs", "DIR",
             "npm packages (maplibre-gl, cesium, pmtiles) served under /lib for the preview "
             "(default: the cache scripts/web-deps.sh fills, ~/.cache/globe-web/node_modules)",
             [&](const std::string& v) { handler.lib_dir = v; });
  cli.option("--lib-url", "URL",
             "where the preview pages load the libraries from instead of /lib (e.g. a CDN)",
             [&](const std::string& v) { handler.lib_url = v; });
  cli.option("--cache-mb", "MB",
             "memory per terrain package for decoded blocks, triangle errors and tiles cut on "
             "the fly (default 512)",
             [&](const std::string& v) {
               services.cache_bytes = size_t(CliArgs::to_int("--cache-mb", v, 0, 1 << 20)) << 20;
             });
  cli.flag("-q,--quiet", "no line per request on stderr", [&] { handler.log = false; });
  const auto inputs = cli.parse_command(args, 1, 10000, "PACKAGE");
  if (!inputs) return kExitOk;

  // SIGINT and SIGTERM end the server from a thread of their own.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::signal(SIGPIPE, SIG_IGN);

  one_heap_per_core();
  // The labels' glyphs: without fonts the packages are served all the same,
  // their styles without labels.
  try {
    handler.glyphs = std::make_shared<const web::GlyphSet>();
    services.fontstack = handler.glyphs->fontstack();
  } catch (const InputError& e) {
    std::cerr << "globe-serve: " << e.what() << "; the styles are left without labels" << std::endl;
  }
  serve::PackageRegistry registry(*inputs, services);
  serve::HttpServer* server_ptr = nullptr;
  serve::RequestHandler handle(registry, handler);
  serve::HttpServer server(http, [&](const serve::HttpRequest& r) { return handle(r); });
  server_ptr = &server;
  int port;
  try {
    port = server.bind();
  } catch (const std::runtime_error& e) {
    throw OutputError(e.what());
  }
  handle.set_fallback_host(http.bind + ":" + std::to_string(port));
  const std::string url = "http://" + http.bind + ":" + std::to_string(port) + "/";
  std::cout << url << std::endl;
  std::cerr << "globe-serve: " << inputs->size() << " package" << (inputs->size() == 1 ? "" : "s")
            << " on " << url << " (Ctrl-C stops)" << std::endl;
  std::thread waiter([&] {
    int sig = 0;
    sigwait(&signals, &sig);
    server_ptr->stop();
  });
  server.run();
  pthread_kill(waiter.native_handle(), SIGTERM);
  waiter.join();
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  return globe::run_reporting_errors("globe-serve", "globe-serve", "", [&] { return serve(args); });
}
