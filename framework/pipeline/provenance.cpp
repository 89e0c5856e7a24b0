#include "framework/pipeline/provenance.hpp"

#include <sys/utsname.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>

#include "framework/core/allocator.hpp"

namespace dtsl {

namespace {

/// First line printed by `command`, or "" if it fails (no git, not a checkout).
std::string first_line_of(const std::string& command) {
  FILE* pipe = ::popen((command + " 2>/dev/null").c_str(), "r");
  if (!pipe) return "";
  std::array<char, 512> buf{};
  std::string out;
  if (std::fgets(buf.data(), buf.size(), pipe)) out = buf.data();
  ::pclose(pipe);
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string proc_field(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.compare(0, key.size(), key) == 0) {
      const auto colon = line.find(':');
      std::string v = colon == std::string::npos ? "" : line.substr(colon + 1);
      v.erase(0, v.find_first_not_of(" \t"));
      return v;
    }
  return "";
}

}  // namespace

nlohmann::json provenance(const std::vector<std::string>& command_line) {
  nlohmann::json j;
  const std::string git = std::string("git -C '") + DTSL_SOURCE_DIR + "' ";
  j["git_commit"] = first_line_of(git + "rev-parse HEAD");
  j["git_dirty"] = !first_line_of(git + "status --porcelain --untracked-files=no").empty();
  j["libraries"] = DTSL_LIBRARY_VERSIONS;
#ifdef __VERSION__
  j["compiler"] = __VERSION__;
#endif
  utsname u{};
  ::uname(&u);
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const std::string mem_kib = proc_field("/proc/meminfo", "MemTotal");
  j["machine"] = {{"hostname", host},
                  {"os", std::string(u.sysname) + " " + u.release + " " + u.machine},
                  {"cpu", proc_field("/proc/cpuinfo", "model name")},
                  {"cores", std::thread::hardware_concurrency()},
                  {"memory_gib", mem_kib.empty() ? 0.0 : std::stod(mem_kib) / (1024.0 * 1024.0)}};
  j["allocator"] = allocator_configuration();  // it moves timings by a quarter (allocator.hpp)
  j["command"] = command_line;
  std::time_t now = std::time(nullptr);
  char when[32];
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  j["started_utc"] = when;
  return j;
}

}  // namespace dtsl
