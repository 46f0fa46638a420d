// Shard planning (see shard_plan.hpp).
#include "kit/shard_plan.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include "kit/build_options.hpp"
#include "runtime/cli_args.hpp"
#include "runtime/errors.hpp"

namespace globe {

using tileformat::TileId;

namespace {

// Bits of x and y interleaved (x in the even bits): the Morton order of
// tiles of one zoom.
uint64_t morton(uint32_t x, uint32_t y) {
  auto spread = [](uint64_t v) {
    v &= 0xffffffffu;
    v = (v | (v << 16)) & 0x0000ffff0000ffffull;
    v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
    v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    v = (v | (v << 1)) & 0x5555555555555555ull;
    return v;
  };
  return spread(x) | (spread(y) << 1);
}

TileId ancestor(TileId id, int z) {
  const int up = id.z - z;
  return TileId{z, id.x >> up, id.y >> up};
}

constexpr uint64_t kRootsPerShard = 16;

}  // namespace

ShardSpec parse_shard(const std::string& text) {
  const size_t slash = text.find('/');
  const std::string what = "--shard: expected I/N with 0 <= I < N (e.g. 3/8), got '" + text + "'";
  if (slash == std::string::npos) throw UsageError(what);
  ShardSpec s;
  try {
    size_t used = 0;
    s.index = std::stoi(text.substr(0, slash), &used);
    if (used != slash) throw UsageError(what);
    const std::string n = text.substr(slash + 1);
    s.count = std::stoi(n, &used);
    if (used != n.size()) throw UsageError(what);
  } catch (const std::logic_error&) {
    throw UsageError(what);
  }
  if (s.count < 1 || s.count > 100000 || s.index < 0 || s.index >= s.count) throw UsageError(what);
  return s;
}

void declare_shard_options(CliArgs& cli, BuildOptions& o) {
  cli.option("--shard", "I/N",
             "build only shard I of N (0-based) into OUT; `merge` joins the N shards into the "
             "package one machine would build (docs/scale-out.md)",
             [&o](const std::string& v) { o.shard = parse_shard(v); });
  cli.option("--split-zoom", "Z",
             "with --shard: the zoom whose subtrees are shared out (default: the coarsest with "
             "16 subtrees of data per shard); the merge builds the zooms above it",
             [&o](const std::string& v) {
               o.split_zoom = CliArgs::to_int("--split-zoom", v, 0, tileformat::kMaxZoom);
             });
}

bool ShardPlan::contains(TileId id) const {
  return std::binary_search(roots.begin(), roots.end(),
                            id.z < split_zoom ? id : ancestor(id, split_zoom));
}

ShardPlan plan_shard(const std::vector<TileWork>& tiles, int min_zoom,
                     std::optional<int> split_zoom, ShardSpec spec,
                     const std::vector<TileWork>& coarse) {
  ShardPlan plan;
  if (tiles.empty()) return plan;
  const int finest = tiles.front().id.z;
  if (split_zoom && *split_zoom > finest)
    throw UsageError("--split-zoom " + std::to_string(*split_zoom) +
                     " is finer than the build's finest zoom " + std::to_string(finest));
  if (split_zoom && *split_zoom < min_zoom)
    throw UsageError("--split-zoom " + std::to_string(*split_zoom) +
                     " is coarser than the build's coarsest zoom " + std::to_string(min_zoom));
  // Work per subtree root at zoom z, in Morton order.
  auto roots_at = [&](int z) {
    std::map<std::pair<uint64_t, TileId>, uint64_t> work;
    for (const TileWork& t : tiles) {
      const TileId r = ancestor(t.id, z);
      work[{morton(r.x, r.y), r}] += std::max<uint64_t>(t.work, 1);
    }
    return work;
  };
  int z = split_zoom.value_or(min_zoom);
  auto roots = roots_at(z);
  const uint64_t wanted = kRootsPerShard * static_cast<uint64_t>(spec.count);
  while (!split_zoom && roots.size() < wanted && z < finest)
    roots = roots_at(++z);
  plan.split_zoom = z;
  // Coarse tiles at the Morton index of their first split zoom descendant;
  // TileId order puts them before that subtree, the coarser first.
  for (const TileWork& c : coarse)
    if (c.id.z < z)
      roots[{morton(c.id.x, c.id.y) << (2 * (z - c.id.z)), c.id}] += std::max<uint64_t>(c.work, 1);
  plan.roots_total = roots.size();
  for (const auto& [key, w] : roots)
    plan.work_total += w;
  // Root j goes to the shard holding the middle of its work on the
  // cumulative scale: contiguous runs of about work_total / N each.
  // (Work totals stay far below 2^46, N below 2^17: no overflow.)
  uint64_t before = 0;
  const uint64_t total = plan.work_total, n = static_cast<uint64_t>(spec.count);
  for (const auto& [key, w] : roots) {
    const uint64_t mid2 = 2 * before + w;
    const int shard = static_cast<int>(std::min<uint64_t>(mid2 * n / (2 * total), n - 1));
    if (shard == spec.index) {
      plan.roots.push_back(key.second);
      plan.work += w;
    }
    before += w;
  }
  std::sort(plan.roots.begin(), plan.roots.end());
  return plan;
}

std::string shard_summary(const ShardPlan& plan, ShardSpec spec) {
  return "shard " + std::to_string(spec.index) + "/" + std::to_string(spec.count) + ": " +
         std::to_string(plan.roots.size()) + " of " + std::to_string(plan.roots_total) +
         " subtrees below zoom " + std::to_string(plan.split_zoom) + ", " +
         std::to_string(plan.work) + " of " + std::to_string(plan.work_total) +
         " units of estimated work";
}

tileformat::ShardMetadata shard_metadata(const BuildOptions& o, const ShardPlan& plan, int min_zoom,
                                         int center_zoom) {
  return {o.shard->index,    o.shard->count, plan.split_zoom, plan.roots_total,
          shard_build_id(o), min_zoom,       center_zoom};
}

std::string shard_build_id(const BuildOptions& o) {
  // The command line without the options that differ between the shards.
  std::string line;
  const std::string& c = o.command_line;
  size_t at = 0;
  bool skip_value = false;
  while (at <= c.size()) {
    size_t end = c.find(' ', at);
    if (end == std::string::npos) end = c.size();
    const std::string word = c.substr(at, end - at);
    at = end + 1;
    if (skip_value) {
      skip_value = false;
      continue;
    }
    if (word == "--shard" || word == "-o" || word == "--output") {
      skip_value = true;
      continue;
    }
    if (word.rfind("--shard=", 0) == 0 || word.rfind("--output=", 0) == 0) continue;
    line += word + " ";
  }
  BuildOptions id = o;
  id.command_line = line;
  const std::string key = build_key(id);
  uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (unsigned char ch : key) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

}  // namespace globe
