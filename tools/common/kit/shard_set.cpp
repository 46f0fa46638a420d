// Shard sets (see shard_set.hpp).
#include "shard_set.hpp"

#include <algorithm>
#include <filesystem>

#include "errors.hpp"
#include "package_open.hpp"
#include "tileformat/metadata.hpp"

namespace globe {

using tileformat::TileId;

namespace {

std::string shard_name(int index, int count) {
  return std::to_string(index) + "/" + std::to_string(count);
}

}  // namespace

ShardSet::ShardSet(const std::vector<std::string>& paths) {
  if (paths.empty()) throw UsageError("no shards given");
  std::vector<Shard> given;
  std::vector<tileformat::ShardMetadata> metas;
  for (const std::string& path : paths) {
    Shard s{path, open_package(path), nullptr};
    const auto kind = package_kind(path);
    const auto meta =
        read_metadata(path, [&] { return tileformat::read_shard_metadata(s.reader->metadata()); });
    if (!meta || !kind)
      throw InputError(path +
                       ": not a shard (no globe:shard metadata); merge joins the packages built "
                       "with --shard I/N");
    if (given.empty()) {
      meta_ = *meta;
      kind_ = *kind;
    } else {
      const std::string& first = given.front().path;
      if (meta->build != meta_.build || *kind != kind_)
        throw InputError(path + ": shard " + shard_name(meta->index, meta->count) +
                         " of another build than " + first + " (globe:shard_build " + meta->build +
                         " vs " + meta_.build +
                         "); shards must come from the same command, inputs and options");
      if (meta->count != meta_.count || meta->split_zoom != meta_.split_zoom ||
          meta->roots != meta_.roots)
        throw InputError(path + " is shard " + shard_name(meta->index, meta->count) +
                         " below zoom " + std::to_string(meta->split_zoom) + " but " + first +
                         " is shard " + shard_name(meta_.index, meta_.count) + " below zoom " +
                         std::to_string(meta_.split_zoom) + "; shards of one build only");
    }
    s.table = std::make_unique<tileformat::ShardTableReader>(*s.reader);
    metas.push_back(*meta);
    given.push_back(std::move(s));
  }
  shards_.resize(static_cast<size_t>(meta_.count));
  for (size_t k = 0; k < given.size(); ++k) {
    Shard& slot = shards_[static_cast<size_t>(metas[k].index)];
    if (slot.reader)
      throw InputError(given[k].path + " and " + slot.path + " are both shard " +
                       shard_name(metas[k].index, meta_.count) + "; give each shard once");
    slot = std::move(given[k]);
  }
  for (int i = 0; i < meta_.count; ++i)
    if (!shards_[static_cast<size_t>(i)].reader)
      throw InputError("shard " + shard_name(i, meta_.count) + " is missing (" +
                       std::to_string(paths.size()) + " of " + std::to_string(meta_.count) +
                       " given); build it with --shard " + shard_name(i, meta_.count) +
                       " and the same command, or re-run that array task");
  for (int i = 0; i < meta_.count; ++i)
    try {
      for (const TileId& root : table(i).list(tileformat::kShardRoot)) {
        if (root.z != meta_.split_zoom)
          throw InputError(path(i) + ": subtree " + root.str() + " is not at the split zoom " +
                           std::to_string(meta_.split_zoom));
        auto [it, fresh] = roots_.emplace(root, i);
        if (!fresh)
          throw InputError("subtree " + root.str() + " is in both " + path(it->second) + " and " +
                           path(i) + "; the shards overlap (rebuild them with one command)");
      }
    } catch (const tileformat::FormatError& e) {
      throw InputError(path(i) + ": " + e.what());
    }
  if (roots_.size() != meta_.roots)
    throw InputError(
        "the shards hold " + std::to_string(roots_.size()) + " subtrees, the build " +
        std::to_string(meta_.roots) +
        "; a shard is incomplete (rebuild it; --resume continues one that was killed)");
}

ShardSet::~ShardSet() = default;

int ShardSet::owner(TileId id) const {
  const int up = id.z - meta_.split_zoom;
  if (up < 0) return -1;
  auto it = roots_.find(TileId{meta_.split_zoom, id.x >> up, id.y >> up});
  return it == roots_.end() ? -1 : it->second;
}

std::vector<TileId> ShardSet::tiles(int z) {
  std::vector<TileId> all;
  for (int i = 0; i < count(); ++i) {
    const std::vector<TileId> ids = reader(i).tile_ids(z);
    all.insert(all.end(), ids.begin(), ids.end());
  }
  std::sort(all.begin(), all.end(), [](const TileId& a, const TileId& b) {
    return std::pair(a.y, a.x) < std::pair(b.y, b.x);
  });
  return all;
}

tileformat::MetadataMap ShardSet::merged_metadata(const std::string& output, int coarsest,
                                                  const std::string& command_line) const {
  tileformat::MetadataMap m = tileformat::without_shard_keys(metadata());
  m["name"] = std::filesystem::path(output).stem().string();
  m["minzoom"] = std::to_string(coarsest);
  const std::string center = m["center"];
  m["center"] = center.substr(0, center.rfind(',') + 1) + std::to_string(meta_.center_zoom);
  m["globe:command_line"] = command_line;
  return m;
}

}  // namespace globe
