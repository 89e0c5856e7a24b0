#include "experiments/cli.hpp"

#include <stdexcept>

#include "framework/core/suggest.hpp"

namespace dtsl::cli {

std::vector<std::string> Args::values(const std::string& name) {
  std::vector<std::string> out, rest;
  const std::string opt = "--" + name;
  known_.push_back(opt);
  for (std::size_t i = 0; i < args_.size(); ++i) {
    const std::string& a = args_[i];
    if (a == opt) {
      if (i + 1 >= args_.size()) throw UsageError{opt + " needs a value"};
      out.push_back(args_[++i]);
    } else if (a.compare(0, opt.size() + 1, opt + "=") == 0) {
      out.push_back(a.substr(opt.size() + 1));
    } else {
      rest.push_back(a);
    }
  }
  args_ = rest;
  return out;
}

std::string Args::value(const std::string& name, const std::string& fallback) {
  const std::vector<std::string> v = values(name);
  if (v.size() > 1) throw UsageError{"--" + name + " given more than once"};
  return v.empty() ? fallback : v.front();
}

bool Args::flag(const std::string& name) {
  std::vector<std::string> rest;
  bool found = false;
  known_.push_back("--" + name);
  for (const std::string& a : args_) {
    if (a == "--" + name) found = true;
    else rest.push_back(a);
  }
  args_ = rest;
  return found;
}

std::vector<std::string> Args::positionals() {
  for (const std::string& a : args_)
    if (a.size() > 1 && a[0] == '-' && a[1] == '-') {
      const std::string option = a.substr(0, a.find('='));
      throw UsageError{"unknown option '" + option + "'" + did_you_mean(option, known_)};
    }
  return args_;
}

int Args::integer(const std::string& name, const std::string& text, int min, int max) {
  long value = 0;
  try {
    std::size_t used = 0;
    value = std::stol(text, &used);
    if (used != text.size()) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    throw UsageError{"--" + name + ": expected a whole number, got '" + text + "'"};
  }
  if (value < min || value > max)
    throw UsageError{"--" + name + ": must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + text};
  return int(value);
}

}  // namespace dtsl::cli
