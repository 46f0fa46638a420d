// Helpers shared by the tests: temporary folders, running the CLI tools and
// capturing exit code / stdout / stderr, and where the sample data lives.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <stdlib.h>

namespace globe_test {

namespace fs = std::filesystem;

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs a shell command line; stdout and stderr are captured separately.
inline RunResult run(const std::string& command, const fs::path& scratch) {
  const fs::path out = scratch / "run.stdout", err = scratch / "run.stderr";
  const std::string full = command + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(full.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

inline std::string tiler() {
  return GLOBE_TILER_PATH;
}
inline std::string vectorize() {
  return GLOBE_VECTORIZE_PATH;
}
inline fs::path samples() {
  return GLOBE_SAMPLES_DIR;
}

// A fresh folder per test, removed afterwards.
class TempDir {
 public:
  // `tag` tells apart two folders of one test.
  explicit TempDir(const std::string& tag = "") {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ =
        fs::temp_directory_path() / ("globe-test-" + std::string(info->test_suite_name()) + "-" +
                                     info->name() + tag + "-" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  // Kept for a look when the test failed and GLOBE_TEST_KEEP is set.
  ~TempDir() {
    if (std::getenv("GLOBE_TEST_KEEP") && ::testing::Test::HasFailure()) {
      std::cerr << "kept " << path_ << " (GLOBE_TEST_KEEP)\n";
      return;
    }
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

// A folder for fixtures shared by all tests of one binary run: unique (made by
// mkdtemp, so never a leftover of an earlier process with the same pid) and
// removed when the process exits.
inline fs::path run_scratch_dir(const std::string& prefix) {
  struct Owned {
    std::vector<fs::path> dirs;
    ~Owned() {
      std::error_code ec;
      for (const fs::path& d : dirs)
        fs::remove_all(d, ec);
    }
  };
  static Owned owned;
  std::string name = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
  if (!::mkdtemp(name.data())) {
    ADD_FAILURE() << "cannot make a folder like " << name;
    return {};
  }
  owned.dirs.emplace_back(name);
  return owned.dirs.back();
}

// Requires a sample fetched by samples/fetch.sh; fails (not skips) without it.
inline fs::path sample(const std::string& name) {
  const fs::path p = samples() / name;
  if (!fs::exists(p)) ADD_FAILURE() << p << " is missing: run samples/fetch.sh first";
  return p;
}

// The integer that follows the first `label` in `text` (spaces skipped), or
// -1 when there is none. Plain string search: GCC 12 warns inside std::regex
// in the sanitizer build, which CI compiles with -Werror.
inline long long integer_after(const std::string& text, const std::string& label) {
  size_t at = text.find(label);
  if (at == std::string::npos) return -1;
  at += label.size();
  while (at < text.size() && text[at] == ' ')
    ++at;
  size_t end = at;
  while (end < text.size() && text[end] >= '0' && text[end] <= '9')
    ++end;
  return end == at ? -1 : std::stoll(text.substr(at, end - at));
}

// `globe-tiler terrain -q OPTIONS INPUT -o OUT` run in `dir`, as a user
// runs it; for ASSERT_TRUE, failing with the tool's stderr.
inline ::testing::AssertionResult build_terrain(const std::string& options,
                                                const std::string& input, const std::string& out,
                                                const fs::path& dir) {
  const RunResult r = run(tiler() + " terrain -q " + options + " " + input + " -o " + out, dir);
  if (r.exit_code == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "terrain " << options << " " << input << ": exit " << r.exit_code << "\n"
         << r.err;
}

}  // namespace globe_test
