// Opening an existing package of one kind for inspection: errors name the
// file and say what the package is instead (tileformat §3.2). The keys
// themselves are read by lib/tileformat (metadata.hpp).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/metadata.hpp"
#include "tileformat/package.hpp"

namespace globe {

// Throws InputError if `path` is missing or not a package.
std::unique_ptr<tileformat::PackageReader> open_package(const std::string& path);

// Sources: a package file, or a URL (http:// or https://) where a program has
// registered an opener for URLs (globe-view: viewer/data/remote_reader.hpp).
// lib/runtime itself never touches the network.
bool is_url(const std::string& path);
using RemoteOpener = std::function<std::unique_ptr<tileformat::TileReader>(const std::string& url)>;
void set_remote_opener(RemoteOpener opener);
// A URL through the registered opener (InputError without one: "this command
// reads package files"), else open_package.
std::unique_ptr<tileformat::TileReader> open_source(const std::string& path);
// The package file behind `reader`, for its other tables (features, labels,
// shards); throws InputError naming the URL for a remote source.
tileformat::PackageReader& package_file(tileformat::TileReader& reader);

// The package's `format` metadata value; throws InputError if it has none.
std::string package_format(const tileformat::TileReader& reader, const std::string& path);
// The kind of the package at `path` (nullopt: a format none of our kinds
// has); throws InputError if it is missing, not a package or has no format.
std::optional<tileformat::PackageKind> package_kind(const std::string& path);
// "a terrain package", "an analysis package": the kind in messages.
std::string a_package_of(tileformat::PackageKind kind);
// Throws InputError if `path` is missing, not a package, or not of `kind`
// (a URL: as open_source).
std::unique_ptr<tileformat::TileReader> open_package_of_kind(const std::string& path,
                                                             tileformat::PackageKind kind);

// read(): one of tileformat's read_*_metadata on the package at `path`; its
// FormatError becomes an InputError naming the file.
template <typename Read>
auto read_metadata(const std::string& path, Read read) -> decltype(read()) {
  try {
    return read();
  } catch (const tileformat::FormatError& e) {
    throw InputError(path + ": " + e.what());
  }
}

}  // namespace globe
