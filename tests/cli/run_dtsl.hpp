// Running the `dtsl` binary from a test: its exit code and everything it printed.
#pragma once

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <string>

namespace dtsl_cli_test {

struct Outcome {
  int code;            ///< exit code, or 128 + signal
  std::string output;  ///< stdout and stderr together
};

inline Outcome dtsl(const std::string& arguments) {
  const std::string command = std::string(DTSL_EXECUTABLE) + " " + arguments + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe);
  std::string out;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = ::pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), out};
}

}  // namespace dtsl_cli_test
