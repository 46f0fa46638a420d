// Creating and committing the package a build writes, with package errors
// turned into OutputError (exit code 3: exists, unwritable, disk full).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "tileformat/package.hpp"

namespace globe {

// Throws OutputError if `path` exists and !force, or cannot be created.
std::unique_ptr<tileformat::PackageWriter> create_package(const std::string& path, bool force);
// Commits (renames to the final name) and returns the final file's size.
uint64_t commit_package(tileformat::PackageWriter& writer, const std::string& path);

}  // namespace globe
