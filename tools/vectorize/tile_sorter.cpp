// External sort of tile records (see tile_sorter.hpp).
#include "tile_sorter.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <tuple>

#include "errors.hpp"

namespace globe {

// One spilled run: a file of records in (key, seq, sub) order, read back
// through a buffer with the head record decoded.
struct TileSorter::Run {
  std::FILE* file = nullptr;
  std::string path;
  bool valid = false;
  uint64_t key = 0, seq = 0;
  uint32_t sub = 0;
  std::vector<uint8_t> payload;

  ~Run() {
    if (file) std::fclose(file);
  }
  void advance() {
    uint8_t head[24];
    const size_t got = std::fread(head, 1, sizeof head, file);
    if (got == 0 && std::feof(file)) {
      valid = false;
      return;
    }
    if (got != sizeof head) throw OutputError(path + ": scratch run file truncated");
    std::memcpy(&key, head, 8);
    std::memcpy(&seq, head + 8, 8);
    std::memcpy(&sub, head + 16, 4);
    uint32_t len;
    std::memcpy(&len, head + 20, 4);
    payload.resize(len);
    if (len && std::fread(payload.data(), 1, len, file) != len)
      throw OutputError(path + ": scratch run file truncated");
    valid = true;
  }
};

TileSorter::TileSorter(std::string scratch_prefix, size_t memory_budget_bytes)
    : prefix_(std::move(scratch_prefix)), budget_(std::max<size_t>(memory_budget_bytes, 1 << 16)) {}

TileSorter::~TileSorter() {
  runs_.clear();
  std::error_code ec;
  for (const std::string& p : run_paths_)
    std::filesystem::remove(p, ec);
}

void TileSorter::add(uint64_t key, uint64_t seq, uint32_t sub, std::span<const uint8_t> payload) {
  entries_.push_back({key, seq, sub, static_cast<uint32_t>(payload.size()), arena_.size()});
  arena_.insert(arena_.end(), payload.begin(), payload.end());
  ++records_;
  // Allocated (not used) bytes, so vector growth cannot overshoot the budget.
  if (arena_.capacity() + entries_.capacity() * sizeof(Entry) > budget_) spill();
}

void TileSorter::sort_memory() {
  std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.key, a.seq, a.sub) < std::tie(b.key, b.seq, b.sub);
  });
}

void TileSorter::spill() {
  sort_memory();
  const std::string path = prefix_ + "." + std::to_string(run_paths_.size());
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f)
    throw OutputError(path + ": cannot create scratch file (" + std::strerror(errno) +
                      "); check free space and permissions next to the output");
  run_paths_.push_back(path);
  std::vector<uint8_t> buf;
  for (const Entry& e : entries_) {
    uint8_t head[24];
    std::memcpy(head, &e.key, 8);
    std::memcpy(head + 8, &e.seq, 8);
    std::memcpy(head + 16, &e.sub, 4);
    std::memcpy(head + 20, &e.len, 4);
    buf.insert(buf.end(), head, head + 24);
    buf.insert(buf.end(), arena_.begin() + e.offset, arena_.begin() + e.offset + e.len);
    if (buf.size() > (1 << 20) || &e == &entries_.back()) {
      if (std::fwrite(buf.data(), 1, buf.size(), f) != buf.size()) {
        std::fclose(f);
        throw OutputError(path + ": cannot write scratch data (" + std::strerror(errno) +
                          "); check free space");
      }
      spilled_bytes_ += buf.size();
      buf.clear();
    }
  }
  if (std::fclose(f) != 0)
    throw OutputError(path + ": cannot write scratch data; check free space");
  entries_.clear();
  entries_.shrink_to_fit();
  arena_.clear();
  arena_.shrink_to_fit();
}

void TileSorter::finish() {
  finished_ = true;
  sort_memory();  // the last run stays in memory
  for (const std::string& p : run_paths_) {
    auto r = std::make_unique<Run>();
    r->path = p;
    r->file = std::fopen(p.c_str(), "rb");
    if (!r->file) throw OutputError(p + ": cannot reopen scratch file");
    std::setvbuf(r->file, nullptr, _IOFBF, 1 << 20);
    r->advance();
    runs_.push_back(std::move(r));
  }
}

bool TileSorter::peek(uint64_t& key) {
  bool any = false;
  if (mem_pos_ < entries_.size()) {
    key = entries_[mem_pos_].key;
    any = true;
  }
  for (const auto& r : runs_)
    if (r->valid && (!any || r->key < key)) {
      key = r->key;
      any = true;
    }
  return any;
}

bool TileSorter::next_group(TileGroup& group) {
  group.records.clear();
  group.bytes.clear();
  uint64_t key = 0;
  if (!finished_ || !peek(key)) return false;
  group.key = key;
  auto append = [&](uint64_t seq, uint32_t sub, const uint8_t* data, size_t size) {
    group.records.push_back(
        {seq, sub, static_cast<uint32_t>(group.bytes.size()), static_cast<uint32_t>(size)});
    group.bytes.insert(group.bytes.end(), data, data + size);
  };
  for (;;) {
    // The smallest (seq, sub) among the heads holding `key`.
    Run* best_run = nullptr;
    bool best_mem = false;
    uint64_t bseq = 0;
    uint32_t bsub = 0;
    if (mem_pos_ < entries_.size() && entries_[mem_pos_].key == key) {
      best_mem = true;
      bseq = entries_[mem_pos_].seq;
      bsub = entries_[mem_pos_].sub;
    }
    for (const auto& r : runs_)
      if (r->valid && r->key == key &&
          (!(best_mem || best_run) || std::tie(r->seq, r->sub) < std::tie(bseq, bsub))) {
        best_run = r.get();
        best_mem = false;
        bseq = r->seq;
        bsub = r->sub;
      }
    if (best_run) {
      append(bseq, bsub, best_run->payload.data(), best_run->payload.size());
      best_run->advance();
    } else if (best_mem) {
      const Entry& e = entries_[mem_pos_++];
      append(bseq, bsub, arena_.data() + e.offset, e.len);
    } else {
      return true;
    }
  }
}

}  // namespace globe
