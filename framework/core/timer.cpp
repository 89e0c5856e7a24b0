#include "framework/core/timer.hpp"

#include <sys/resource.h>

#include <algorithm>

namespace dtsl {

double peak_memory_mib() {
  rusage self{}, children{};
  getrusage(RUSAGE_SELF, &self);
  // An external reconstructor runs in a child process: its memory is the run's too.
  getrusage(RUSAGE_CHILDREN, &children);
  return static_cast<double>(std::max(self.ru_maxrss, children.ru_maxrss)) / 1024.0;  // KiB on Linux
}

}  // namespace dtsl
