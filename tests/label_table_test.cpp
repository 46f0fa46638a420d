// The labels table (tileformat/label_table.hpp): rows come back as written,
// in id order, with a line's path exact to the bit; a resumed build finds
// the committed table complete; a path that is not whole lon/lat pairs is a
// format error naming the file.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_support.hpp"
#include "tileformat/error.hpp"
#include "tileformat/label_table.hpp"
#include "tileformat/package.hpp"

namespace tileformat {
struct PackageTestAccess {
  static SqliteDb& db(PackageWriter& w) { return w.db(); }
};
}  // namespace tileformat

using globe_test::TempDir;
using tileformat::LabelPlacement;
using tileformat::LabelRecord;

TEST(LabelTable, RoundTripsEveryField) {
  TempDir dir;
  const auto path = (dir / "l.mbtiles").string();
  std::vector<LabelRecord> in(3);
  in[0] = {0, 7, "Zürich", 1.5e6, 8.5417, 47.3769, LabelPlacement::kPoint, {}};
  in[1] = {0, 9, "القاهرة", 2.0, 31.2357, 30.0444, LabelPlacement::kArea, {}};
  in[2] = {0,
           12,
           "R464",
           0.25,
           -155.8,
           23.0,
           LabelPlacement::kLine,
           {-156.170961, 22.528056, -155.478836, 23.528031, 179.999999999, -0.1}};
  {
    tileformat::PackageWriter w(path, tileformat::IfExists::kFail);
    {  // the statement goes before the commit closes the database
      tileformat::LabelTableWriter labels(w);
      EXPECT_FALSE(labels.complete());
      for (const LabelRecord& r : in)
        labels.add(r);
      EXPECT_EQ(labels.count(), 3);
    }
    w.put_tile({0, 0, 0}, std::vector<uint8_t>{1});
    w.set_metadata("format", "application/vnd.globe.lines");
    w.commit();
  }
  tileformat::PackageReader r(path);
  ASSERT_TRUE(tileformat::has_labels(r));
  tileformat::LabelTableReader table(r);
  EXPECT_EQ(table.count(), 3);
  std::vector<LabelRecord> out;
  table.for_each([&](const LabelRecord& l) { out.push_back(l); });
  ASSERT_EQ(out.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(out[i].id, int64_t(i + 1));
    EXPECT_EQ(out[i].feature, in[i].feature);
    EXPECT_EQ(out[i].text, in[i].text);
    EXPECT_EQ(out[i].priority, in[i].priority);
    EXPECT_EQ(out[i].lon, in[i].lon);
    EXPECT_EQ(out[i].lat, in[i].lat);
    EXPECT_EQ(out[i].placement, in[i].placement);
    EXPECT_EQ(out[i].path, in[i].path);  // bit for bit
  }
}

TEST(LabelTable, PackagesWithoutOneSayHowToGetOne) {
  TempDir dir;
  const auto path = (dir / "n.mbtiles").string();
  {
    tileformat::PackageWriter w(path, tileformat::IfExists::kFail);
    w.put_tile({0, 0, 0}, std::vector<uint8_t>{1});
    w.commit();
  }
  tileformat::PackageReader r(path);
  EXPECT_FALSE(tileformat::has_labels(r));
  try {
    tileformat::LabelTableReader table(r);
    FAIL() << "no error";
  } catch (const tileformat::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("--label-field"), std::string::npos) << e.what();
  }
}

TEST(LabelTable, BrokenPathIsAFormatErrorNamingTheFile) {
  TempDir dir;
  const auto path = (dir / "b.mbtiles").string();
  {
    tileformat::PackageWriter w(path, tileformat::IfExists::kFail);
    tileformat::LabelTableWriter(w).add({0, 1, "x", 0, 0, 0, LabelPlacement::kLine, {1, 2, 3, 4}});
    tileformat::PackageTestAccess::db(w).exec("UPDATE labels SET path = x'0102030405'");
    w.put_tile({0, 0, 0}, std::vector<uint8_t>{1});
    w.commit();
  }
  tileformat::PackageReader r(path);
  try {
    tileformat::LabelTableReader(r).for_each([](const LabelRecord&) {});
    FAIL() << "no error";
  } catch (const tileformat::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("b.mbtiles"), std::string::npos) << e.what();
  }
}

TEST(LabelTable, AResumedBuildFindsTheCommittedTableComplete) {
  TempDir dir;
  const auto path = (dir / "r.mbtiles").string();
  // A child writes the table, commits it with a checkpoint and dies.
  const pid_t pid = ::fork();
  if (pid == 0) {
    tileformat::PackageWriter w(path, tileformat::IfExists::kFail, "key",
                                tileformat::Resume::kStartAfresh);
    tileformat::LabelTableWriter labels(w);
    labels.add({0, 1, "a", 0, 0, 0, LabelPlacement::kPoint, {}});
    labels.add({0, 2, "b", 0, 0, 0, LabelPlacement::kPoint, {}});
    w.checkpoint();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  tileformat::PackageWriter w(path, tileformat::IfExists::kFail, "key",
                              tileformat::Resume::kContinue);
  ASSERT_TRUE(w.resumed());
  tileformat::LabelTableWriter labels(w);
  EXPECT_TRUE(labels.complete());
  EXPECT_EQ(labels.count(), 2);
}
