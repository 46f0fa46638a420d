// Sharded terrain and line builds on a real Slurm cluster (label `cluster`): a single-node
// cluster from Debian's slurm-wlm and munge, started by the test in a
// temporary folder (scripts/slurm/local-cluster.sh) and stopped at the end.
// scripts/slurm/submit.sh submits the shards as an sbatch array job and the
// merge as a job that depends on it (afterok); the merged package must equal
// the one-machine build. A shard left out (as if it had failed) makes the
// merge fail with a clear error; resubmitting just that index gives the
// package. Needs root (slurmd runs the jobs).
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <thread>

#include "package_compare.hpp"
#include "test_paths.hpp"
#include "test_support.hpp"

using namespace globe_test;

namespace {

const std::string kScripts = globe_test::paths::source_dir() + "/scripts/slurm/";

class SlurmCluster : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(::geteuid(), 0u) << "the cluster tests start slurmd, which needs root";
    // A port of its own, so two test runs on one machine do not meet.
    const int port = 20000 + 2 * (::getpid() % 10000);
    env_ = "SLURM_CONF=" + (dir_ / "cluster" / "slurm.conf").string();
    const RunResult r = run("SLURM_PORT=" + std::to_string(port) + " " + kScripts +
                                "local-cluster.sh start " + (dir_ / "cluster").string(),
                            dir_.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    started_ = true;
  }
  void TearDown() override {
    if (started_)
      run(kScripts + "local-cluster.sh stop " + (dir_ / "cluster").string(), dir_.path());
  }

  // submit.sh with `options` for the build `command` (-o OUT included).
  RunResult submit(const std::string& options, const std::string& command) {
    return run(env_ + " " + kScripts + "submit.sh " + options + " -- " + command, dir_.path());
  }
  // Waits until job `id` has left the queue (up to 5 minutes); its state.
  std::string wait_for(const std::string& id) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    while (std::chrono::steady_clock::now() < deadline) {
      const RunResult q = run(env_ + " squeue -h -j " + id + " -o %T", dir_.path());
      if (q.exit_code == 0 && q.out.empty()) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    const RunResult s = run(env_ + " scontrol -o show job " + id, dir_.path());
    const size_t at = s.out.find("JobState=");
    return at == std::string::npos ? "GONE" : s.out.substr(at + 9, s.out.find(' ', at) - at - 9);
  }
  static std::string job(const std::string& submit_out, const std::string& which) {
    const size_t at = submit_out.find(which + " ");
    if (at == std::string::npos) return "";
    return submit_out.substr(at + which.size() + 1,
                             submit_out.find('\n', at) - at - which.size() - 1);
  }

  TempDir dir_;
  std::string env_;
  bool started_ = false;
};

}  // namespace

TEST_F(SlurmCluster, ArrayJobOfTerrainShardsAndADependentMergeGiveTheOneMachineBuild) {
  const std::string dem = sample("jacksboro.tif").string();
  const std::string out = (dir_ / "j.mbtiles").string();
  ASSERT_TRUE(build_terrain("", dem, (dir_ / "one.mbtiles").string(), dir_.path()));
  const RunResult s =
      submit("--shards 3", tiler() + " terrain " + dem + " --split-zoom 9 -o " + out);
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const std::string shards = job(s.out, "shards"), merge = job(s.out, "merge");
  ASSERT_FALSE(merge.empty()) << s.out;
  EXPECT_EQ(wait_for(merge), "COMPLETED") << read_file(dir_ / "j.shards" / "logs" / "merge.log");
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE(fs::exists(dir_ / "j.shards" / ("j.shard-" + std::to_string(i) + ".mbtiles")));
  ASSERT_TRUE(fs::exists(out)) << read_file(dir_ / "j.shards" / "logs" / "merge.log");
  expect_same_package(out, (dir_ / "one.mbtiles").string());
}

TEST_F(SlurmCluster, ArrayJobOfLineShardsAndADependentMergeGiveTheOneMachineBuild) {
  const std::string lines = sample("ne_admin1.shp").string() + " --max-zoom 5";
  const std::string out = (dir_ / "l.mbtiles").string();
  const RunResult one = run(
      vectorize() + " lines -q " + lines + " -o " + (dir_ / "one.mbtiles").string(), dir_.path());
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const RunResult s = submit("--shards 4", vectorize() + " lines " + lines + " -o " + out);
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const std::string merge = job(s.out, "merge");
  ASSERT_FALSE(merge.empty()) << s.out;
  EXPECT_EQ(wait_for(merge), "COMPLETED") << read_file(dir_ / "l.shards" / "logs" / "merge.log");
  ASSERT_TRUE(fs::exists(out)) << read_file(dir_ / "l.shards" / "logs" / "merge.log");
  expect_same_package(out, (dir_ / "one.mbtiles").string());
}

TEST_F(SlurmCluster, AMissingShardFailsTheMergeAndResubmittingItCompletesTheBuild) {
  const std::string dem = sample("brasilia.tif").string();
  const std::string out = (dir_ / "b.mbtiles").string();
  const std::string build = tiler() + " terrain " + dem + " --split-zoom 11 -o " + out;
  ASSERT_TRUE(build_terrain("", dem, (dir_ / "one.mbtiles").string(), dir_.path()));
  // Shard 1 of 3 never ran (as if its task had failed and been cancelled).
  const RunResult first = submit("--shards 3 --only 0,2", build);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(wait_for(job(first.out, "merge")), "FAILED");
  const std::string log = read_file(dir_ / "b.shards" / "logs" / "merge.log");
  EXPECT_NE(log.find("b.shard-1.mbtiles: no such file"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out));
  // Just that index again, and a new merge.
  const RunResult again = submit("--shards 3 --only 1", build);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(wait_for(job(again.out, "merge")), "COMPLETED")
      << read_file(dir_ / "b.shards" / "logs" / "merge.log");
  ASSERT_TRUE(fs::exists(out));
  expect_same_package(out, (dir_ / "one.mbtiles").string());
}
