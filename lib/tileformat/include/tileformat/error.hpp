// Typed errors of the tileformat library. Every decoding error names the
// section of docs/tileformat.md that the input violates, so a message such as
// "MBlock heights: truncated (tileformat §5.2)" points straight at the spec.
#pragma once

#include <stdexcept>
#include <string>

namespace tileformat {

// Bad bytes: a blob or package that does not follow docs/tileformat.md.
class FormatError : public std::runtime_error {
 public:
  FormatError(std::string section, const std::string& what)
      : std::runtime_error(what + " (tileformat §" + section + ")"), section_(std::move(section)) {}
  const std::string& section() const { return section_; }

 private:
  std::string section_;
};

// A package file that cannot be opened, read or written (I/O, SQLite).
class PackageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace tileformat
