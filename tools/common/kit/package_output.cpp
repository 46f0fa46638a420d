// Package creation and commit (see package_output.hpp).
#include "kit/package_output.hpp"

#include <filesystem>

#include "kit/build_options.hpp"
#include "kit/progress.hpp"
#include "runtime/errors.hpp"
#include "tileformat/error.hpp"

namespace globe {

void check_output_folder(const std::string& output) {
  const std::filesystem::path folder = std::filesystem::path(output).parent_path();
  if (folder.empty()) return;  // the current folder
  std::error_code ec;
  if (!std::filesystem::exists(folder, ec))
    throw OutputError(output + ": the folder " + folder.string() +
                      " does not exist; create it (mkdir -p " + folder.string() +
                      ") or choose another -o");
  if (!std::filesystem::is_directory(folder, ec))
    throw OutputError(output + ": " + folder.string() + " is not a folder; choose another -o");
}

std::unique_ptr<tileformat::PackageWriter> create_package(const BuildOptions& o,
                                                          Progress& progress) {
  check_output_folder(o.output);
  std::error_code ec;
  const bool stale = std::filesystem::exists(o.output + ".tmp", ec);
  std::unique_ptr<tileformat::PackageWriter> w;
  try {
    w = std::make_unique<tileformat::PackageWriter>(
        o.output, o.force ? tileformat::IfExists::kOverwrite : tileformat::IfExists::kFail,
        build_key(o), o.resume ? tileformat::Resume::kContinue : tileformat::Resume::kStartAfresh);
  } catch (const tileformat::PackageError& e) {
    throw OutputError(e.what());
  }
  if (w->resumed())
    progress.note("resuming " + o.output + ".tmp: " + std::to_string(w->tiles_written()) +
                  " tiles were committed before the interruption");
  else if (o.resume)
    progress.note("nothing to resume for " + o.output + "; starting a new build");
  else if (stale)
    progress.note("removed " + o.output +
                  ".tmp left by an interrupted build (pass --resume to continue it)");
  return w;
}

OutputError build_write_error(const std::string& output, const std::exception& e) {
  std::string what = e.what();
  if (what.find("check free space") == std::string::npos)
    what += "; check free space and permissions";
  return OutputError(what + " (nothing was written to " + output + ")");
}

void commit_package(tileformat::PackageWriter& writer, const std::string& path,
                    std::chrono::steady_clock::time_point start, PackageSummary& sum) {
  try {
    writer.commit();
  } catch (const tileformat::PackageError& e) {
    throw OutputError(e.what());
  }
  sum.tiles = writer.tiles_written();
  sum.unique_blobs = writer.unique_blobs();
  sum.blob_bytes = writer.blob_bytes();
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  sum.file_bytes = ec ? 0 : bytes;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace globe
