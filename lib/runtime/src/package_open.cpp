// Opening packages for inspection (see package_open.hpp).
#include "runtime/package_open.hpp"

namespace globe {
namespace {

std::string article(const std::string& noun) {
  return (std::string("aeiou").find(noun[0]) != std::string::npos ? "an " : "a ") + noun;
}

RemoteOpener& remote_opener() {
  static RemoteOpener opener;
  return opener;
}

}  // namespace

bool is_url(const std::string& path) {
  return path.rfind("http://", 0) == 0 || path.rfind("https://", 0) == 0;
}

void set_remote_opener(RemoteOpener opener) {
  remote_opener() = std::move(opener);
}

std::unique_ptr<tileformat::TileReader> open_source(const std::string& path) {
  if (!is_url(path)) return open_package(path);
  if (!remote_opener())
    throw InputError(path + ": a URL, where this command reads package files (globe-view " +
                     "reads URLs; download the package first)");
  return remote_opener()(path);
}

tileformat::PackageReader& package_file(tileformat::TileReader& reader) {
  if (tileformat::PackageReader* p = reader.package()) return *p;
  throw InputError(reader.path() + ": a remote source, where this needs the package file");
}

std::string a_package_of(tileformat::PackageKind kind) {
  return article(tileformat::package_kind_name(kind)) + " package";
}

std::unique_ptr<tileformat::PackageReader> open_package(const std::string& path) {
  try {
    return std::make_unique<tileformat::PackageReader>(path);
  } catch (const tileformat::PackageError& e) {
    throw InputError(e.what());
  }
}

std::string package_format(const tileformat::TileReader& reader, const std::string& path) {
  const auto fmt = reader.meta("format");
  if (!fmt) throw InputError(path + ": metadata has no 'format'; not a globe package");
  return *fmt;
}

std::optional<tileformat::PackageKind> package_kind(const std::string& path) {
  return tileformat::package_kind_of_format(package_format(*open_source(path), path));
}

std::unique_ptr<tileformat::TileReader> open_package_of_kind(const std::string& path,
                                                             tileformat::PackageKind kind) {
  std::unique_ptr<tileformat::TileReader> reader = open_source(path);
  const std::string fmt = package_format(*reader, path);
  const std::optional<tileformat::PackageKind> actual = tileformat::package_kind_of_format(fmt);
  if (actual != kind) {
    const std::string is = actual ? a_package_of(*actual)
                                  : "a package of format '" + fmt + "', not made by these tools";
    throw InputError(path + ": " + is + ", where " + a_package_of(kind) + " is needed (made by " +
                     tileformat::describe(kind).maker + ")");
  }
  return reader;
}

}  // namespace globe
