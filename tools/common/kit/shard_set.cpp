// Shard sets (see shard_set.hpp).
#include "kit/shard_set.hpp"

#include <algorithm>
#include <filesystem>

#include "kit/build_options.hpp"
#include "kit/progress.hpp"
#include "runtime/errors.hpp"
#include "runtime/package_open.hpp"
#include "tileformat/metadata.hpp"

namespace globe {

using tileformat::TileId;

namespace {

std::string shard_name(int index, int count) {
  return std::to_string(index) + "/" + std::to_string(count);
}

}  // namespace

bool parse_merge_command(CliArgs& cli, BuildOptions& o, const std::vector<std::string>& args,
                         const std::string& program) {
  cli.option("-o,--output", "OUT.mbtiles",
             "merged package (written as OUT.mbtiles.tmp, renamed when complete)",
             [&o](const std::string& v) { o.output = CliArgs::to_output_path(v); });
  declare_run_options(cli, o);
  if (!parse_build_command(cli, o, args, program, "shard package (see --help)")) return false;
  for (const std::string& in : o.inputs)
    if (std::filesystem::weakly_canonical(in) == std::filesystem::weakly_canonical(o.output))
      throw UsageError("-o " + o.output + " is one of the shards; write the merge elsewhere");
  return true;
}

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
        if (root.z > meta_.split_zoom)
          throw InputError(path(i) + ": subtree " + root.str() + " is below the split zoom " +
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
  auto it = roots_.find(up < 0 ? id : TileId{meta_.split_zoom, id.x >> up, id.y >> up});
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

void ShardSet::copy_tiles(tileformat::PackageWriter& writer, int min_zoom, int max_zoom,
                          Progress& progress) {
  for (int z = min_zoom; z <= max_zoom; ++z) {
    const std::vector<TileId> ids = tiles(z);
    const size_t done = writer.resumed() ? writer.tiles_at_zoom(z) : 0;
    progress.begin("z" + std::to_string(z) + " merge", ids.size());
    for (size_t i = 0; i < ids.size(); ++i) {
      if (i > 0 && ids[i] == ids[i - 1])
        throw InputError("tile " + ids[i].str() + " is in two shards; the shards overlap");
      // Above the split zoom, a tile no shard lists is shard 0's.
      int from = owner(ids[i]);
      if (from < 0 && z < split_zoom()) from = 0;
      auto blob = from < 0 ? std::nullopt : reader(from).tile(ids[i]);
      if (!blob)
        throw InputError("tile " + ids[i].str() +
                         " is not where the shards' subtrees put it; the shards do not come "
                         "from one build");
      if (i >= done) writer.put_tile(ids[i], *blob);
      progress.advance();
    }
    progress.end();
    writer.checkpoint();
  }
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
