// A loader thread for one package: reads the blobs of queued tiles through
// the caller's reader (the only user of its tile(); the connection is
// serialized, so the caller may call has_tile() meanwhile, and both see the one
// file opened at start even if the path is replaced), decodes them with the
// caller's function, and hands the results back to the render thread, which
// never waits unless it asks to. Used by every tile cache of the viewer.
// A remote reader (viewer/data/remote_reader.hpp) is told of each batch as it
// is queued (prefetch), so its requests run at once while this thread decodes
// in queue order; a tile it finds missing (404) comes back `absent`.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "tileformat/package.hpp"
#include "tileformat/tile_id.hpp"

namespace globe::viewer {

template <class Decoded>
class TileLoader {
 public:
  // Runs on the loader thread; throws to report a bad tile.
  using Decode = std::function<Decoded(tileformat::TileId, std::span<const uint8_t> blob)>;

  struct Job {
    tileformat::TileId id;
    int tag = -1;  // the caller's (e.g. the reserved texture slot)
  };
  struct Done {
    Job job;
    Decoded value{};
    bool ok = true;
    bool absent = false;  // !ok because the source has no tile there (a remote source's 404)
    std::string error;    // when !ok
    uint64_t bytes = 0;
  };

  // `reader` must outlive the loader.
  TileLoader(tileformat::TileReader& reader, Decode decode)
      : reader_(reader), decode_(std::move(decode)), thread_([this] { main(); }) {}
  ~TileLoader() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_loader_.notify_all();
    thread_.join();
  }
  TileLoader(const TileLoader&) = delete;
  TileLoader& operator=(const TileLoader&) = delete;

  void submit(const std::vector<Job>& jobs) {
    if (jobs.empty()) return;
    std::vector<tileformat::TileId> ids;
    ids.reserve(jobs.size());
    for (const Job& j : jobs)
      ids.push_back(j.id);
    reader_.prefetch(ids);
    {
      std::lock_guard lock(mutex_);
      jobs_.insert(jobs_.end(), jobs.begin(), jobs.end());
      in_flight_ += static_cast<int>(jobs.size());
    }
    wake_loader_.notify_one();
  }
  // Submits `jobs` coarser tiles first (they cover more of the screen) and
  // empties it.
  void submit_coarsest_first(std::vector<Job>& jobs) {
    std::sort(jobs.begin(), jobs.end(), [](const Job& a, const Job& b) { return a.id < b.id; });
    submit(jobs);
    jobs.clear();
  }
  std::vector<Done> take_done() {
    std::vector<Done> out;
    std::lock_guard lock(mutex_);
    out.swap(done_);
    return out;
  }
  // Blocks until something is done or nothing is queued.
  void wait() {
    std::unique_lock lock(mutex_);
    wake_main_.wait(lock, [this] { return !done_.empty() || in_flight_ == 0; });
  }
  // Blocks until every queued tile is done.
  void wait_all() {
    std::unique_lock lock(mutex_);
    wake_main_.wait(lock, [this] { return in_flight_ == 0; });
  }
  bool busy() {
    std::lock_guard lock(mutex_);
    return in_flight_ > 0 || !done_.empty();
  }

 private:
  void main() {
    for (;;) {
      Done d;
      {
        std::unique_lock lock(mutex_);
        wake_loader_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
        if (stop_) return;
        d.job = jobs_.front();
        jobs_.pop_front();
      }
      try {
        const auto blob = reader_.tile(d.job.id);
        if (!blob) {
          d.absent = reader_.package() == nullptr;  // a file's tile cannot vanish
          throw std::runtime_error(d.absent ? "the source has no such tile"
                                            : "tile vanished from the package");
        }
        d.bytes = blob->size();
        d.value = decode_(d.job.id, *blob);
      } catch (const std::exception& e) {
        d.ok = false;
        d.error = e.what();
      }
      {
        std::lock_guard lock(mutex_);
        done_.push_back(std::move(d));
        --in_flight_;
      }
      wake_main_.notify_all();
    }
  }

  tileformat::TileReader& reader_;
  Decode decode_;
  std::mutex mutex_;
  std::condition_variable wake_loader_, wake_main_;
  std::deque<Job> jobs_;
  std::vector<Done> done_;
  int in_flight_ = 0;
  bool stop_ = false;
  std::thread thread_;  // last: starts after everything it uses exists
};

}  // namespace globe::viewer
