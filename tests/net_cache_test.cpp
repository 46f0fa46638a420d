// DiskCache (lib/net): entries kept and found, least-recently-used eviction,
// a byte cap that holds for the bodies and for the file on disk, reopening,
// two connections sharing one file, the file's SQLite settings read from its
// header; and the HTTP caching rules of net/cache_policy.hpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "net/cache_policy.hpp"
#include "net/disk_cache.hpp"
#include "net/http_client.hpp"
#include "test_support.hpp"

namespace {

using namespace globe::net;
using globe_test::TempDir;
namespace fs = std::filesystem;

CacheEntry entry_of(size_t size, char fill = 'x', const std::string& etag = "") {
  CacheEntry e;
  e.body.assign(size, static_cast<uint8_t>(fill));
  e.content_type = "image/png";
  e.etag = etag;
  e.stored_at = 1000;
  e.expires_at = 2000;
  return e;
}

// SQLite's page size, from the file's header (bytes 16-17, big-endian; 1 is 65536).
uint64_t page_size(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  unsigned char header[100] = {};
  in.read(reinterpret_cast<char*>(header), sizeof header);
  const uint64_t p = (uint64_t{header[16]} << 8) | header[17];
  return p == 1 ? 65536 : p;
}

TEST(NetCache, PutFindRefreshErase) {
  TempDir dir;
  DiskCache cache((dir / "c").string(), 1 << 20);
  EXPECT_EQ(cache.path(), (dir / "c" / "http-cache.sqlite").string());
  EXPECT_FALSE(cache.find("http://a/1").has_value());
  CacheEntry e = entry_of(3, 'a', "\"e1\"");
  e.last_modified = "Tue, 15 Nov 1994 12:45:26 GMT";
  cache.put("http://a/1", e);
  auto got = cache.find("http://a/1");
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->body, e.body);
  EXPECT_EQ(got->content_type, "image/png");
  EXPECT_EQ(got->etag, "\"e1\"");
  EXPECT_EQ(got->last_modified, e.last_modified);
  EXPECT_EQ(got->stored_at, 1000);
  EXPECT_EQ(got->expires_at, 2000);
  EXPECT_EQ(cache.entries(), 1u);
  EXPECT_EQ(cache.body_bytes(), 3u);

  cache.refresh("http://a/1", 5000, "", "");  // no new validators: the old ones stay
  got = cache.find("http://a/1");
  EXPECT_EQ(got->expires_at, 5000);
  EXPECT_EQ(got->etag, "\"e1\"");
  cache.refresh("http://a/1", 6000, "\"e2\"", "Wed, 16 Nov 1994 12:45:26 GMT");
  got = cache.find("http://a/1");
  EXPECT_EQ(got->expires_at, 6000);
  EXPECT_EQ(got->etag, "\"e2\"");
  EXPECT_EQ(got->last_modified, "Wed, 16 Nov 1994 12:45:26 GMT");
  EXPECT_EQ(got->body, e.body);

  cache.put("http://a/1", entry_of(7, 'b'));  // replaced
  EXPECT_EQ(cache.find("http://a/1")->body, std::vector<uint8_t>(7, 'b'));
  EXPECT_EQ(cache.body_bytes(), 7u);
  cache.put("http://a/empty", entry_of(0));
  ASSERT_TRUE(cache.find("http://a/empty").has_value());
  EXPECT_TRUE(cache.find("http://a/empty")->body.empty());

  cache.erase("http://a/1");
  EXPECT_FALSE(cache.find("http://a/1").has_value());
  cache.erase("http://a/never");  // no effect
  EXPECT_EQ(cache.entries(), 1u);
}

TEST(NetCache, EvictsTheLeastRecentlyUsedFirst) {
  TempDir dir;
  DiskCache cache(dir.path().string(), 3000);
  cache.put("a", entry_of(1000));
  cache.put("b", entry_of(1000));
  cache.put("c", entry_of(1000));
  ASSERT_TRUE(cache.find("a").has_value());  // a is now newer than b and c
  cache.put("d", entry_of(1000));
  EXPECT_FALSE(cache.find("b").has_value());
  EXPECT_TRUE(cache.find("a").has_value());
  EXPECT_TRUE(cache.find("c").has_value());
  EXPECT_TRUE(cache.find("d").has_value());
  // Order of use now: a, c, d. Two more to fit: a and c go.
  cache.put("e", entry_of(2000));
  EXPECT_FALSE(cache.find("a").has_value());
  EXPECT_FALSE(cache.find("c").has_value());
  EXPECT_TRUE(cache.find("d").has_value());
  EXPECT_TRUE(cache.find("e").has_value());
  EXPECT_LE(cache.body_bytes(), 3000u);
}

TEST(NetCache, AnEntryLargerThanTheCapIsNotKept) {
  TempDir dir;
  DiskCache cache(dir.path().string(), 100);
  cache.put("big", entry_of(50));
  cache.put("big", entry_of(101));
  EXPECT_FALSE(cache.find("big").has_value());
  EXPECT_EQ(cache.entries(), 0u);
}

TEST(NetCache, ByteCapHoldsAndTheFileShrinks) {
  TempDir dir;
  const uint64_t big_cap = 1 << 20, small_cap = 128 << 10, size = 40000;
  const fs::path file = dir / "http-cache.sqlite";
  {
    DiskCache cache(dir.path().string(), big_cap);
    for (int i = 0; i < 30; ++i)  // 1.2 MB: the first ones are evicted
      cache.put("k" + std::to_string(i), entry_of(size, static_cast<char>('a' + i % 26)));
    EXPECT_LE(cache.body_bytes(), big_cap);
    EXPECT_GT(cache.body_bytes(), big_cap - size);
    EXPECT_FALSE(cache.find("k0").has_value());
    EXPECT_TRUE(cache.find("k29").has_value());
  }
  const uint64_t full = fs::file_size(file);
  EXPECT_GT(full, big_cap - size);
  {
    DiskCache cache(dir.path().string(), small_cap);  // a smaller cap applies at once
    EXPECT_LE(cache.body_bytes(), small_cap);
    EXPECT_TRUE(cache.find("k29").has_value());  // the newest stayed
    for (int i = 0; i < 20; ++i)
      cache.put("n" + std::to_string(i), entry_of(7000, 'z'));
    EXPECT_LE(cache.body_bytes(), small_cap);
    EXPECT_GT(cache.body_bytes(), small_cap - 7000);
    EXPECT_TRUE(cache.find("n19").has_value());
    EXPECT_FALSE(cache.find("k29").has_value());
  }
  const uint64_t after = fs::file_size(file);
  EXPECT_LT(after, full / 4);
  // Each body wastes at most a page's tail (9 pages over the cap, measured, for these
  // 18 bodies of 7000 bytes); the schema, the index and the pointer map a few more.
  const uint64_t page = page_size(file);
  EXPECT_LE(after, small_cap + 16 * page) << "pages of " << page << " bytes";
}

TEST(NetCache, SurvivesReopening) {
  TempDir dir;
  {
    DiskCache cache(dir.path().string(), 1 << 20);
    cache.put("http://x/1", entry_of(10, 'q', "\"tag\""));
    cache.put("http://x/2", entry_of(20));
  }
  DiskCache again(dir.path().string(), 1 << 20);
  EXPECT_EQ(again.entries(), 2u);
  EXPECT_EQ(again.body_bytes(), 30u);
  const auto got = again.find("http://x/1");
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->etag, "\"tag\"");
  EXPECT_EQ(got->body, std::vector<uint8_t>(10, 'q'));
}

TEST(NetCache, TwoConnectionsShareOneFile) {
  TempDir dir;
  const uint64_t cap = 30000;
  DiskCache one(dir.path().string(), cap), two(dir.path().string(), cap);
  for (int i = 0; i < 24; ++i) {
    DiskCache& writer = i % 2 ? two : one;
    DiskCache& reader = i % 2 ? one : two;
    const std::string key = "k" + std::to_string(i);
    writer.put(key, entry_of(3000, static_cast<char>('a' + i % 26)));
    const auto seen = reader.find(key);
    ASSERT_TRUE(seen.has_value()) << key;
    EXPECT_EQ(seen->body.size(), 3000u);
    // Each connection counts the other's entries: the cap holds over both.
    EXPECT_LE(one.body_bytes(), cap);
    EXPECT_EQ(one.body_bytes(), two.body_bytes());
  }
  EXPECT_EQ(one.entries(), cap / 3000);
}

TEST(NetCache, FileUsesIncrementalVacuumAndARollbackJournal) {
  TempDir dir;
  { DiskCache cache(dir.path().string(), 1000); }
  std::ifstream in(dir / "http-cache.sqlite", std::ios::binary);
  unsigned char header[100] = {};
  in.read(reinterpret_cast<char*>(header), sizeof header);
  ASSERT_EQ(std::string(reinterpret_cast<char*>(header), 15), "SQLite format 3");
  EXPECT_EQ(header[18], 1) << "write version 1: rollback journal, not WAL";
  EXPECT_EQ(header[19], 1) << "read version 1: rollback journal, not WAL";
  EXPECT_NE(header[55], 0) << "auto-vacuum: a largest root page is recorded";
  EXPECT_EQ(header[67], 1) << "incremental-vacuum flag";
  EXPECT_FALSE(fs::exists(dir / "http-cache.sqlite-wal"));
}

TEST(NetCache, UnusableFolderThrowsNamingTheFile) {
  TempDir dir;
  std::ofstream(dir / "plain-file") << "not a folder";
  const std::string folder = (dir / "plain-file" / "cache").string();
  try {
    DiskCache cache(folder, 1000);
    FAIL() << "no error";
  } catch (const NetError& e) {
    EXPECT_NE(std::string(e.what()).find(folder), std::string::npos) << e.what();
  }
  // Not a database: an error naming the file, not a crash.
  std::ofstream(dir / "http-cache.sqlite") << std::string(4096, 'j');
  try {
    DiskCache cache(dir.path().string(), 1000);
    FAIL() << "no error";
  } catch (const NetError& e) {
    EXPECT_NE(std::string(e.what()).find("http-cache.sqlite"), std::string::npos) << e.what();
  }
}

TEST(NetCache, ClientThrowsOnAnUnusableCacheFolder) {
  TempDir dir;
  std::ofstream(dir / "plain-file") << "x";
  ClientOptions o;
  o.cache_dir = (dir / "plain-file").string();
  EXPECT_THROW(HttpClient client(o), NetError);
}

// ----- the rules of net/cache_policy.hpp -----

TEST(CachePolicy, CacheControl) {
  CacheControl cc = parse_cache_control("public, Max-Age=60");
  ASSERT_TRUE(cc.max_age.has_value());
  EXPECT_EQ(*cc.max_age, 60);
  EXPECT_FALSE(cc.no_store);
  EXPECT_FALSE(cc.no_cache);
  cc = parse_cache_control("no-store");
  EXPECT_TRUE(cc.no_store);
  cc = parse_cache_control(" no-cache , max-age=\"5\"");
  EXPECT_TRUE(cc.no_cache);
  EXPECT_EQ(cc.max_age.value_or(-1), 5);
  EXPECT_FALSE(parse_cache_control("max-age=-3").max_age.has_value());
  EXPECT_FALSE(parse_cache_control("max-age=soon").max_age.has_value());
  EXPECT_FALSE(parse_cache_control("s-maxage=60").max_age.has_value());
  EXPECT_EQ(parse_cache_control("max-age=99999999999999999999999").max_age.value_or(0), INT64_MAX);
  EXPECT_FALSE(parse_cache_control("").max_age.has_value());
}

TEST(CachePolicy, HttpDatesInAllThreeForms) {
  constexpr int64_t k1994 = 784111777;  // Sun, 06 Nov 1994 08:49:37 GMT
  EXPECT_EQ(parse_http_date("Sun, 06 Nov 1994 08:49:37 GMT"), k1994);
  EXPECT_EQ(parse_http_date("Sunday, 06-Nov-94 08:49:37 GMT"), k1994);
  EXPECT_EQ(parse_http_date("Sun Nov  6 08:49:37 1994"), k1994);
  EXPECT_EQ(parse_http_date("Thu, 01 Jan 1970 00:00:00 GMT"), 0);
  EXPECT_EQ(parse_http_date("Tue, 29 Feb 2028 23:59:59 GMT"), 1835481599);
  EXPECT_FALSE(parse_http_date("").has_value());
  EXPECT_FALSE(parse_http_date("0").has_value());
  EXPECT_FALSE(parse_http_date("Sun, 06 Nov 1994 25:49:37 GMT").has_value());
  EXPECT_FALSE(parse_http_date("Sun, 06 Foo 1994 08:49:37 GMT").has_value());
  EXPECT_FALSE(parse_http_date("Sun, 06 Nov 1994 08:49:37 CET").has_value());
}

TEST(CachePolicy, Freshness) {
  const int64_t now = 1'700'000'000;
  EXPECT_EQ(expires_at({"max-age=60", "", "", ""}, now), now + 60);
  EXPECT_EQ(expires_at({"max-age=60", "", "", "20"}, now), now + 40);
  EXPECT_EQ(expires_at({"max-age=60", "", "", "90"}, now), 0);
  EXPECT_EQ(expires_at({"max-age=0", "", "", ""}, now), 0);
  EXPECT_EQ(expires_at({"no-cache, max-age=60", "", "", ""}, now), 0);
  // max-age wins over Expires.
  EXPECT_EQ(expires_at({"max-age=10", "Thu, 01 Jan 2099 00:00:00 GMT", "", ""}, now), now + 10);
  // Expires relative to the server's Date: its clock error cancels out.
  EXPECT_EQ(
      expires_at({"", "Sun, 06 Nov 1994 09:49:37 GMT", "Sun, 06 Nov 1994 08:49:37 GMT", ""}, now),
      now + 3600);
  EXPECT_EQ(expires_at({"", "Thu, 01 Jan 2099 00:00:00 GMT", "", ""}, now), 4070908800);
  EXPECT_EQ(expires_at({"", "Sun, 06 Nov 1994 08:49:37 GMT", "", ""}, now), 0);  // past
  EXPECT_EQ(expires_at({"", "0", "", ""}, now), 0);                              // invalid
  EXPECT_EQ(expires_at({"", "", "", ""}, now), 0);
}

TEST(CachePolicy, RetryAfter) {
  const int64_t now = 784111777;
  EXPECT_EQ(retry_after_s("1", now), 1.0);
  EXPECT_EQ(retry_after_s(" 120 ", now), 120.0);
  EXPECT_EQ(retry_after_s("Sun, 06 Nov 1994 08:50:07 GMT", now), 30.0);
  EXPECT_EQ(retry_after_s("Sun, 06 Nov 1994 08:00:00 GMT", now), 0.0);  // passed
  EXPECT_FALSE(retry_after_s("", now).has_value());
  EXPECT_FALSE(retry_after_s("-1", now).has_value());
  EXPECT_FALSE(retry_after_s("soon", now).has_value());
}

TEST(CachePolicy, ContentTypesAndKeys) {
  EXPECT_TRUE(content_type_accepted("image/png", {"image/"}));
  EXPECT_TRUE(content_type_accepted("Application/JSON; charset=utf-8", {"application/json"}));
  EXPECT_TRUE(content_type_accepted("", {}));
  EXPECT_FALSE(content_type_accepted("", {"image/"}));
  EXPECT_FALSE(content_type_accepted("text/html", {"image/", "application/octet-stream"}));
  EXPECT_EQ(cache_key("https://h/t.pmtiles", ""), "https://h/t.pmtiles");
  EXPECT_EQ(cache_key("https://h/t.pmtiles", "bytes=0-16383"), "https://h/t.pmtiles#range=0-16383");
}

}  // namespace
