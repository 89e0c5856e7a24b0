// Nested options under a name prefix ("sharp_", "evolution_"): a stage that embeds another stage's options
// visits them under a prefix, so YAML, --set and `dtsl list` see one flat list of fields.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/core/error.hpp"

namespace dtsl {

/// Forwards every field to `inner` under `prefix` + name (the names live as long as the visitor).
class PrefixedVisitor final : public FieldVisitor {
 public:
  PrefixedVisitor(FieldVisitor& inner, std::string prefix) : inner_(inner), prefix_(std::move(prefix)) {}
  void field(const char* n, bool& v, const char* d) override { inner_.field(name(n), v, d); }
  void field(const char* n, int& v, const char* d) override { inner_.field(name(n), v, d); }
  void field(const char* n, double& v, const char* d) override { inner_.field(name(n), v, d); }
  void field(const char* n, std::string& v, const char* d) override { inner_.field(name(n), v, d); }
  void field(const char* n, std::vector<double>& v, const char* d) override { inner_.field(name(n), v, d); }

 private:
  const char* name(const char* n) {
    names_.push_back(prefix_ + n);
    return names_.back().c_str();
  }
  FieldVisitor& inner_;
  std::string prefix_;
  std::deque<std::string> names_;
};

/// Runs a nested check(), putting the prefix in front of the field its ConfigError names.
template <class Check>
void checked_with_prefix(const std::string& prefix, Check&& check) {
  try {
    check();
  } catch (const ConfigError& e) {
    throw ConfigError(prefix + e.what());
  }
}

}  // namespace dtsl
