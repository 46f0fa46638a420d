// Progress reporting on stderr: a throttled bar on a TTY (phase, done/total,
// rate, ETA), one JSON object per line with --progress json, silent with -q.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace globe {

enum class ProgressMode { kAuto, kQuiet, kJson };

class Progress {
 public:
  explicit Progress(ProgressMode mode);
  void begin(const std::string& phase, uint64_t total);
  void advance(uint64_t n = 1);
  void end();  // finishes the current phase (prints a final line)
  // A human message on stderr unless quiet (JSON mode wraps it).
  void note(const std::string& message);
  bool quiet() const { return mode_ == ProgressMode::kQuiet; }

 private:
  void print(bool final);
  ProgressMode mode_;
  bool tty_ = false;
  std::string phase_;
  uint64_t total_ = 0, done_ = 0;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace globe
