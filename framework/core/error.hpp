// The exception family of dtsl. Every failure a user can cause (bad file, bad config, input a method
// cannot handle) is one of these, carrying enough context (file, line, key, value) to act on it.
#pragma once

#include <stdexcept>
#include <string>

namespace dtsl {

/// Base of every error dtsl reports to the user.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/// A file that is missing, unreadable or malformed. The message names the file and, where known, the
/// line (text formats) or byte offset (binary formats).
class FileError : public Error {
 public:
  FileError(const std::string& path, const std::string& problem, long line = -1)
      : Error(format(path, problem, line)), path_(path), line_(line) {}
  const std::string& path() const { return path_; }
  long line() const { return line_; }

 private:
  static std::string format(const std::string& path, const std::string& problem, long line) {
    return line >= 0 ? path + ":" + std::to_string(line) + ": " + problem : path + ": " + problem;
  }
  std::string path_;
  long line_;
};

/// A configuration error: unknown key, wrong type, value out of range, unknown plugin name. The message
/// starts with the dotted key path (e.g. "pipelines[1].options.depth").
class ConfigError : public Error {
 public:
  explicit ConfigError(const std::string& what) : Error(what) {}
};

/// Input a method cannot work with (too few points, degenerate geometry, a problem too large), or a
/// numerical failure it cannot recover from (a solver that did not converge).
class AlgorithmError : public Error {
 public:
  explicit AlgorithmError(const std::string& what) : Error(what) {}
};

}  // namespace dtsl
