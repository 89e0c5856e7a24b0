// Options structs: every plugin's parameters are a plain struct with defaults, a `visit` that lists
// each field with its name and a one-line doc, and a `check` that names the field and the rule it
// breaks. The visitor is what lets one generic piece of code read them from YAML, apply --set
// overrides, write them to JSON and print them in `dtsl list`, with no per-plugin parsing code.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

namespace dtsl {

/// Receives each field of an options struct in turn.
class FieldVisitor {
 public:
  virtual ~FieldVisitor() = default;
  virtual void field(const char* name, bool& value, const char* doc) = 0;
  virtual void field(const char* name, int& value, const char* doc) = 0;
  virtual void field(const char* name, double& value, const char* doc) = 0;
  virtual void field(const char* name, std::string& value, const char* doc) = 0;
  virtual void field(const char* name, std::vector<double>& value, const char* doc) = 0;
};

/// Base of every options struct. `visit` must list every field; `check` throws ConfigError (via the
/// helpers below) naming the field and the broken rule.
struct Options {
  virtual ~Options() = default;
  virtual void visit(FieldVisitor& v) = 0;
  virtual void check() const {}
};

/// An options struct with no fields.
struct NoOptions final : Options {
  void visit(FieldVisitor&) override {}
};

// Helpers for check(): each throws ConfigError("<field> must ..., got <value>").
void require(bool ok, const char* field, const std::string& rule);
void check_range(const char* field, int value, int lo, int hi);
void check_range(const char* field, double value, double lo, double hi);
void check_positive(const char* field, double value);
void check_non_negative(const char* field, double value);
void check_one_of(const char* field, const std::string& value,
                  std::initializer_list<const char*> allowed);

}  // namespace dtsl
