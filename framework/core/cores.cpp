#include "framework/core/cores.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace dtsl {

int free_cores() {
  const long online = std::max(1L, ::sysconf(_SC_NPROCESSORS_ONLN));
  // The fourth field is "running/total": the runnable tasks now, this process's calling thread included.
  std::ifstream loadavg("/proc/loadavg");
  double one, five, fifteen;
  std::string running_total;
  if (!(loadavg >> one >> five >> fifteen >> running_total)) return int(online);
  const std::size_t slash = running_total.find('/');
  long running = 0;
  try {
    running = std::stol(running_total.substr(0, slash));
  } catch (const std::exception&) {
    return int(online);
  }
  const long others = std::max(0L, running - 1);
  return int(std::clamp(online - others, 1L, online));
}

void set_threads(int threads) {
#ifdef _OPENMP
  omp_set_num_threads(std::max(1, threads));
#else
  (void)threads;
#endif
}

int current_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

int process_threads() {
  std::error_code ec;
  int threads = 0;
  for (std::filesystem::directory_iterator it("/proc/self/task", ec), end; !ec && it != end; it.increment(ec))
    ++threads;
  return std::max(1, threads);
}

}  // namespace dtsl
