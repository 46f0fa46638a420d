// CurlMulti (curl_multi.hpp): the only file of lib/net that calls libcurl.
// Easy handles are made per transfer and freed when it ends; connections
// live on in the multi handle's cache and are reused (HTTP/1.1 keep-alive,
// HTTP/2 streams with CURLOPT_PIPEWAIT). Every setopt's return code is
// checked: a refused option is a NetError naming the URL.
#include "curl_multi.hpp"

#include <curl/curl.h>

#include <algorithm>
#include <cctype>
#include <mutex>
#include <unordered_map>

#include "net/http_client.hpp"

namespace globe::net::detail {
namespace {

void global_init() {
  static std::once_flag once;
  static CURLcode rc = CURLE_OK;
  std::call_once(once, [] { rc = curl_global_init(CURL_GLOBAL_DEFAULT); });
  if (rc != CURLE_OK)
    throw NetError(std::string("libcurl cannot start: ") + curl_easy_strerror(rc));
}

// The failures worth another attempt: the network or the server hiccuped.
TransferFailure classify(CURLcode rc) {
  switch (rc) {
    case CURLE_OK:
      return TransferFailure::kNone;
    case CURLE_OPERATION_TIMEDOUT:  // also the low-speed limit
    case CURLE_PARTIAL_FILE:
    case CURLE_RECV_ERROR:
    case CURLE_SEND_ERROR:
    case CURLE_GOT_NOTHING:
    case CURLE_COULDNT_CONNECT:
    case CURLE_COULDNT_RESOLVE_HOST:
    case CURLE_COULDNT_RESOLVE_PROXY:
    case CURLE_SSL_CONNECT_ERROR:
    case CURLE_HTTP2:
    case CURLE_HTTP2_STREAM:
    case CURLE_HTTP3:
    case CURLE_QUIC_CONNECT_ERROR:
    case CURLE_BAD_CONTENT_ENCODING:
    case CURLE_WEIRD_SERVER_REPLY:
    case CURLE_AGAIN:
      return TransferFailure::kRetryable;
    default:
      return TransferFailure::kPermanent;
  }
}

std::string trim(std::string s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && space(s.back()))
    s.pop_back();
  size_t start = 0;
  while (start < s.size() && space(s[start]))
    ++start;
  return s.substr(start);
}

// One transfer: the easy handle and what its callbacks collect.
struct Transfer {
  uint64_t token = 0;
  std::string url;
  CURL* easy = nullptr;
  curl_slist* headers_out = nullptr;
  std::vector<uint8_t> body;
  std::map<std::string, std::string> headers_in;
  char error[CURL_ERROR_SIZE] = {};

  ~Transfer() {
    if (easy) curl_easy_cleanup(easy);
    curl_slist_free_all(headers_out);
  }
};

size_t on_body(char* data, size_t size, size_t count, void* user) {
  auto* t = static_cast<Transfer*>(user);
  const size_t n = size * count;
  t->body.insert(t->body.end(), reinterpret_cast<const uint8_t*>(data),
                 reinterpret_cast<const uint8_t*>(data) + n);
  return n;
}

// One header line at a time; a status line starts a new response (a
// redirect's or a 100 Continue's headers are forgotten).
size_t on_header(char* data, size_t size, size_t count, void* user) {
  auto* t = static_cast<Transfer*>(user);
  const size_t n = size * count;
  const std::string line(data, n);
  if (line.starts_with("HTTP/")) {
    t->headers_in.clear();
    return n;
  }
  const size_t colon = line.find(':');
  if (colon == std::string::npos || colon == 0) return n;  // the blank line, or folding
  std::string name = line.substr(0, colon);
  for (char& c : name)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string value = trim(line.substr(colon + 1));
  auto [it, fresh] = t->headers_in.emplace(name, value);
  if (!fresh) it->second += ", " + value;
  return n;
}

}  // namespace

struct CurlMulti::Impl {
  CurlSettings settings;
  CURLM* multi = nullptr;
  std::unordered_map<uint64_t, std::unique_ptr<Transfer>> transfers;

  void setopt_failed(const Transfer& t, CURLcode rc, const char* option) {
    throw NetError(t.url + ": libcurl refused " + option + ": " + curl_easy_strerror(rc));
  }
};

CurlMulti::CurlMulti(const CurlSettings& settings) : impl_(std::make_unique<Impl>()) {
  global_init();
  impl_->settings = settings;
  impl_->multi = curl_multi_init();
  if (!impl_->multi) throw NetError("libcurl cannot start: curl_multi_init failed");
  const long per_host = std::max(1L, settings.max_host_connections);
  const long total = std::max(1L, settings.max_total_connections);
  CURLMcode rc = curl_multi_setopt(impl_->multi, CURLMOPT_MAX_HOST_CONNECTIONS, per_host);
  if (rc == CURLM_OK) rc = curl_multi_setopt(impl_->multi, CURLMOPT_MAX_TOTAL_CONNECTIONS, total);
  if (rc == CURLM_OK) rc = curl_multi_setopt(impl_->multi, CURLMOPT_MAXCONNECTS, total);
  if (rc != CURLM_OK) {
    curl_multi_cleanup(impl_->multi);
    throw NetError(std::string("libcurl cannot start: ") + curl_multi_strerror(rc));
  }
}

CurlMulti::~CurlMulti() {
  for (auto& [token, t] : impl_->transfers)
    curl_multi_remove_handle(impl_->multi, t->easy);
  impl_->transfers.clear();
  curl_multi_cleanup(impl_->multi);
}

void CurlMulti::start(uint64_t token, const TransferSpec& spec) {
  auto t = std::make_unique<Transfer>();
  t->token = token;
  t->url = spec.url;
  t->easy = curl_easy_init();
  if (!t->easy) throw NetError(spec.url + ": libcurl cannot make a transfer (curl_easy_init)");
  for (const std::string& h : spec.headers) {
    curl_slist* next = curl_slist_append(t->headers_out, h.c_str());
    if (!next) throw NetError(spec.url + ": out of memory for the request's headers");
    t->headers_out = next;
  }
  const CurlSettings& s = impl_->settings;
  CURL* e = t->easy;
  Transfer* raw = t.get();
  const auto ms = [](double seconds) { return static_cast<long>(std::max(0.0, seconds) * 1000); };
  // Each option is checked; the name goes into the error.
#define GLOBE_SETOPT(option, value)                                           \
  if (const CURLcode rc = curl_easy_setopt(e, option, value); rc != CURLE_OK) \
  impl_->setopt_failed(*raw, rc, #option)
  GLOBE_SETOPT(CURLOPT_URL, spec.url.c_str());
  GLOBE_SETOPT(CURLOPT_PRIVATE, static_cast<void*>(raw));
  GLOBE_SETOPT(CURLOPT_ERRORBUFFER, raw->error);
  GLOBE_SETOPT(CURLOPT_WRITEFUNCTION, on_body);
  GLOBE_SETOPT(CURLOPT_WRITEDATA, static_cast<void*>(raw));
  GLOBE_SETOPT(CURLOPT_HEADERFUNCTION, on_header);
  GLOBE_SETOPT(CURLOPT_HEADERDATA, static_cast<void*>(raw));
  if (t->headers_out) GLOBE_SETOPT(CURLOPT_HTTPHEADER, t->headers_out);
  GLOBE_SETOPT(CURLOPT_USERAGENT, s.user_agent.c_str());
  GLOBE_SETOPT(CURLOPT_HTTP_VERSION, static_cast<long>(CURL_HTTP_VERSION_2TLS));
  GLOBE_SETOPT(CURLOPT_PIPEWAIT, 1L);
  if (spec.compressed) GLOBE_SETOPT(CURLOPT_ACCEPT_ENCODING, "");
  GLOBE_SETOPT(CURLOPT_CONNECTTIMEOUT_MS, ms(s.connect_timeout_s));
  GLOBE_SETOPT(CURLOPT_TIMEOUT_MS, ms(s.transfer_timeout_s));
  GLOBE_SETOPT(CURLOPT_LOW_SPEED_LIMIT, s.low_speed_bytes_per_s);
  GLOBE_SETOPT(CURLOPT_LOW_SPEED_TIME, s.low_speed_time_s);
  GLOBE_SETOPT(CURLOPT_NOSIGNAL, 1L);
  GLOBE_SETOPT(CURLOPT_FAILONERROR, 0L);  // statuses are HttpClient's to judge
  GLOBE_SETOPT(CURLOPT_FOLLOWLOCATION, 1L);
  GLOBE_SETOPT(CURLOPT_MAXREDIRS, 5L);
  GLOBE_SETOPT(CURLOPT_PROTOCOLS_STR, "http,https");
  GLOBE_SETOPT(CURLOPT_REDIR_PROTOCOLS_STR, "http,https");
#undef GLOBE_SETOPT
  const CURLMcode rc = curl_multi_add_handle(impl_->multi, e);
  if (rc != CURLM_OK)
    throw NetError(spec.url + ": libcurl cannot start the transfer: " + curl_multi_strerror(rc));
  impl_->transfers[token] = std::move(t);
}

void CurlMulti::abort(uint64_t token) {
  const auto it = impl_->transfers.find(token);
  if (it == impl_->transfers.end()) return;
  curl_multi_remove_handle(impl_->multi, it->second->easy);
  impl_->transfers.erase(it);
}

std::vector<TransferResult> CurlMulti::perform() {
  int running = 0;
  const CURLMcode prc = curl_multi_perform(impl_->multi, &running);
  if (prc != CURLM_OK && prc != CURLM_CALL_MULTI_PERFORM)
    throw NetError(std::string("libcurl: ") + curl_multi_strerror(prc));
  std::vector<TransferResult> done;
  int left = 0;
  while (CURLMsg* msg = curl_multi_info_read(impl_->multi, &left)) {
    if (msg->msg != CURLMSG_DONE) continue;
    void* priv = nullptr;
    curl_easy_getinfo(msg->easy_handle, CURLINFO_PRIVATE, &priv);
    auto* t = static_cast<Transfer*>(priv);
    const auto it = t ? impl_->transfers.find(t->token) : impl_->transfers.end();
    if (it == impl_->transfers.end()) continue;
    const CURLcode rc = msg->data.result;

    TransferResult r;
    r.token = t->token;
    long status = 0;
    if (curl_easy_getinfo(t->easy, CURLINFO_RESPONSE_CODE, &status) == CURLE_OK)
      r.status = static_cast<int>(status);
    curl_off_t received = 0, declared = -1;
    if (curl_easy_getinfo(t->easy, CURLINFO_SIZE_DOWNLOAD_T, &received) == CURLE_OK && received > 0)
      r.bytes_received = static_cast<uint64_t>(received);
    if (curl_easy_getinfo(t->easy, CURLINFO_CONTENT_LENGTH_DOWNLOAD_T, &declared) != CURLE_OK)
      declared = -1;
    r.failure = classify(rc);
    if (r.failure != TransferFailure::kNone) {
      r.error = t->error[0] ? std::string(t->error) : std::string(curl_easy_strerror(rc));
    } else if (r.status >= 200 && r.status < 300 && r.status != 204 && declared >= 0 &&
               received < declared) {
      // libcurl reports CURLE_PARTIAL_FILE for most short bodies; this
      // catches the rest (a stream ended early without an error).
      r.failure = TransferFailure::kRetryable;
      r.error = "truncated body: " + std::to_string(received) + " of " + std::to_string(declared) +
                " bytes";
    }
    r.body = std::move(t->body);
    r.headers = std::move(t->headers_in);
    curl_multi_remove_handle(impl_->multi, t->easy);
    impl_->transfers.erase(it);  // frees t
    done.push_back(std::move(r));
  }
  return done;
}

void CurlMulti::wait(int timeout_ms) {
  const CURLMcode rc = curl_multi_poll(impl_->multi, nullptr, 0, std::max(0, timeout_ms), nullptr);
  if (rc != CURLM_OK) throw NetError(std::string("libcurl: ") + curl_multi_strerror(rc));
}

void CurlMulti::wakeup() {
  // Fails only on a handle that is not a multi one: nothing to report then.
  (void)curl_multi_wakeup(impl_->multi);
}

size_t CurlMulti::running() const {
  return impl_->transfers.size();
}

}  // namespace globe::net::detail
