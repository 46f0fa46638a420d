// URLs as TileJSON and layer.json use them: a tile template relative to the
// document that names it ("tiles/{z}/{x}/{y}.png", "/x/{z}.png",
// "//host/x.png") resolved against the document's URL (RFC 3986 §5.2, for
// the forms such documents hold; the base's query and fragment dropped).
// Template braces are kept as they are.
#pragma once

#include <string>

namespace globe::net {

std::string resolve_url(const std::string& base, const std::string& reference);

// `url_template` with every `placeholder` ("{z}", "{-y}", "{version}") replaced
// by `value`: one step of filling a tile URL template.
std::string fill_placeholder(std::string url_template, const std::string& placeholder,
                             const std::string& value);

}  // namespace globe::net
