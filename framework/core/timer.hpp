// Wall-clock timing and peak-memory reading.
#pragma once

#include <chrono>

namespace dtsl {

class Stopwatch {
 public:
  Stopwatch() : start_(Clock::now()) {}
  void restart() { start_ = Clock::now(); }
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

/// Peak resident set size of this process so far, or of the largest child process it waited for if
/// larger (an external command), in MiB (getrusage ru_maxrss).
double peak_memory_mib();

}  // namespace dtsl
