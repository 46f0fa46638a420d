// docs/tutorial.md as a new user follows it: every `sh` block of the page
// runs, in order, in an empty folder with the programs on PATH and `samples`
// linked to the sample data; the pictures it makes match the expected ones
// (tests/data/render/tutorial_*.png, with the render tests' tolerance), so
// the page and the programs cannot drift apart.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

namespace {

using namespace globe_test;

// The page's ```sh blocks, in order.
std::vector<std::string> sh_blocks(const std::string& markdown) {
  std::vector<std::string> blocks;
  std::istringstream in(markdown);
  std::string line, block;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line == "```sh") {
      inside = true;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      blocks.push_back(block);
    } else if (inside) {
      block += line + "\n";
    }
  }
  return blocks;
}

TEST(Tutorial, EveryStepRunsAndMakesItsPictures) {
  TempDir dir;
  const std::string page =
      read_file(fs::path(globe_test::paths::source_dir()) / "docs/tutorial.md");
  const std::vector<std::string> blocks = sh_blocks(page);
  ASSERT_GE(blocks.size(), 6u) << "docs/tutorial.md lost its steps";
  fs::create_directory_symlink(fs::path(globe_test::paths::samples_dir()).parent_path(),
                               dir / "samples");
  std::ofstream script(dir / "tutorial.sh");
  script << "set -euo pipefail\ncd " << dir.path().string() << "\n"
         << "export PATH=" << fs::path(globe_test::paths::tiler()).parent_path().string() << ":"
         << fs::path(globe_test::paths::vectorize()).parent_path().string() << ":"
         << fs::path(globe_test::paths::view()).parent_path().string() << ":$PATH\n";
  for (const std::string& b : blocks)
    script << b;
  script.close();
  const RunResult r = run("bash " + (dir / "tutorial.sh").string(), dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // Every picture the page names, against its expected image.
  const std::regex snapshot("--snapshot (tutorial_[a-z]+)\\.png");
  size_t pictures = 0;
  for (std::sregex_iterator m(page.begin(), page.end(), snapshot), end; m != end; ++m) {
    expect_image((dir / ((*m)[1].str() + ".png")).string(), (*m)[1].str());
    ++pictures;
  }
  EXPECT_GE(pictures, 6u);
}

}  // namespace
