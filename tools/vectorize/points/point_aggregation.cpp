// Place aggregation (see point_aggregation.hpp).
#include "points/point_aggregation.hpp"

#include <algorithm>
#include <cmath>

namespace globe {

CellWindow::CellWindow(double radius, Wrap wrap)
    : wrap_(wrap), r2_(radius * radius), size_x_(radius), size_y_(radius) {
  if (wrap.width > 0) {
    columns_ = std::max<int64_t>(1, static_cast<int64_t>(std::floor(wrap.width / radius)));
    size_x_ = wrap.width / double(columns_);
  }
}

int64_t CellWindow::column(double x) const {
  const int64_t c = static_cast<int64_t>(std::floor((x - wrap_.west) / size_x_));
  return columns_ > 0 ? std::clamp<int64_t>(c, 0, columns_ - 1) : c;
}

int64_t CellWindow::row(double y) const {
  return static_cast<int64_t>(std::floor(y / size_y_));
}

void CellWindow::add(uint64_t seq, double x, double y) {
  if (keys_.empty()) first_ = seq;
  const uint64_t k = key(column(x), row(y));
  keys_.push_back(k);
  cells_[k].push_back(seq);
}

void CellWindow::drop_before(uint64_t seq) {
  while (!keys_.empty() && first_ < seq) {
    // The oldest place is the first of its cell.
    auto it = cells_.find(keys_.front());
    it->second.erase(it->second.begin());
    if (it->second.empty()) cells_.erase(it);
    keys_.pop_front();
    ++first_;
  }
}

BandMerger::BandMerger(double radius, Wrap wrap, std::function<void(const Place&)> emit)
    : cells_(radius, wrap), wrap_(wrap), emit_(std::move(emit)) {}

void BandMerger::add_band(int64_t band, std::vector<Place>&& places) {
  for (Place& p : places) {
    const uint64_t seq = first_ + slots_.size();
    cells_.add(seq, p.x, p.y);
    const double w = p.weight();
    slots_.push_back({std::move(p), w, band});
    undecided_.push_back(seq);
  }
  peak_ = std::max(peak_, slots_.size());
  last_band_ = band;
  // Places in earlier bands have every neighbour loaded now.
  decide(band);
  int64_t decided_through = last_band_;
  for (uint64_t seq : undecided_)
    decided_through = std::min(decided_through, slot(seq).band - 1);
  emit_and_drop(decided_through);
}

void BandMerger::finish() {
  decide(INT64_MAX);
  for (; next_emit_ < first_ + slots_.size(); ++next_emit_)
    if (slot(next_emit_).state == State::kCentre) emit_centre(next_emit_);
  first_ += slots_.size();
  slots_.clear();
  cells_.drop_before(first_);
}

// Decides, in merge order, the undecided places of bands below `below_band`
// whose heavier neighbours are all decided.
void BandMerger::decide(int64_t below_band) {
  std::vector<uint64_t> candidates, waiting;
  for (uint64_t seq : undecided_)
    (slot(seq).band < below_band ? candidates : waiting).push_back(seq);
  std::sort(candidates.begin(), candidates.end(),
            [&](uint64_t a, uint64_t b) { return before(slot(a), slot(b)); });
  for (uint64_t seq : candidates) {
    Slot& s = slot(seq);
    bool blocked = false, any_centre = false;
    uint64_t best = 0;
    cells_.near(s.place.x, s.place.y, [&](uint64_t q) {
      if (q == seq || blocked) return;
      const Slot& t = slot(q);
      if (!before(t, s) || !cells_.within(s.place.x, s.place.y, t.place.x, t.place.y)) return;
      if (t.state == State::kUndecided) {
        blocked = true;
      } else if (t.state == State::kCentre && (!any_centre || before(t, slot(best)))) {
        any_centre = true;
        best = q;
      }
    });
    if (blocked) {
      waiting.push_back(seq);
    } else if (any_centre) {
      s.state = State::kMember;
      s.owner = best;
    } else {
      s.state = State::kCentre;
    }
  }
  undecided_ = std::move(waiting);
}

void BandMerger::emit_centre(uint64_t seq) {
  const Slot& c = slot(seq);
  members_.clear();
  cells_.near(c.place.x, c.place.y, [&](uint64_t q) {
    const Slot& t = slot(q);
    if (q == seq || (t.state == State::kMember && t.owner == seq)) members_.push_back(q);
  });
  // Members in id order, so the sums do not depend on the cells' order.
  std::sort(members_.begin(), members_.end(),
            [&](uint64_t a, uint64_t b) { return slot(a).place.id < slot(b).place.id; });
  Place out;
  out.sums.assign(c.place.sums.size(), 0.0);
  double wx = 0, wy = 0, wsum = 0;
  uint64_t count = 0;
  out.id = c.place.id;
  for (uint64_t q : members_) {
    const Slot& t = slot(q);
    wx += t.weight * cells_.dx(c.place.x, t.place.x);
    wy += t.weight * (t.place.y - c.place.y);
    wsum += t.weight;
    out.id = std::min(out.id, t.place.id);
    count += t.place.count;
    for (size_t f = 0; f < out.sums.size(); ++f)
      out.sums[f] += t.place.sums[f];
  }
  out.x = c.place.x + wx / wsum;
  if (wrap_.width > 0) {
    if (out.x < wrap_.west) out.x += wrap_.width;
    if (out.x >= wrap_.west + wrap_.width) out.x -= wrap_.width;
  }
  out.y = c.place.y + wy / wsum;
  out.count = static_cast<uint32_t>(std::min<uint64_t>(count, 0xfffffffeu));
  emit_(out);
}

// Every place of bands up to `decided_through` is decided: the centres of the
// bands before it have all their members (which lie within a band of them)
// and go out; the places two bands back are no one's neighbours or members
// any more.
void BandMerger::emit_and_drop(int64_t decided_through) {
  if (decided_through == INT64_MIN) return;
  for (; next_emit_ < first_ + slots_.size() && slot(next_emit_).band < decided_through;
       ++next_emit_)
    if (slot(next_emit_).state == State::kCentre) emit_centre(next_emit_);
  while (!slots_.empty() && slots_.front().band < decided_through - 1) {
    slots_.pop_front();
    ++first_;
  }
  cells_.drop_before(first_);
}

double crowded_share(PlaceSource& places, double radius, Wrap wrap,
                     const std::function<int64_t(const Place&)>& band) {
  struct At {
    double x, y;
    int64_t band;
  };
  CellWindow cells(radius, wrap);
  std::deque<At> window;
  uint64_t first = 0, next_eval = 0, total = 0, crowded = 0;
  // Counts the places of bands up to `through` that have a neighbour.
  const auto evaluate = [&](int64_t through) {
    for (; next_eval < first + window.size() && window[next_eval - first].band <= through;
         ++next_eval) {
      const At& a = window[next_eval - first];
      bool near = false;
      cells.near(a.x, a.y, [&](uint64_t q) {
        if (near || q == next_eval) return;
        const At& b = window[q - first];
        near = cells.within(a.x, a.y, b.x, b.y);
      });
      crowded += near;
    }
  };
  Place p;
  while (places.next(p)) {
    const int64_t b = band(p);
    evaluate(b - 2);
    while (!window.empty() && window.front().band <= b - 3 && first < next_eval) {
      window.pop_front();
      ++first;
    }
    cells.drop_before(first);
    cells.add(first + window.size(), p.x, p.y);
    window.push_back({p.x, p.y, b});
    ++total;
  }
  evaluate(INT64_MAX);
  return total == 0 ? 0 : double(crowded) / double(total);
}

}  // namespace globe
