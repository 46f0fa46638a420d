// `cmake --install` and `cpack -G DEB` as a packager runs them: the five
// programs, the tile-format library and headers, the GDAL plugin and the
// docs land under the prefix, the installed globe-tiler finds its GDAL half
// there, GDAL reads a package through the installed plugin, a program builds
// against the installed headers, and the .deb holds the same files.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "test_paths.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

TEST(Install, ProgramsLibraryHeadersAndDocsLandUnderThePrefix) {
  TempDir dir;
  const fs::path prefix = dir / "prefix";
  ASSERT_TRUE(run_all(
      {"cmake --install " + globe_test::paths::binary_dir() + " --prefix " + prefix.string()},
      dir.path()));
  for (const char* f : {"bin/globe-tiler", "bin/globe-tiler-gdal", "bin/globe-vectorize",
                        "bin/globe-view", "bin/globe-serve", "lib/libtileformat.a",
                        "include/tileformat/mblock.hpp", "share/doc/globe-tiles/README.md",
                        "share/doc/globe-tiles/LICENSE", "share/doc/globe-tiles/cli.md"})
    EXPECT_TRUE(fs::exists(prefix / f)) << f;
  // The installed front runs the GDAL commands through the installed half.
  const RunResult t =
      run((prefix / "bin/globe-tiler").string() + " terrain -q " +
              sample("jacksboro.tif").string() + " --max-zoom 8 -o " + (dir / "t.mbtiles").string(),
          dir.path());
  EXPECT_EQ(t.exit_code, 0) << t.err;
  // The GDAL plugin, where GDAL of this prefix looks (LIBDIR/gdalplugins),
  // reads the package through GDAL's own gdalinfo.
  fs::path plugin;
  for (const auto& e : fs::recursive_directory_iterator(prefix))
    if (e.path().filename() == "gdal_GlobeTiles.so") plugin = e.path();
  ASSERT_FALSE(plugin.empty());
  EXPECT_EQ(plugin.parent_path().filename(), "gdalplugins");
#ifndef GLOBE_ADDRESS_SANITIZER  // an ASan-built plugin cannot load into gdalinfo
  const RunResult g = run("GDAL_DRIVER_PATH=" + plugin.parent_path().string() + " gdalinfo " +
                              (dir / "t.mbtiles").string(),
                          dir.path());
  EXPECT_NE(g.out.find("Driver: GlobeTiles/"), std::string::npos) << g.out << g.err;
#endif
  // A program of a user's, against the installed headers and library alone.
  std::ofstream(dir / "user.cpp")
      << "#include <tileformat/tiling.hpp>\n"
         "#include <cstdio>\n"
         "int main() { std::printf(\"%g\\n\", tileformat::Tiling::geodetic().root_size); }\n";
  const RunResult c =
      run(globe_test::paths::user_cxx() + " -std=c++20 -I" + (prefix / "include").string() + " " +
              (dir / "user.cpp").string() + " " + (prefix / "lib/libtileformat.a").string() +
              " -lzstd -lsqlite3 -o " + (dir / "user").string() + " && " + (dir / "user").string(),
          dir.path());
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(c.out, "180\n");
}

TEST(Install, CpackMakesADebianPackageWithItsDependencies) {
  TempDir dir;
  ASSERT_TRUE(
      run_all({"cpack -G DEB --config " + globe_test::paths::binary_dir() + "/CPackConfig.cmake"},
              dir.path()));
  const RunResult info = run("dpkg-deb -f globe-tiles_*.deb Package Depends", dir.path());
  EXPECT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("Package: globe-tiles"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("libgdal"), std::string::npos) << info.out;
  const RunResult files = run("dpkg-deb -c globe-tiles_*.deb", dir.path());
  for (const char* f : {"./usr/bin/globe-tiler-gdal", "./usr/bin/globe-view",
                        "./usr/include/tileformat/package.hpp", "gdalplugins/gdal_GlobeTiles.so"})
    EXPECT_NE(files.out.find(f), std::string::npos) << f;
}

}  // namespace
