// Progress reporting (see progress.hpp).
#include "kit/progress.hpp"

#include "tileformat/json.hpp"

#include <unistd.h>

#include <cstdio>

namespace globe {
Progress::Progress(ProgressMode mode) : mode_(mode), tty_(isatty(STDERR_FILENO) != 0) {}

void Progress::begin(const std::string& phase, uint64_t total) {
  phase_ = phase;
  total_ = total;
  done_ = 0;
  start_ = last_ = std::chrono::steady_clock::now();
  if (mode_ == ProgressMode::kJson) print(false);
}

void Progress::advance(uint64_t n) {
  done_ += n;
  auto now = std::chrono::steady_clock::now();
  auto interval = mode_ == ProgressMode::kJson ? std::chrono::milliseconds(1000)
                                               : std::chrono::milliseconds(200);
  if (now - last_ >= interval) {
    last_ = now;
    print(false);
  }
}

void Progress::end() {
  print(true);
}

void Progress::note(const std::string& message) {
  if (mode_ == ProgressMode::kQuiet) return;
  if (mode_ == ProgressMode::kJson)
    std::fprintf(stderr, "{\"message\":\"%s\"}\n", tileformat::json_escape(message).c_str());
  else
    std::fprintf(stderr, "%s\n", message.c_str());
}

void Progress::print(bool final) {
  if (mode_ == ProgressMode::kQuiet) return;
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = secs > 0 ? done_ / secs : 0;
  const double eta = rate > 0 && total_ > done_ ? (total_ - done_) / rate : 0;
  if (mode_ == ProgressMode::kJson) {
    std::fprintf(stderr,
                 "{\"phase\":\"%s\",\"done\":%llu,\"total\":%llu,\"rate\":%.1f,\"eta_s\":%.1f,"
                 "\"final\":%s}\n",
                 tileformat::json_escape(phase_).c_str(), static_cast<unsigned long long>(done_),
                 static_cast<unsigned long long>(total_), rate, eta, final ? "true" : "false");
    return;
  }
  // Without a TTY: no redraws, and one line only for phases worth logging.
  if (!tty_ && (!final || secs < 1.0)) return;
  const int width = 30;
  const int filled = total_ ? static_cast<int>(width * static_cast<double>(done_) / total_) : width;
  std::string bar(filled, '#');
  bar.resize(width, '.');
  char tail[64];
  if (final)
    std::snprintf(tail, sizeof tail, "in %.1f s\n", secs);
  else
    std::snprintf(tail, sizeof tail, "ETA %.0f s   ", eta);
  std::fprintf(stderr, "%s%-22s [%s] %llu/%llu  %.0f/s  %s", tty_ ? "\r" : "", phase_.c_str(),
               bar.c_str(), static_cast<unsigned long long>(done_),
               static_cast<unsigned long long>(total_), rate, tail);
  std::fflush(stderr);
}

}  // namespace globe
