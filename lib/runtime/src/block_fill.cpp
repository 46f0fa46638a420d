// Hole filling (see block_fill.hpp).
#include "runtime/block_fill.hpp"

#include <algorithm>
#include <cmath>

namespace globe {
namespace {

// Fills unknown entries of one edge (indices idx[0..n-1]) whose two ends are known.
void fill_edge(std::vector<int32_t>& q, std::vector<uint8_t>& known,
               const std::vector<size_t>& idx) {
  const int n = static_cast<int>(idx.size());
  int prev = 0;  // the first entry (a corner) is known
  for (int i = 1; i < n; ++i) {
    if (!known[idx[i]]) continue;
    for (int j = prev + 1; j < i; ++j) {
      const int64_t a = q[idx[prev]], b = q[idx[i]];
      const double t = static_cast<double>(j - prev) / (i - prev);
      q[idx[j]] = static_cast<int32_t>(a + std::llround(static_cast<double>(b - a) * t));
      known[idx[j]] = 1;
    }
    prev = i;
  }
}

}  // namespace

void fill_holes(std::vector<int32_t>& q, const std::vector<uint8_t>& valid, int size,
                int32_t fill_q) {
  const size_t n = static_cast<size_t>(size) * size;
  if (std::all_of(valid.begin(), valid.end(), [](uint8_t v) { return v != 0; })) return;
  std::vector<uint8_t> known(valid);
  const int last = size - 1;
  const size_t corners[4] = {0, static_cast<size_t>(last), static_cast<size_t>(last) * size,
                             static_cast<size_t>(last) * size + last};
  for (size_t c : corners)
    if (!known[c]) {
      q[c] = fill_q;
      known[c] = 1;
    }
  std::vector<size_t> top, bottom, left, right;
  for (int i = 0; i < size; ++i) {
    top.push_back(i);
    bottom.push_back(static_cast<size_t>(last) * size + i);
    left.push_back(static_cast<size_t>(i) * size);
    right.push_back(static_cast<size_t>(i) * size + last);
  }
  for (const auto* e : {&top, &bottom, &left, &right})
    fill_edge(q, known, *e);

  // Interior: synchronous waves from the known samples inwards.
  std::vector<size_t> frontier;
  auto unknown_with_known_neighbour = [&](size_t i) {
    const int x = static_cast<int>(i % size), y = static_cast<int>(i / size);
    return !known[i] && ((x > 0 && known[i - 1]) || (x < last && known[i + 1]) ||
                         (y > 0 && known[i - size]) || (y < last && known[i + size]));
  };
  for (size_t i = 0; i < n; ++i)
    if (unknown_with_known_neighbour(i)) frontier.push_back(i);
  std::vector<int32_t> values;
  std::vector<uint8_t> queued(n, 0);
  while (!frontier.empty()) {
    values.resize(frontier.size());
    for (size_t k = 0; k < frontier.size(); ++k) {
      const size_t i = frontier[k];
      const int x = static_cast<int>(i % size), y = static_cast<int>(i / size);
      int64_t sum = 0;
      int count = 0;
      for (auto [ok, j] : {std::pair{x > 0, i - 1}, std::pair{x < last, i + 1},
                           std::pair{y > 0, i - size}, std::pair{y < last, i + size}})
        if (ok && known[j]) {
          sum += q[j];
          ++count;
        }
      values[k] = static_cast<int32_t>(std::llround(static_cast<double>(sum) / count));
    }
    for (size_t k = 0; k < frontier.size(); ++k) {
      q[frontier[k]] = values[k];
      known[frontier[k]] = 1;
    }
    std::vector<size_t> next;
    for (size_t i : frontier) {
      const int x = static_cast<int>(i % size), y = static_cast<int>(i / size);
      for (auto [ok, j] : {std::pair{x > 0, i - 1}, std::pair{x < last, i + 1},
                           std::pair{y > 0, i - size}, std::pair{y < last, i + size}})
        if (ok && !known[j] && !queued[j]) {
          queued[j] = 1;
          next.push_back(j);
        }
    }
    frontier.swap(next);
  }
}

}  // namespace globe
