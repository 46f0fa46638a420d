// Relative tile URLs as TileJSON and layer.json hold them, resolved against
// the document's URL (lib/net/include/net/url.hpp; RFC 3986 §5.4's examples
// for the forms such documents use).
#include <gtest/gtest.h>

#include "net/url.hpp"

using globe::net::resolve_url;

TEST(NetUrl, RelativeTemplatesResolveAgainstTheDocument) {
  const std::string base = "http://a.example:8080/b/c/layer.json?v=1";
  EXPECT_EQ(resolve_url(base, "{z}/{x}/{y}.terrain?v={version}"),
            "http://a.example:8080/b/c/{z}/{x}/{y}.terrain?v={version}");
  EXPECT_EQ(resolve_url(base, "/t/{z}.png"), "http://a.example:8080/t/{z}.png");
  EXPECT_EQ(resolve_url(base, "//cdn.example/x.png"), "http://cdn.example/x.png");
  EXPECT_EQ(resolve_url(base, "https://o.example/{z}.png"), "https://o.example/{z}.png");
  EXPECT_EQ(resolve_url(base, "../d/{z}.png"), "http://a.example:8080/b/d/{z}.png");
  EXPECT_EQ(resolve_url(base, "./e.png"), "http://a.example:8080/b/c/e.png");
  EXPECT_EQ(resolve_url("http://h/x.json", "t/{z}.png"), "http://h/t/{z}.png");
  EXPECT_EQ(resolve_url("http://h", "t.png"), "http://h/t.png");
  EXPECT_EQ(resolve_url("http://h/a/b", "../../../t.png"), "http://h/t.png");
}
