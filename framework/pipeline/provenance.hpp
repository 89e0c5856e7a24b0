// What a result needs to be reproduced: code version, libraries, machine, command line, time.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace dtsl {

/// {git_commit, git_dirty, libraries, machine{hostname, os, cpu, cores, memory_gib}, command, started_utc}
nlohmann::json provenance(const std::vector<std::string>& command_line);

}  // namespace dtsl
