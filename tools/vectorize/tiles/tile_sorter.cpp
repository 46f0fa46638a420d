// External sort of tile records (see tile_sorter.hpp).
#include "tiles/tile_sorter.hpp"

#include <algorithm>
#include <new>
#include <tuple>

#include "kit/scratch_file.hpp"
#include "tileformat/byte_io.hpp"

namespace globe {

// One spilled run: a scratch file of records in (key, seq, sub) order, each
// key (u64), seq (u64), sub (u32) and the payload; read back with the head
// record decoded.
struct TileSorter::Run {
  explicit Run(std::string path) : file(std::move(path)) {}
  ScratchFile file;
  bool valid = false;
  uint64_t key = 0, seq = 0;
  uint32_t sub = 0;
  std::vector<uint8_t> record;
  std::span<const uint8_t> payload;

  void advance() {
    valid = file.next(record);
    if (!valid) return;
    tileformat::ByteReader r(record, file.path() + ": scratch run record", "scratch");
    key = r.u64();
    seq = r.u64();
    sub = r.u32();
    payload = r.bytes(r.remaining());
  }
};

TileSorter::TileSorter(std::string scratch_prefix, size_t memory_budget_bytes)
    : prefix_(std::move(scratch_prefix)), budget_(std::max<size_t>(memory_budget_bytes, 1 << 16)) {}

TileSorter::~TileSorter() = default;

void TileSorter::add(uint64_t key, uint64_t seq, uint32_t sub, std::span<const uint8_t> payload) {
  if (!entries_.empty() &&
      arena_.size() + payload.size() + (entries_.size() + 1) * sizeof(Entry) > budget_)
    spill();
  if (entries_.capacity() == 0) {
    // Address space for the whole budget up front, so the buffers never
    // reallocate (a reallocation holds the old and the new buffer at once);
    // only the pages written count. Where that much cannot be reserved, the
    // buffers grow as they fill.
    try {
      arena_.reserve(budget_);
      entries_.reserve(budget_ / sizeof(Entry));
    } catch (const std::bad_alloc&) {
    }
  }
  entries_.push_back({key, seq, sub, static_cast<uint32_t>(payload.size()), arena_.size()});
  arena_.insert(arena_.end(), payload.begin(), payload.end());
  ++records_;
}

void TileSorter::sort_memory() {
  std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.key, a.seq, a.sub) < std::tie(b.key, b.seq, b.sub);
  });
}

void TileSorter::spill() {
  sort_memory();
  auto run = std::make_unique<Run>(prefix_ + "." + std::to_string(runs_.size()));
  for (const Entry& e : entries_) {
    tileformat::ByteWriter w;
    w.u64(e.key);
    w.u64(e.seq);
    w.u32(e.sub);
    w.bytes({arena_.data() + e.offset, e.len});
    run->file.append(w.take());
  }
  spilled_bytes_ += run->file.bytes_written();
  runs_.push_back(std::move(run));
  entries_.clear();
  entries_.shrink_to_fit();
  arena_.clear();
  arena_.shrink_to_fit();
}

void TileSorter::finish() {
  finished_ = true;
  sort_memory();  // the last run stays in memory
  for (const auto& r : runs_) {
    r->file.rewind();
    r->advance();
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
