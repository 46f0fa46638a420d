// The layering rules of docs/architecture.md, checked on the source tree and
// the built binaries: a rule that is not checked erodes.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace {

using namespace globe_test;

const fs::path kSource = GLOBE_SOURCE_DIR;

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
  EXPECT_EQ(joined(matches("lib", gdal)), "");
}

TEST(Architecture, LibraryIncludesNothingAbove) {
  auto above = [](const std::string& l) {
    return l.starts_with("#include \"") && !l.starts_with("#include \"tileformat/");
  };
  EXPECT_EQ(joined(matches("lib", above)), "");
}

TEST(Architecture, ViewerAndLibTestsLinkNoGdal) {
  TempDir dir;
  for (const std::string& binary :
       {std::string(GLOBE_VIEW_PATH), std::string(GLOBE_LIB_TESTS_PATH)}) {
    const RunResult r = run("ldd " + binary, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.find("libgdal"), std::string::npos) << binary << ":\n" << r.out;
  }
}

}  // namespace
