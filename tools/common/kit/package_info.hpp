// The part of `info` every package kind shares: file size, metadata (long
// values shortened) and the per-zoom tile table, printed on stdout; or the
// same as a JSON object (`info --json`, full metadata values) to which each
// kind adds its own section (docs/cli.md "info --json").
#pragma once

#include <string>

#include "kit/info_json.hpp"
#include "tileformat/package.hpp"
#include "tileformat/package_kinds.hpp"

namespace globe {

void print_package_info(tileformat::PackageReader& reader, const std::string& path);
// "kind" is the kind's info_key ("terrain", "image", "analysis", "lines" or
// "points").
InfoJson package_info_json(tileformat::PackageReader& reader, const std::string& path,
                           tileformat::PackageKind kind);
// Writes `info` on stdout with a newline.
void print_info_json(const InfoJson& info);
// print_info_json of package_info_json with the kind's own section (under
// its info_key) added.
void print_kind_info_json(tileformat::PackageReader& reader, const std::string& path,
                          tileformat::PackageKind kind, const InfoJson& section);

}  // namespace globe
