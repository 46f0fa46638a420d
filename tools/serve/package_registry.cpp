// Packages by name, reopened when replaced (see package_registry.hpp).
#include "serve/package_registry.hpp"

#include <sys/stat.h>

#include <filesystem>

#include "runtime/errors.hpp"

namespace globe::serve {

bool PackageRegistry::stamp_of(const std::string& path, Stamp& out) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return false;
  out.dev = st.st_dev, out.ino = st.st_ino, out.size = st.st_size;
  out.mtime_ns = int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  return true;
}

PackageRegistry::PackageRegistry(const std::vector<std::string>& paths,
                                 const ServiceOptions& options)
    : options_(options) {
  for (const std::string& path : paths) {
    auto slot = std::make_unique<Slot>();
    slot->path = path;
    slot->name = std::filesystem::path(path).stem().string();
    for (const auto& other : slots_)
      if (other->name == slot->name)
        throw UsageError(path + " and " + other->path + " would both be served as /" + slot->name +
                         "; rename one");
    if (!stamp_of(path, slot->stamp)) throw InputError(path + ": no such file");
    slot->service = std::shared_ptr<PackageService>(open_service(path, slot->name, options_));
    slots_.push_back(std::move(slot));
  }
}

PackageRegistry::Found PackageRegistry::refreshed(Slot& slot) {
  std::lock_guard lock(slot.mutex);
  Stamp now;
  if (!stamp_of(slot.path, now))
    return {nullptr, 503, slot.path + " is gone from the disk; it is served again once it is back"};
  if (!(now == slot.stamp)) {
    try {
      slot.service = std::shared_ptr<PackageService>(open_service(slot.path, slot.name, options_));
      slot.stamp = now;
    } catch (const std::exception& e) {
      return {nullptr, 503,
              slot.path + " changed on disk and cannot be read (" + e.what() +
                  "); it is served again once it can"};
    }
  }
  return {slot.service, 200, ""};
}

PackageRegistry::Found PackageRegistry::find(const std::string& name) {
  for (const auto& slot : slots_)
    if (slot->name == name) return refreshed(*slot);
  return {nullptr, 404, "no package named " + name + " (see /)"};
}

std::vector<PackageRegistry::Listed> PackageRegistry::list() {
  std::vector<Listed> out;
  for (const auto& slot : slots_) {
    const Found f = refreshed(*slot);
    if (f.service) out.push_back({slot->name, f.service->kind(), f.service});
  }
  return out;
}

}  // namespace globe::serve
