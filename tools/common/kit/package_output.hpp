// Creating and committing the package a build writes, with package errors
// turned into OutputError (exit code 3: exists, unwritable, disk full).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "runtime/errors.hpp"
#include "tileformat/error.hpp"
#include "tileformat/package.hpp"

namespace globe {

struct BuildOptions;
class Progress;

// Throws OutputError naming `output` when the folder it goes in does not
// exist or is not a folder (SQLite would only say "unable to open database
// file").
void check_output_folder(const std::string& output);

// The writer for o.output. Throws OutputError if it exists and !o.force, or
// cannot be created, or o.resume finds an unfinished build it cannot
// continue. Notes on `progress` when it continues one or removes a stale one.
std::unique_ptr<tileformat::PackageWriter> create_package(const BuildOptions& o,
                                                          Progress& progress);
// The OutputError for a write that failed while building `output` (disk
// full, folder removed): says what failed and that nothing was written under
// the final name (the temporary files are removed as the build unwinds).
OutputError build_write_error(const std::string& output, const std::exception& e);

// Runs `write` (a build's or merge's tile writing), turning a failed write of
// the package or of scratch files (PackageError, OutputError) into
// build_write_error(output): only outputs are written there, so a failure
// is an output problem (disk full, folder removed), not bad input.
template <class Write>
void write_package_tiles(const std::string& output, Write&& write) {
  try {
    write();
  } catch (const tileformat::PackageError& e) {
    throw build_write_error(output, e);
  } catch (const OutputError& e) {
    throw build_write_error(output, e);
  }
}

// What every build and merge says of the package it wrote; each command's
// summary derives from it and adds its own counts.
struct PackageSummary {
  uint64_t tiles = 0, unique_blobs = 0, blob_bytes = 0, file_bytes = 0;
  double seconds = 0;  // the whole build
};

// Commits (renames to the final name) and fills `sum`'s PackageSummary part:
// the writer's tiles, unique blobs and their bytes, the final file's size
// and the seconds since `start`.
void commit_package(tileformat::PackageWriter& writer, const std::string& path,
                    std::chrono::steady_clock::time_point start, PackageSummary& sum);

}  // namespace globe
