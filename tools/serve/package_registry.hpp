// The packages globe-serve was given, by name (file stem), each reopened when
// its file is replaced (a builder's rename): a request holds the service it
// started with, so it is never answered half from the old file and half from
// the new (docs/serve.md "Packages that change").
#pragma once

#include <sys/types.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "serve/package_services.hpp"

namespace globe::serve {

class PackageRegistry {
 public:
  // Opens every path; throws UsageError for two paths with the same stem and
  // InputError for one that cannot be served.
  PackageRegistry(const std::vector<std::string>& paths, const ServiceOptions& options);

  struct Found {
    std::shared_ptr<PackageService> service;  // nullptr: see `status` and `error`
    int status = 200;                         // 404 unknown name, 503 cannot be reopened
    std::string error;
  };
  Found find(const std::string& name);

  struct Listed {
    std::string name, kind;
    std::shared_ptr<PackageService> service;
  };
  std::vector<Listed> list();

 private:
  struct Stamp {
    dev_t dev = 0;
    ino_t ino = 0;
    off_t size = 0;
    int64_t mtime_ns = 0;
    bool operator==(const Stamp&) const = default;
  };
  struct Slot {
    std::string path, name;
    Stamp stamp;
    std::shared_ptr<PackageService> service;
    std::mutex mutex;
  };
  static bool stamp_of(const std::string& path, Stamp& out);
  Found refreshed(Slot& slot);

  ServiceOptions options_;
  std::vector<std::unique_ptr<Slot>> slots_;
};

}  // namespace globe::serve
