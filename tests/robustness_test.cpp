// Crash safety and failure handling of the package builders (docs/robustness.md):
// kill -9 at random moments never leaves an incomplete package under the final
// name and --resume then yields the uninterrupted run's bytes; a full disk is
// a clear error with nothing left behind; a viewer keeps reading the package
// it opened while another process replaces the file.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <random>
#include <thread>

#include "point_fixtures.hpp"
#include "render_fixtures.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

using namespace globe_test;

namespace {

// Under ASan + UBSan (scripts/sanitize.sh) the builds run 2-4x slower and the
// plain build (scripts/test.sh) has already proven every kill's bytes; there
// the kill-and-resume tests exercise the resume paths under the sanitizers
// with a quarter of the random kills and every third commit (the first and
// the last included), which keeps CI within its budget (docs/ci.md).
// There too the uninterrupted -j1 build is left out: the plain build proves
// that -j1 and -j2 give the same bytes, and one uninterrupted build is all
// the resumed ones are compared with.
#ifdef GLOBE_ADDRESS_SANITIZER
constexpr int kKillDivisor = 4, kCommitStride = 3;
constexpr bool kCompareThreads = false;
#else
constexpr int kKillDivisor = 1, kCommitStride = 1;
constexpr bool kCompareThreads = true;
#endif

// Starts `command` in `dir` with /bin/sh (exec'd, so the pid is the command's).
pid_t spawn(const fs::path& dir, const std::string& command) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string line = "cd '" + dir.string() + "' && exec " + command;
    ::execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

bool same_bytes(const fs::path& a, const fs::path& b) {
  return fs::exists(a) && fs::exists(b) && read_file(a) == read_file(b);
}

// No temporary or scratch file of the build of `out` is left in `dir`.
void expect_no_leftovers(const fs::path& dir, const std::string& out) {
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    EXPECT_FALSE(name.rfind(out + ".", 0) == 0) << "left behind: " << name;
  }
}

// Whether a run's notes say it continued from saved work: committed tiles,
// or a stage checkpoint past the start (the raster builders' note).
bool continued_from_saved_work(const std::string& err) {
  return (err.find("resuming") != std::string::npos &&
          err.find(": 0 tiles") == std::string::npos) ||
         err.find("continuing at zoom") != std::string::npos;
}

// Builds `build` (a command without -o) uninterrupted with -j1 and with -j2
// (same bytes), then again with -j2 --resume, killing it (SIGKILL) after
// random delays (up to `max_delay`, or 1.2 times the -j2 build's time where
// that is shorter) until it has been killed `min_kills` times, then once at
// 3/4 of its usual time. Every kill must leave either no file under the final
// name or the complete package; every run that finishes, and the last resumed
// run, must give the uninterrupted run's bytes, and the last run must have
// continued from saved work.
void kill_and_resume(const std::string& build, int min_kills, std::chrono::milliseconds max_delay) {
  min_kills = std::max(std::min(min_kills, 3), min_kills / kKillDivisor);
  TempDir dir;
  fs::create_directories(dir / "ref");
  fs::create_directories(dir / "work");
  const fs::path ref = dir / "ref" / "out.mbtiles", out = dir / "work" / "out.mbtiles";
  if (kCompareThreads) {
    const RunResult r =
        run("cd " + (dir / "ref").string() + " && " + build + " -o out.mbtiles -j1", dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const RunResult j2 =
      run("cd " + (dir / "work").string() + " && " + build + " -o out.mbtiles -j2", dir.path());
  const auto duration = std::chrono::steady_clock::now() - t0;
  ASSERT_EQ(j2.exit_code, 0) << j2.err;
  if (kCompareThreads) {
    ASSERT_TRUE(same_bytes(out, ref)) << "-j2 and -j1 builds differ";
    fs::remove(out);
  } else {
    fs::rename(out, ref);
  }

  // Delays up to `max_delay`, or a little past the uninterrupted build's
  // duration where that is shorter: a kill drawn later than the build's end
  // would only rerun the whole build, unkilled (the imagery case once spent
  // two minutes so).
  const auto duration_ms = std::chrono::duration_cast<std::chrono::milliseconds>(duration).count();
  const int upper = static_cast<int>(
      std::clamp<int64_t>(duration_ms * 6 / 5, 100, std::max<int64_t>(100, max_delay.count())));
  std::mt19937 rng(20261122);
  std::uniform_int_distribution<int> delay_ms(20, upper);
  int kills = 0, finished = 0, resumed_with_work = 0;
  for (int attempt = 0; kills < min_kills && attempt < 20 * min_kills; ++attempt) {
    const pid_t pid = spawn(dir / "work", build + " -o out.mbtiles -j2 --resume >/dev/null 2>" +
                                              (dir / "run.stderr").string());
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(rng)));
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << read_file(dir / "run.stderr");
      ASSERT_TRUE(same_bytes(out, ref)) << "a resumed build differs from the uninterrupted one";
      ++finished;
      fs::remove(out);
      continue;
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    ++kills;
    if (continued_from_saved_work(read_file(dir / "run.stderr"))) ++resumed_with_work;
    if (fs::exists(out)) {  // killed after the rename: must be the whole package
      ASSERT_TRUE(same_bytes(out, ref)) << "kill " << kills << " left a partial package";
      ++finished;
      fs::remove(out);
    }
  }
  EXPECT_GE(kills, min_kills);
  // A fresh build killed late enough to have saved work: the next run must
  // continue from it. The machine is shared, so the moment adapts: earlier
  // when the build finished first, later (past the measured duration, as a
  // loaded machine runs it slower) when nothing had been saved yet.
  double fraction = 0.75;
  bool continued = false;
  std::string last_err;
  for (int attempt = 0; attempt < 12 && !continued; ++attempt) {
    fs::remove(out);
    const pid_t pid = spawn(dir / "work", build + " -o out.mbtiles -j2 2>/dev/null");
    std::this_thread::sleep_for(std::chrono::duration_cast<std::chrono::milliseconds>(duration) *
                                fraction);
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    if (fs::exists(out)) {  // finished before the kill
      ASSERT_TRUE(same_bytes(out, ref));
      fraction *= 0.7;
      continue;
    }
    const RunResult last =
        run("cd " + (dir / "work").string() + " && " + build + " -o out.mbtiles -j2 --resume",
            dir.path());
    ASSERT_EQ(last.exit_code, 0) << last.err;
    EXPECT_TRUE(same_bytes(out, ref)) << "the resumed package differs from the uninterrupted one";
    expect_no_leftovers(dir / "work", "out.mbtiles");
    continued = continued_from_saved_work(last.err);
    last_err = last.err;
    fraction = std::min(3.0, fraction * 1.25);
  }
  EXPECT_TRUE(continued) << "no resumed run continued from saved work; last notes: " << last_err;
  std::cerr << "kills " << kills << ", finished runs " << finished
            << ", killed runs that had continued from saved work " << resumed_with_work << "\n";
}

// Builds `build` uninterrupted, then once per commit it makes: killed right
// after that commit (the kill_after_commit shim) and resumed. A kill between
// two commits leaves what a kill right after the first leaves, so this visits
// every state an interrupted build can leave, the same ones in every run
// (the random kills above may miss a short window). Every resumed build must
// give the uninterrupted build's bytes. Under the sanitizers it visits every
// kCommitStride-th commit and always the last.
void kill_after_every_commit(const std::string& build) {
  TempDir dir;
  fs::create_directories(dir / "ref");
  const fs::path ref = dir / "ref" / "out.mbtiles", work = dir / "work", out = work / "out.mbtiles";
  const RunResult r =
      run("cd " + (dir / "ref").string() + " && " + build + " -o out.mbtiles -j1", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // (ASan wants its runtime first among the preloaded libraries.)
  const std::string shim = std::string("LD_PRELOAD=") + globe_test::paths::kill_after_commit() +
                           " ASAN_OPTIONS=\"$ASAN_OPTIONS:verify_asan_link_order=0\" ";
  // Kills after commit k and resumes; false when the build made fewer than k
  // commits (it finished).
  const auto visit = [&](int k) {
    fs::remove_all(work);
    fs::create_directories(work);
    const RunResult killed =
        run("cd " + work.string() + " && GLOBE_TEST_KILL_AFTER_COMMIT=" + std::to_string(k) + " " +
                shim + build + " -o out.mbtiles -j2",
            dir.path());
    if (killed.exit_code == 0) return false;
    EXPECT_TRUE(killed.exit_code == 128 + SIGKILL || killed.exit_code == -1) << killed.err;
    EXPECT_FALSE(fs::exists(out)) << "killed after commit " << k << ", yet finished";
    const RunResult resumed =
        run("cd " + work.string() + " && " + build + " -o out.mbtiles -j2 --resume", dir.path());
    EXPECT_EQ(resumed.exit_code, 0) << "resuming after commit " << k << ": " << resumed.err;
    EXPECT_TRUE(same_bytes(out, ref))
        << "killed after commit " << k << " and resumed, the package differs";
    expect_no_leftovers(work, "out.mbtiles");
    return true;
  };
  int k = 1, visited = 0, last = 0;
  for (; !::testing::Test::HasFailure() && visit(k); k += kCommitStride)
    ++visited, last = k;
  // Past the end with a stride: step back to the last commit.
  for (int back = k - 1; back > last; --back)
    if (visit(back)) {
      ++visited, last = back;
      break;
    }
  EXPECT_GE(last, 4) << "the build made too few commits for this test";
  std::cerr << "resumed after " << visited << " of the " << last << " commits\n";
}

std::string terrain_build() {
  return tiler() + " terrain " + sample("etopo20.tif").string() + " --max-zoom 4";
}
std::string lines_build() {
  return vectorize() + " lines " + sample("ne_admin1.shp").string();
}

}  // namespace

TEST(CrashSafety, TerrainSurvivesRandomKillsAndResumesToTheSameBytes) {
  kill_and_resume(terrain_build(), 20, std::chrono::milliseconds(3000));
}

TEST(CrashSafety, LinesSurviveRandomKillsAndResumeToTheSameBytes) {
  kill_and_resume(lines_build(), 20, std::chrono::milliseconds(2500));
}

TEST(CrashSafety, ImageryResumesToTheSameBytes) {
  // Image builds resume by level: the finest takes about 5 s here.
  kill_and_resume(tiler() + " imagery " + sample("bluemarble.tif").string() + " --max-zoom 4", 5,
                  std::chrono::milliseconds(8000));
}

TEST(CrashSafety, AnalyzeResumesToTheSameBytes) {
  const TempDir terrain("-terrain");
  const std::string pkg = (terrain / "t.mbtiles").string();
  ASSERT_EQ(
      run(tiler() + " terrain -q " + sample("etopo20.tif").string() + " --max-zoom 3 -o " + pkg,
          terrain.path())
          .exit_code,
      0);
  kill_and_resume(tiler() + " analyze " + pkg + " --layers slope,aspect,skyview", 10,
                  std::chrono::milliseconds(2500));
}

// A points build reads and aggregates again when resumed and skips the
// tiles already committed, which it writes zoom by zoom in band order
// (docs/points.md "Memory and speed"): killed after any commit, it resumes
// to the same bytes. 1 MB of sort memory makes every sort spill.
TEST(CrashSafety, PointsKilledAfterEveryCommitResumeToTheSameBytes) {
#ifdef GLOBE_ADDRESS_SANITIZER
  // 18 s under ASan + UBSan (10 s in the plain build): left to the plain
  // build; the sanitizers see the same spilling sorts and band merges in
  // PointsCli.OutputIsTheSameForAnyThreadCountAndMemory (docs/ci.md).
  GTEST_SKIP() << "runs in the plain build";
#endif
  const TempDir data("-places");
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> lon(-10, 30), lat(35, 60);
  std::vector<CsvPlace> places;
  for (int i = 0; i < 12000; ++i)
    places.push_back({"p" + std::to_string(i), lon(rng), lat(rng), {double(rng() % 100)}});
  const std::string csv = (data / "p.csv").string();
  write_places_csv(csv, {"a"}, places);
  kill_after_every_commit(vectorize() + " points " + csv +
                          " --xy lon,lat --fields a --max-zoom 9 --memory-mb 1");
}

// An area build commits its features table, then its tiles in key order:
// killed after any commit, it resumes to the same bytes (the world's
// countries as a choropleth to zoom 5, every sort spilling at 1 MB).
TEST(CrashSafety, AreasKilledAfterEveryCommitResumeToTheSameBytes) {
  kill_after_every_commit(vectorize() + " areas " + sample("world.gpkg").string() +
                          " --max-zoom 5 --choropleth pop/area_km2 --memory-mb 1");
}

// A shard is a build like any other (docs/scale-out.md: a failed array task
// is re-run with --resume), and so is the merge.
// A shard's parts (node errors near its border) are committed with their
// tile: one committed without them was lost by the resume.
TEST(CrashSafety, TerrainShardKilledAfterEveryCommitResumesToTheSameBytes) {
  kill_after_every_commit(terrain_build() + " --shard 1/3 --split-zoom 2");
}

TEST(CrashSafety, ImageryShardResumesToTheSameBytes) {
  kill_and_resume(tiler() + " imagery " + sample("bluemarble.tif").string() +
                      " --max-zoom 4 --shard 0/2 --split-zoom 2",
                  6, std::chrono::milliseconds(900));
}

TEST(CrashSafety, LineShardResumesToTheSameBytes) {
  kill_and_resume(lines_build() + " --shard 1/3", 10, std::chrono::milliseconds(1500));
}

TEST(CrashSafety, MergeResumesToTheSameBytes) {
  const TempDir shards("-shards");
  std::string list;
  for (int i = 0; i < 3; ++i) {
    const std::string out = (shards / ("s" + std::to_string(i) + ".mbtiles")).string();
    ASSERT_TRUE(build_terrain("--max-zoom 5 --split-zoom 3 --shard " + std::to_string(i) + "/3",
                              sample("etopo20.tif").string(), out, shards.path()));
    list += " " + out;
  }
  kill_and_resume(tiler() + " merge" + list, 10, std::chrono::milliseconds(800));
}

// A line merge copies the features table in its first transaction, then
// the tiles: killed in either, it resumes to the same bytes.
TEST(CrashSafety, LineMergeResumesToTheSameBytes) {
  const TempDir shards("-shards");
  std::string list;
  for (int i = 0; i < 3; ++i) {
    const std::string out = (shards / ("s" + std::to_string(i) + ".mbtiles")).string();
    ASSERT_EQ(
        run(lines_build() + " -q --shard " + std::to_string(i) + "/3 -o " + out, shards.path())
            .exit_code,
        0);
    list += " " + out;
  }
  kill_and_resume(vectorize() + " merge" + list, 10, std::chrono::milliseconds(600));
}

// The one moment random kills rarely hit: after the last level, before the
// staging file is removed and the package renamed. strace holds the build
// there (a delay injected into the staging file's second unlink, its
// removal), the test kills it, and the resumed build - with nothing left to
// do but the metadata - must still give the uninterrupted bytes (it wrote no
// globe:png_level, as it had counted no PNG tile).
TEST(CrashSafety, ImageryKilledAfterItsLastLevelResumesToTheSameBytes) {
  TempDir dir;
  // A container may forbid ptrace; then there is no way to hold the build.
  if (run("strace -f -o /dev/null true", dir.path()).exit_code != 0)
    GTEST_SKIP() << "strace cannot trace here (ptrace not permitted)";
  fs::create_directories(dir / "ref");
  fs::create_directories(dir / "work");
  const std::string build = tiler() + " imagery -q " + sample("bluemarble.tif").string() +
                            " --max-zoom 3 -o out.mbtiles -j2";
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(run("cd " + (dir / "ref").string() + " && " + build, dir.path()).exit_code, 0);
  const auto took = std::chrono::steady_clock::now() - t0;
  const auto hold =
      std::chrono::duration_cast<std::chrono::microseconds>(took * 4 + std::chrono::seconds(10));
  const pid_t pid = spawn(dir / "work",
                          "strace -f -o /dev/null -P out.mbtiles.staging -e trace=unlink "
                          "-e inject=unlink:delay_enter=" +
                              std::to_string(hold.count()) + ":when=2 " + build + " --resume");
  ASSERT_GT(pid, 0);
  // Wait until the build (strace's child) sits in the delayed unlink, seen
  // in /proc/PID/syscall (x86-64's unlink is 87); elsewhere, for a while.
  const auto deadline = std::chrono::steady_clock::now() + took * 3 + std::chrono::seconds(5);
  std::string build_pid;
  while (std::chrono::steady_clock::now() < deadline) {
    build_pid = run("pgrep -P " + std::to_string(pid), dir.path()).out;
    build_pid = build_pid.substr(0, build_pid.find('\n'));
    if (!build_pid.empty() && read_file("/proc/" + build_pid + "/syscall").rfind("87 ", 0) == 0)
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  // The build first, and only it: killed first, strace would let the build
  // go on (a pattern naming the command matched strace too, a race).
  ASSERT_FALSE(build_pid.empty()) << "the build under strace did not start";
  ::kill(std::stoi(build_pid), SIGKILL);
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_FALSE(fs::exists(dir / "work" / "out.mbtiles"))
      << "the build was not held before its rename";
  ASSERT_TRUE(fs::exists(dir / "work" / "out.mbtiles.staging"))
      << run("ls -la " + (dir / "work").string(), dir.path()).out;
  const RunResult r =
      run("cd " + (dir / "work").string() + " && " + tiler() + " imagery " +
              sample("bluemarble.tif").string() + " --max-zoom 3 -o out.mbtiles -j2 --resume",
          dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("continuing at zoom -1"), std::string::npos) << r.err;
  EXPECT_TRUE(same_bytes(dir / "work" / "out.mbtiles", dir / "ref" / "out.mbtiles"));
}

TEST(CrashSafety, ResumeRefusesAnotherBuildsTemporaryFile) {
  TempDir dir;
  const std::string cd = "cd " + dir.path().string() + " && ";
  const pid_t pid = spawn(dir.path(), terrain_build() + " -o out.mbtiles -q -j1 2>/dev/null");
  // Wait until the build has committed something, then kill it.
  for (int i = 0; i < 300 && !fs::exists(dir / "out.mbtiles.tmp"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  ASSERT_TRUE(fs::exists(dir / "out.mbtiles.tmp"));

  const RunResult other =
      run(cd + terrain_build() + " --precision 0.5 -o out.mbtiles --resume", dir.path());
  EXPECT_EQ(other.exit_code, 3) << other.err;
  EXPECT_NE(other.err.find("out.mbtiles.tmp"), std::string::npos) << other.err;
  EXPECT_NE(other.err.find("without --resume"), std::string::npos) << other.err;
  EXPECT_TRUE(fs::exists(dir / "out.mbtiles.tmp")) << "a refused resume must keep the file";
  EXPECT_FALSE(fs::exists(dir / "out.mbtiles"));

  // Without --resume, the stale file is replaced and the user told so.
  const RunResult fresh = run(cd + terrain_build() + " -o out.mbtiles", dir.path());
  EXPECT_EQ(fresh.exit_code, 0) << fresh.err;
  EXPECT_NE(fresh.err.find("left by an interrupted build"), std::string::npos) << fresh.err;
  expect_no_leftovers(dir.path(), "out.mbtiles");

  // --resume with nothing to resume starts a new build.
  const RunResult none = run(cd + terrain_build() + " -o new.mbtiles --resume", dir.path());
  EXPECT_EQ(none.exit_code, 0) << none.err;
  EXPECT_NE(none.err.find("nothing to resume"), std::string::npos) << none.err;
}

// An injected write failure: RLIMIT_FSIZE makes writes past the limit fail
// (EFBIG; SIGXFSZ ignored), like a disk that fills up during the build.
TEST(DiskFull, WriteFailureIsAClearErrorAndLeavesNothing) {
  TempDir dir;
  const std::string limit = "cd " + dir.path().string() + " && trap '' XFSZ && ulimit -f 1024 && ";
  for (const std::string& build : {terrain_build(), lines_build()}) {
    const RunResult r = run(limit + build + " -o out.mbtiles -q", dir.path());
    EXPECT_EQ(r.exit_code, 3) << build << "\n" << r.err;
    EXPECT_NE(r.err.find("out.mbtiles"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("check free space"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nothing was written to out.mbtiles"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.mbtiles"));
    expect_no_leftovers(dir.path(), "out.mbtiles");
  }
}

// A real full file system: a 2 MiB tmpfs (needs the right to mount; CI runs
// as root, elsewhere the test is skipped and the injected failure above
// stands in).
TEST(DiskFull, FullFileSystemIsAClearErrorAndLeavesNothing) {
  TempDir dir;
  const fs::path mnt = dir / "small";
  fs::create_directories(mnt);
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=2m") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (not root?)";
  for (const std::string& build : {terrain_build(), lines_build()}) {
    const RunResult r =
        run("cd " + mnt.string() + " && " + build + " -o out.mbtiles -q", dir.path());
    EXPECT_EQ(r.exit_code, 3) << build << "\n" << r.err;
    EXPECT_TRUE(r.err.find("disk is full") != std::string::npos ||
                r.err.find("No space left on device") != std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("nothing was written to out.mbtiles"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(mnt / "out.mbtiles"));
    expect_no_leftovers(mnt, "out.mbtiles");
  }
  ::umount(mnt.c_str());
}

// The viewer flies over a package while another process keeps replacing the
// file (the other of two packages written next to it, then renamed over it).
// The viewer reads the file it opened: the picture is exactly that of one of
// the two packages viewed alone, no tile of the other one, no crash.
TEST(ViewerRobustness, PackageReplacedWhileReadingIsNeverTorn) {
  TempDir dir;
  const std::string dem = sample("jacksboro.tif").string();
  const fs::path a = dir / "a.mbtiles", b = dir / "b.mbtiles", live = dir / "live.mbtiles";
  ASSERT_EQ(run(tiler() + " terrain " + dem + " -o " + a.string() + " -q", dir.path()).exit_code,
            0);
  // Another block size: any tile of b read as a's is a decoding error.
  ASSERT_EQ(
      run(tiler() + " terrain " + dem + " --block-size 65 -o " + b.string() + " -q", dir.path())
          .exit_code,
      0);
  {
    std::ofstream flight(dir / "flight.txt");
    for (int i = 0; i <= 24; ++i)
      flight << -84.42 + i * 0.015 << "," << 36.45 + i * 0.01 << ",900," << i * 15 << ",60\n";
  }
  const std::string view = viewer() + " " + live.string() +
                           " --size 320x180 --cache-mb 4 --snapshot %s --camera-path " +
                           (dir / "flight.txt").string();
  auto view_to = [&](const std::string& png) {
    std::string cmd = view;
    cmd.replace(cmd.find("%s"), 2, (dir / png).string());
    return cmd;
  };
  for (const fs::path& p : {a, b}) {
    fs::copy_file(p, live, fs::copy_options::overwrite_existing);
    const RunResult quiet = run(view_to(p.stem().string() + ".png"), dir.path());
    ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  }

  std::atomic<bool> done{false};
  int replacements = 0;
  std::thread replacer([&] {
    for (int i = 0; !done; ++i) {
      const fs::path next = dir / "next.mbtiles";
      fs::copy_file(i % 2 ? a : b, next, fs::copy_options::overwrite_existing);
      fs::rename(next, live);
      ++replacements;
    }
  });
  const RunResult busy = run(view_to("busy.png"), dir.path());
  done = true;
  replacer.join();
  ASSERT_EQ(busy.exit_code, 0) << busy.err;
  EXPECT_EQ(busy.err.find("warning"), std::string::npos) << busy.err;
  EXPECT_GT(replacements, 10);
  int w, h;
  const auto picture = read_rgb((dir / "busy.png").string(), w, h);
  EXPECT_TRUE(picture == read_rgb((dir / "a.png").string(), w, h) ||
              picture == read_rgb((dir / "b.png").string(), w, h))
      << "the picture mixes the packages (" << replacements << " replacements)";
}
