// Deterministic parallelism: work items are processed in batches; inside a
// batch, worker threads compute results in any order, then the caller's
// thread consumes them in item order. Output therefore never depends on the
// thread count. The first exception (in item order) is rethrown. Items
// before `first` are skipped (a resumed build's finished work).
#pragma once

#include <atomic>
#include <exception>
#include <functional>
#include <optional>
#include <thread>
#include <vector>

namespace globe {

template <typename Result>
void parallel_batches(size_t count, int threads, size_t batch_size,
                      const std::function<void(size_t begin, size_t end)>& prepare,
                      const std::function<Result(size_t index, int worker)>& compute,
                      const std::function<void(size_t index, Result&& result)>& consume,
                      size_t first = 0) {
  threads = std::max(1, threads);
  for (size_t begin = first; begin < count; begin += batch_size) {
    const size_t end = std::min(count, begin + batch_size);
    prepare(begin, end);
    std::vector<std::optional<Result>> results(end - begin);
    std::vector<std::exception_ptr> errors(end - begin);
    std::atomic<size_t> next{begin};
    auto work = [&](int worker) {
      for (size_t i; (i = next.fetch_add(1)) < end;) {
        try {
          results[i - begin].emplace(compute(i, worker));
        } catch (...) {
          errors[i - begin] = std::current_exception();
        }
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t)
      pool.emplace_back(work, t);
    work(0);
    for (auto& t : pool)
      t.join();
    for (size_t i = begin; i < end; ++i) {
      if (errors[i - begin]) std::rethrow_exception(errors[i - begin]);
      consume(i, std::move(*results[i - begin]));
    }
  }
}

}  // namespace globe
