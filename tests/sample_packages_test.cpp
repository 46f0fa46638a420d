// The packages the tools make from the samples, pinned by their SHA-256:
// refactorings must not change a byte of them (issue "Architecture"). A
// deliberate change of the output (format, coding, metadata) updates
// tests/data/sample_package_hashes.txt in the same commit and says why;
// GLOBE_UPDATE_HASHES=1 makes the test print the new lines instead of
// failing.
//
// Every command runs in a scratch folder that links the samples as `data/`,
// so the recorded command line and input names do not depend on where the
// checkout lies. The hashes hold for Debian 12's GDAL, PROJ, zstd, libpng and
// libjpeg (what CI and scripts/install-deps.sh install).
#include <cstdlib>
#include <map>

#include "test_paths.hpp"
#include "test_support.hpp"

using namespace globe_test;

namespace {

struct SamplePackage {
  const char* name;     // package file, and the key in the hash file
  const char* tool;     // "tiler" or "vectorize"
  const char* command;  // arguments, inputs relative to the scratch folder
};

// One package of every kind and scheme the samples allow.
const SamplePackage kPackages[] = {
    {"jacksboro.mbtiles", "tiler", "terrain data/jacksboro.tif"},
    {"brasilia_local.mbtiles", "tiler", "terrain data/brasilia.tif --tiling local"},
    {"etopo20_geodetic.mbtiles", "tiler", "terrain data/etopo20.tif --tiling geodetic"},
    {"landsat321.mbtiles", "tiler", "imagery data/landsat.tif --bands 3,2,1"},
    {"cbers20_jpg.mbtiles", "tiler", "imagery data/cbers20.tif --format jpg --max-zoom 11"},
    {"canada_roads.mbtiles", "vectorize",
     "lines data/canada_roads.shp --s_srs EPSG:3978 --class-field CLASS "
     "--class-map 1=highway,2=primary,3=secondary,4=minor,200=ferry "
     "--style highway:color=#d7301f,width=4px --style ferry:color=#2b8cbe,width=2px,dash=6+4"},
};

std::map<std::string, std::string> pinned_hashes() {
  std::map<std::string, std::string> hashes;
  std::ifstream in(fs::path(globe_test::paths::test_data_dir()) / "sample_package_hashes.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name, hash;
    fields >> name >> hash;
    hashes[name] = hash;
  }
  return hashes;
}

std::string sha256_of(const fs::path& file, const fs::path& scratch) {
  const auto r = run("sha256sum " + file.string(), scratch);
  return r.out.substr(0, r.out.find(' '));
}

TEST(SamplePackages, AreByteIdenticalToThePinnedHashes) {
  TempDir dir;
  fs::create_directory_symlink(samples(), dir / "data");
  sample("jacksboro.tif");  // fails with a clear message when samples are missing
  const auto pinned = pinned_hashes();
  const bool update = std::getenv("GLOBE_UPDATE_HASHES") != nullptr;
  std::string new_lines;
  for (const auto& p : kPackages) {
    SCOPED_TRACE(p.name);
    const std::string tool = std::string(p.tool) == "tiler" ? tiler() : vectorize();
    const auto r =
        run("cd " + dir.path().string() + " && " + tool + " " + p.command + " -q -o " + p.name,
            dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string hash = sha256_of(dir / p.name, dir.path());
    ASSERT_EQ(hash.size(), 64u);
    new_lines += std::string(p.name) + " " + hash + "\n";
    if (update) continue;
    const auto it = pinned.find(p.name);
    ASSERT_NE(it, pinned.end()) << p.name << " has no pinned hash";
    EXPECT_EQ(hash, it->second)
        << p.name << " changed: if on purpose, update tests/data/sample_package_hashes.txt "
        << "(GLOBE_UPDATE_HASHES=1 prints the lines) and say why in the commit";
  }
  if (update) std::cout << new_lines;
}

}  // namespace
