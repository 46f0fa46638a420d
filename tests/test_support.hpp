// Helpers shared by the tests: temporary folders, running the CLI tools and
// capturing exit code / stdout / stderr, and where the sample data lives.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <stdlib.h>
#include "test_paths.hpp"

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
  return globe_test::paths::tiler();
}
inline std::string vectorize() {
  return globe_test::paths::vectorize();
}
// Great-circle metres on the mean sphere (haversine): the bundling tests'
// reference length, written here, not the tools' ellipsoid (they agree
// within 0.6 %).
inline double haversine_m(double lon1, double lat1, double lon2, double lat2) {
  constexpr double kR = 6371008.8, d = 3.14159265358979323846 / 180;
  const double sy = std::sin((lat2 - lat1) * d / 2), sx = std::sin((lon2 - lon1) * d / 2);
  const double h = sy * sy + std::cos(lat1 * d) * std::cos(lat2 * d) * sx * sx;
  return 2 * kR * std::asin(std::min(1.0, std::sqrt(h)));
}

inline fs::path samples() {
  return globe_test::paths::samples_dir();
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

// Runs each command in `dir` and stops at the first that fails, a test
// failure with its stderr; returns whether all of them succeeded.
inline bool run_all(const std::vector<std::string>& commands, const fs::path& dir) {
  for (const std::string& cmd : commands) {
    const RunResult r = run(cmd, dir);
    if (r.exit_code != 0) {
      ADD_FAILURE() << cmd << ": exit " << r.exit_code << "\n" << r.err;
      return false;
    }
  }
  return true;
}

// A folder of inputs that the tests of one binary read and never change,
// built once per build tree: ctest runs each TEST in a process of its own, so
// a per-process fixture would be rebuilt for every test. The folder lives
// under <build>/tests/shared/NAME.BINARY (one per test binary: two binaries'
// stamps differ, so a shared folder would be rebuilt under the other's
// readers); the first process builds it while the
// others wait on a lock, and it is built again whenever the test binary, the
// tools (both tiler executables) or the samples folder changed (their sizes
// and times are the stamp).
// `build(dir)` returns whether everything it made is good; a failed build
// leaves no stamp, so the next test tries again. `also` names more files the
// build reads (a script of tests/data, say) that go into the stamp.
template <class Build>
fs::path shared_folder(const std::string& name, Build build, std::vector<fs::path> also = {}) {
  const fs::path dir = fs::path(globe_test::paths::shared_dir()) /
                       (name + "." + fs::read_symlink("/proc/self/exe").filename().string());
  fs::create_directories(dir.parent_path());
  const std::string lock_path = dir.string() + ".lock";
  const int lock = ::open(lock_path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
  if (lock < 0 || ::flock(lock, LOCK_EX) != 0) {
    ADD_FAILURE() << "cannot lock " << lock_path;
    if (lock >= 0) ::close(lock);
    return dir;
  }
  std::string stamp;
  const fs::path tiler_gdal = fs::path(tiler()).parent_path() / "globe-tiler-gdal";
  also.insert(also.end(), {fs::path("/proc/self/exe"), fs::path(tiler()), tiler_gdal,
                           fs::path(vectorize()), samples()});
  for (const fs::path& p : also) {
    std::error_code ec;
    const fs::path real = fs::canonical(p, ec);
    const auto time = fs::last_write_time(real, ec).time_since_epoch().count();
    const auto size = fs::is_regular_file(real, ec) ? fs::file_size(real, ec) : 0;
    stamp += real.string() + " " + std::to_string(size) + " " + std::to_string(time) + "\n";
  }
  const fs::path stamp_path = dir / ".stamp";
  if (!fs::exists(stamp_path) || read_file(stamp_path) != stamp) {
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::create_directories(dir);
    if (build(dir)) std::ofstream(stamp_path, std::ios::binary) << stamp;
  }
  ::flock(lock, LOCK_UN);
  ::close(lock);
  return dir;
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
