// The layering rules of docs/architecture.md, checked on the source tree and
// the built binaries: a rule that is not checked erodes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "test_paths.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

const fs::path kSource = globe_test::paths::source_dir();

// Lines of the C++ files under `dir` for which `bad` holds, as "path:line: text".
// (Plain string tests: GCC 12 warns inside std::regex in the sanitizer build.)
std::vector<std::string> matches(const fs::path& dir,
                                 const std::function<bool(const std::string&)>& bad) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(kSource / dir)) {
    const auto ext = e.path().extension();
    if (!e.is_regular_file() || (ext != ".cpp" && ext != ".hpp")) continue;
    std::istringstream in(read_file(e.path()));
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
      if (bad(line))
        out.push_back(fs::relative(e.path(), kSource).string() + ":" + std::to_string(n) + ": " +
                      line);
  }
  return out;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& l : v)
    s += l + "\n";
  return s;
}

bool has_any(const std::string& line, std::initializer_list<const char*> words) {
  for (const char* w : words)
    if (line.find(w) != std::string::npos) return true;
  return false;
}

TEST(Architecture, NoSqlOutsideTheLibrary) {
  auto sql = [](const std::string& l) {
    return has_any(l, {"SqliteDb", "SqliteStatement", "sqlite3", "db()", "\"SELECT ", "\"INSERT ",
                       "\"CREATE TABLE", "\"DROP TABLE", "\"DELETE FROM", "\"UPDATE "});
  };
  for (const char* dir : {"tools", "viewer"})
    EXPECT_EQ(joined(matches(dir, sql)), "") << dir << " talks SQL; add a query to lib/tileformat";
}

TEST(Architecture, ViewerIncludesNoGdal) {
  auto gdal = [](const std::string& l) {
    return l.starts_with("#include") && has_any(l, {"<gdal", "<ogr", "<cpl", "gdal_dataset.hpp",
                                                    "spatial_ref.hpp", "image_codec.hpp"});
  };
  EXPECT_EQ(joined(matches("viewer", gdal)), "");
  EXPECT_EQ(joined(matches("tools/common/kit", gdal)), "") << "the kit is GDAL-free";
  EXPECT_EQ(joined(matches("tools/tiler/analysis", gdal)), "") << "analysis is GDAL-free";
  EXPECT_EQ(joined(matches("lib", gdal)), "");
}

// tileformat includes its public headers (tileformat/) and, from its
// sources, its private ones (src/internal/, never beside the public ones).
TEST(Architecture, LibraryIncludesNothingAbove) {
  auto above = [](const std::string& l) {
    return l.starts_with("#include \"") && !l.starts_with("#include \"tileformat/") &&
           !l.starts_with("#include \"internal/");
  };
  EXPECT_EQ(joined(matches("lib/tileformat", above)), "");
  auto private_in_public = [](const std::string& l) {
    return l.starts_with("#include \"internal/");
  };
  EXPECT_EQ(joined(matches("lib/tileformat/include", private_in_public)), "")
      << "a public header includes a private one";
}

// The viewer stands on lib: its own folders, lib/runtime, lib/tileformat,
// lib/text and lib/net, nothing from tools/ (whose headers are found by bare
// names). And runtime stands on tileformat only; text and net on nothing of
// the project.
TEST(Architecture, ViewerIncludesNothingFromTools) {
  auto foreign = [](const std::string& l) {
    if (!l.starts_with("#include \"")) return false;
    for (const char* ok : {"app/", "camera/", "data/", "render/", "platform/", "runtime/",
                           "tileformat/", "text/", "net/"})
      if (l.starts_with(std::string("#include \"") + ok)) return false;
    return true;
  };
  EXPECT_EQ(joined(matches("viewer", foreign)), "") << "the viewer includes from tools/";
  auto above_runtime = [](const std::string& l) {
    return l.starts_with("#include \"") && !l.starts_with("#include \"runtime/") &&
           !l.starts_with("#include \"tileformat/");
  };
  EXPECT_EQ(joined(matches("lib/runtime", above_runtime)), "");
  auto outside_text = [](const std::string& l) {
    if (!l.starts_with("#include \"")) return false;
    for (const char* ok : {"text/", "bidi.hpp", "freetype_faces.hpp", "utf8.hpp"})
      if (l.starts_with(std::string("#include \"") + ok)) return false;
    return true;
  };
  EXPECT_EQ(joined(matches("lib/text", outside_text)), "") << "lib/text stands on no project code";
  auto outside_net = [](const std::string& l) {
    return l.starts_with("#include \"") && !l.starts_with("#include \"net/") &&
           !l.starts_with("#include \"curl_multi.hpp\"");
  };
  EXPECT_EQ(joined(matches("lib/net", outside_net)), "") << "lib/net stands on no project code";
}

// Each layer includes only its own folder and the layers below it
// (docs/architecture.md, the table): the viewer's platform < camera < data
// < render < app, and the tiler's pipelines over raster/, with analysis/
// and export/ beside them (no GDAL) and inspect/ and merge/ over them all.
TEST(Architecture, LayersIncludeOnlyTheirOwnAndBelow) {
  struct Layer {
    const char* dir;
    std::vector<std::string> may;  // the first folder of an include
  };
  const std::vector<std::string> lib = {"runtime", "tileformat", "text", "net"};
  auto with = [&](std::vector<std::string> v) {
    v.insert(v.end(), lib.begin(), lib.end());
    return v;
  };
  const std::vector<Layer> layers = {
      {"viewer/platform", with({"platform"})},
      {"viewer/camera", with({"camera", "platform"})},
      {"viewer/data", with({"data", "camera", "platform"})},
      {"viewer/render", with({"render", "data", "camera", "platform"})},
      {"viewer/app", with({"app", "render", "data", "camera", "platform"})},
      {"tools/tiler/raster", with({"raster", "geo", "kit"})},
      {"tools/tiler/terrain", with({"terrain", "raster", "geo", "kit"})},
      {"tools/tiler/imagery", with({"imagery", "raster", "geo", "kit"})},
      {"tools/tiler/analysis", with({"analysis", "kit"})},
      {"tools/tiler/export", with({"export", "web", "kit"})},
      {"tools/tiler/inspect",
       with({"inspect", "terrain", "imagery", "analysis", "raster", "geo", "web", "kit"})},
      {"tools/tiler/merge",
       with({"merge", "terrain", "imagery", "analysis", "raster", "geo", "kit"})},
  };
  for (const Layer& layer : layers) {
    auto above = [&](const std::string& l) {
      if (!l.starts_with("#include \"")) return false;
      const std::string path = l.substr(10, l.find('"', 10) - 10);
      const size_t slash = path.find('/');
      if (slash == std::string::npos) return false;
      return std::find(layer.may.begin(), layer.may.end(), path.substr(0, slash)) ==
             layer.may.end();
    };
    EXPECT_EQ(joined(matches(layer.dir, above)), "")
        << layer.dir << " includes from a layer above or beside it";
  }
}

// Whether `line` calls a C function named PREFIX + [A-Z_]... (e.g. GDALOpen,
// OGR_F_Create, OSRRelease, sqlite3_step), outside comments.
bool calls_c_api(const std::string& line, std::initializer_list<const char*> prefixes) {
  const std::string code = line.substr(0, line.find("//"));
  for (const char* prefix : prefixes)
    for (size_t at = code.find(prefix); at != std::string::npos; at = code.find(prefix, at + 1)) {
      if (at > 0 && (std::isalnum(static_cast<unsigned char>(code[at - 1])) || code[at - 1] == '_'))
        continue;
      const std::string p = prefix;
      size_t end = at + p.size();
      // GDALOpen, OGR_F_Create: an upper-case letter or '_' after the prefix;
      // prefixes ending in '_' (sqlite3_, ZSTD_, png_) take any letter.
      const bool name_goes_on =
          end < code.size() &&
          (std::isupper(static_cast<unsigned char>(code[end])) || code[end] == '_' ||
           (p.back() == '_' && std::isalpha(static_cast<unsigned char>(code[end]))));
      if (!name_goes_on) continue;
      while (end < code.size() &&
             (std::isalnum(static_cast<unsigned char>(code[end])) || code[end] == '_'))
        ++end;
      if (end < code.size() && code[end] == '(') return true;
    }
  return false;
}

std::vector<std::string> outside(const std::vector<std::string>& hits,
                                 std::initializer_list<const char*> wrappers) {
  std::vector<std::string> out;
  for (const std::string& h : hits) {
    bool allowed = false;
    for (const char* w : wrappers)
      allowed = allowed || h.starts_with(w);
    if (!allowed) out.push_back(h);
  }
  return out;
}

// globe-vectorize is one folder per pipeline (docs/architecture.md): only
// main.cpp and vectorize_commands.hpp at its root.
TEST(Architecture, VectorizeIsOneFolderPerPipeline) {
  const fs::path root = kSource / "tools/vectorize";
  std::vector<std::string> loose;
  for (const auto& e : fs::directory_iterator(root)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && name != "main.cpp" && name != "vectorize_commands.hpp" &&
        name != "CMakeLists.txt")
      loose.push_back(name);
  }
  EXPECT_EQ(joined(loose), "") << "put these in the folder of their pipeline";
}

// Includes name the folder of what they include ("kit/progress.hpp",
// "analysis/flow/flow_solver.hpp", "lines/line_plan.hpp"): no header under
// tools/ (but the two programs' command lists at their roots) is included
// by its bare name.
TEST(Architecture, IncludesNameTheirFolder) {
  std::vector<std::string> headers;
  for (const auto& e : fs::recursive_directory_iterator(kSource / "tools")) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && e.path().extension() == ".hpp" && name != "tiler_commands.hpp" &&
        name != "vectorize_commands.hpp")
      headers.push_back(name);
  }
  auto bare = [&](const std::string& l) {
    for (const std::string& h : headers)
      if (l.find("#include \"" + h + "\"") != std::string::npos) return true;
    return false;
  };
  for (const char* dir : {"tools", "tests", "bench", "viewer"})
    EXPECT_EQ(joined(matches(dir, bare)), "") << "include these by their folder";
}

// info, validate and extract find a package's kind in their tool's table of
// kinds (kit/kind_inspection), never by testing the kind themselves: adding
// a kind adds a row (docs/architecture.md, "A new package kind").
TEST(Architecture, InspectionDispatchesThroughTheTableOfKinds) {
  auto dispatch = [](const std::string& l) {
    return has_any(l, {"package_kind(", "package_kind_of_format(", "kind == ", "kind != "});
  };
  for (const char* dir : {"tools/tiler/inspect", "tools/vectorize/inspect"})
    EXPECT_EQ(joined(matches(dir, dispatch)), "")
        << dir << " tells kinds apart itself; add a row to its inspect_commands.cpp table";
}

// The scene and the headless run draw, resize, poll and report the layers
// over the terrain through SceneLayer, not by kind (docs/architecture.md,
// "A new viewer layer"); only construction names the kinds.
TEST(Architecture, SceneDrivesItsLayersThroughOneInterface) {
  auto by_kind = [](const std::string& l) {
    return has_any(l, {"images_->", "charts_->", "scene.lines()", "scene.charts()",
                       "scene.images()"}) ||
           (l.find("lines_->") != std::string::npos &&
            l.find("lines_->enable_heatmap") == std::string::npos);
  };
  for (const char* file : {"terrain_scene.cpp", "headless_run.cpp"}) {
    std::vector<std::string> hits;
    std::istringstream in(read_file(kSource / "viewer/app" / file));
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
      if (by_kind(line)) hits.push_back(std::string(file) + ":" + std::to_string(n) + ": " + line);
    EXPECT_EQ(joined(hits), "") << "drive the layers through SceneLayer";
  }
}

TEST(Architecture, EachCApiIsCalledOnlyFromItsWrapper) {
  auto gdal = [](const std::string& l) {
    return calls_c_api(l, {"GDAL", "OGR", "OSR", "OCT", "CPL", "CSL", "VSI"});
  };
  EXPECT_EQ(
      joined(outside(matches("tools", gdal),
                     {"tools/common/geo/", "tools/tiler/raster/raster_warper.",
                      "tools/vectorize/io/vector_reader.", "tools/vectorize/io/vector_writer.",
                      // a GDAL driver implements GDAL's own API
                      "tools/gdal_plugin/"})),
      "")
      << "call GDAL/OGR/OSR through tools/common/geo (docs/architecture.md rule 3)";
  auto sqlite = [](const std::string& l) { return calls_c_api(l, {"sqlite3_"}); };
  EXPECT_EQ(joined(outside(matches("lib", sqlite),
                           {"lib/tileformat/src/sqlite_db.", "lib/net/src/disk_cache."})),
            "");
  // libcurl (lib/net's HTTP client) in its one wrapper.
  auto curl = [](const std::string& l) { return calls_c_api(l, {"curl_"}); };
  for (const char* dir : {"lib", "tools", "viewer"})
    EXPECT_EQ(joined(outside(matches(dir, curl), {"lib/net/src/curl_multi."})), "") << dir;
  auto zstd = [](const std::string& l) { return calls_c_api(l, {"ZSTD_"}); };
  EXPECT_EQ(joined(outside(matches("lib", zstd), {"lib/tileformat/src/zstd_codec."})), "");
  auto png = [](const std::string& l) { return calls_c_api(l, {"png_"}); };
  auto jpeg_webp = [](const std::string& l) { return calls_c_api(l, {"jpeg_", "WebP"}); };
  for (const char* dir : {"lib", "tools", "viewer"}) {
    EXPECT_EQ(joined(outside(matches(dir, png), {"lib/runtime/src/png_codec."})), "") << dir;
    EXPECT_EQ(joined(outside(matches(dir, jpeg_webp), {"lib/runtime/src/jpeg_webp_decoders."})), "")
        << dir;
  }
  // libmicrohttpd (globe-serve's HTTP) in its one wrapper.
  auto mhd = [](const std::string& l) { return calls_c_api(l, {"MHD_"}); };
  EXPECT_EQ(joined(outside(matches("tools", mhd), {"tools/serve/http_server."})), "");
  for (const char* dir : {"tools", "viewer"}) {
    EXPECT_EQ(joined(matches(dir, sqlite)), "") << dir;
    EXPECT_EQ(joined(matches(dir, zstd)), "") << dir;
  }
}

// globe-tiler itself runs `analyze` without GDAL and execs globe-tiler-gdal
// for the rest (tools/tiler/main.cpp).
TEST(Architecture, ViewerLibTestsAndTheTilerFrontLinkNoGdal) {
  TempDir dir;
  for (const std::string& binary :
       {globe_test::paths::view(), globe_test::paths::lib_tests(), tiler()}) {
    const RunResult r = run("ldd " + binary, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.find("libgdal"), std::string::npos) << binary << ":\n" << r.out;
  }
}

}  // namespace
