// Deterministic parallelism for the builders: work items are processed in
// batches; worker threads compute results in any order, and the caller's
// thread consumes them in item order, so output never depends on the thread
// count. The caller's thread is the only one that touches the builder's
// files: it loads each batch's inputs (`load`) and consumes results
// (`consume`), and it does so for one batch while the workers compute the
// next, so reading and writing SQLite hides behind the computing. At most
// two batches are in flight.
//
// Order on the caller's thread: load(b0), load(b1), consume(b0...),
// consumed(end of b0), load(b2), consume(b1...), consumed(end of b1), ...
// `consumed(end)` means every item before `end` has been consumed (a point
// to commit a checkpoint at). The first exception (in item order) of
// compute, and any of the caller's callbacks, is rethrown after the workers
// have stopped. Items before `first` are skipped (a resumed build's finished
// work).
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace globe {

struct NoInputs {};

template <typename Inputs, typename Result>
void parallel_batches(size_t count, int threads, size_t batch_size,
                      const std::function<Inputs(size_t begin, size_t end)>& load,
                      const std::function<Result(size_t index, int worker, const Inputs&)>& compute,
                      const std::function<void(size_t index, Result&& result)>& consume,
                      const std::function<void(size_t consumed)>& consumed, size_t first = 0) {
  struct Batch {
    size_t begin, end;
    Inputs inputs;
    std::vector<std::optional<Result>> results;
    std::vector<std::exception_ptr> errors;
    size_t next;       // next item to hand out (under the mutex)
    size_t remaining;  // items not computed yet (under the mutex)
  };
  threads = std::max(1, threads);
  batch_size = std::max<size_t>(1, batch_size);
  std::mutex mutex;
  std::condition_variable work_ready, batch_done;
  std::deque<std::unique_ptr<Batch>> inflight;
  bool stop = false;

  auto worker = [&](int id) {
    std::unique_lock lock(mutex);
    for (;;) {
      Batch* batch = nullptr;
      work_ready.wait(lock, [&] {
        if (stop) return true;
        for (auto& b : inflight)
          if (b->next < b->end) {
            batch = b.get();
            return true;
          }
        return false;
      });
      if (stop) return;
      const size_t i = batch->next++;
      lock.unlock();
      std::optional<Result> r;
      std::exception_ptr error;
      try {
        r.emplace(compute(i, id, batch->inputs));
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      batch->results[i - batch->begin] = std::move(r);
      batch->errors[i - batch->begin] = error;
      if (--batch->remaining == 0) batch_done.notify_all();
    }
  };
  std::vector<std::thread> pool;
  auto shutdown = [&] {
    {
      std::lock_guard lock(mutex);
      stop = true;
    }
    work_ready.notify_all();
    for (auto& t : pool)
      t.join();
    pool.clear();
  };

  size_t next_begin = first;
  auto publish = [&] {
    if (next_begin >= count) return;
    const size_t end = std::min(count, next_begin + batch_size);
    auto b = std::make_unique<Batch>(
        Batch{next_begin, end, load(next_begin, end), {}, {}, next_begin, end - next_begin});
    b->results.resize(end - next_begin);
    b->errors.resize(end - next_begin);
    {
      std::lock_guard lock(mutex);
      inflight.push_back(std::move(b));
    }
    work_ready.notify_all();
    next_begin = end;
  };

  try {
    for (int t = 0; t < threads; ++t)
      pool.emplace_back(worker, t);
    publish();
    publish();
    while (!inflight.empty()) {
      Batch* b = inflight.front().get();
      {
        std::unique_lock lock(mutex);
        batch_done.wait(lock, [&] { return b->remaining == 0; });
      }
      for (size_t i = b->begin; i < b->end; ++i) {
        if (b->errors[i - b->begin]) std::rethrow_exception(b->errors[i - b->begin]);
        consume(i, std::move(*b->results[i - b->begin]));
      }
      consumed(b->end);
      {
        std::lock_guard lock(mutex);
        inflight.pop_front();
      }
      publish();
    }
  } catch (...) {
    shutdown();
    throw;
  }
  shutdown();
}

}  // namespace globe
