// A remote source's tile requests (see tile_requests.hpp).
#include "data/tile_requests.hpp"

#include <algorithm>

#include "tileformat/error.hpp"

namespace globe::viewer {
namespace {

constexpr size_t kMaxPending = 1024;

uint64_t key(tileformat::TileId id) {
  return (uint64_t(id.z) << 58) | (uint64_t(id.x) << 29) | id.y;
}

}  // namespace

TileRequests::TileRequests(net::HttpClient& client, std::vector<std::string> accept_types)
    : client_(client), accept_types_(std::move(accept_types)) {}

TileRequests::~TileRequests() {
  std::unique_lock lock(mutex_);
  for (const auto& [k, p] : pending_)
    if (!p->done) client_.cancel(p->request);
  answered_.wait(lock, [&] {
    return std::all_of(pending_.begin(), pending_.end(),
                       [](const auto& e) { return e.second->done; });
  });
}

std::shared_ptr<TileRequests::Pending> TileRequests::ask(tileformat::TileId id,
                                                         const std::string& url,
                                                         const std::string& range) {
  // Answers nobody read (prefetched for a view that moved on) are let go
  // past a bound, so a long flight does not keep every tile's body.
  if (pending_.size() > kMaxPending)
    std::erase_if(pending_, [&](const auto& e) { return e.second->done && e.first != key(id); });
  std::shared_ptr<Pending>& slot = pending_[key(id)];
  // A request forgotten and answered kCancelled is asked again.
  if (slot && !(slot->done && slot->response.outcome == net::Outcome::kCancelled)) return slot;
  auto p = std::make_shared<Pending>();
  slot = p;
  net::Request req;
  req.url = url;
  req.range = range;
  req.priority = next_priority_ -= 1;
  req.accept_types = accept_types_;
  p->request = client_.get(std::move(req), [this, p](net::Response r) {
    {
      std::lock_guard lock(mutex_);
      p->response = std::move(r);
      p->done = true;
    }
    answered_.notify_all();
  });
  return p;
}

void TileRequests::prefetch(tileformat::TileId id, const std::string& url,
                            const std::string& range) {
  std::lock_guard lock(mutex_);
  if (!absent_.count(key(id))) ask(id, url, range);
}

std::optional<std::vector<uint8_t>> TileRequests::take(tileformat::TileId id,
                                                       const std::string& url,
                                                       const std::string& range) {
  std::unique_lock lock(mutex_);
  if (absent_.count(key(id))) return std::nullopt;
  const std::shared_ptr<Pending> p = ask(id, url, range);
  answered_.wait(lock, [&] { return p->done; });
  if (const auto it = pending_.find(key(id)); it != pending_.end() && it->second == p)
    pending_.erase(it);
  net::Response& r = p->response;
  switch (r.outcome) {
    case net::Outcome::kOk:
      return std::move(r.body);
    case net::Outcome::kNoContent:
      absent_.insert(key(id));
      return std::nullopt;
    default:
      throw tileformat::PackageError(r.error.empty() ? url + ": " + net::to_string(r.outcome)
                                                     : r.error);
  }
}

void TileRequests::forget(tileformat::TileId id) {
  std::lock_guard lock(mutex_);
  // Kept until answered (kCancelled, or the answer if it came first): the
  // destructor waits for every callback, and take() asks again if wanted.
  const auto it = pending_.find(key(id));
  if (it != pending_.end() && !it->second->done) client_.cancel(it->second->request);
}

bool TileRequests::absent(tileformat::TileId id) {
  std::lock_guard lock(mutex_);
  return absent_.count(key(id)) != 0;
}

}  // namespace globe::viewer
