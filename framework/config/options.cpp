#include "framework/config/options.hpp"

#include <sstream>

#include "framework/core/error.hpp"

namespace dtsl {

namespace {
template <class T>
std::string str(const T& v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}
}  // namespace

void require(bool ok, const char* field, const std::string& rule) {
  if (!ok) throw ConfigError(std::string(field) + ": " + rule);
}

void check_range(const char* field, int value, int lo, int hi) {
  require(value >= lo && value <= hi, field,
          "must be in [" + str(lo) + ", " + str(hi) + "], got " + str(value));
}

void check_range(const char* field, double value, double lo, double hi) {
  require(value >= lo && value <= hi, field,
          "must be in [" + str(lo) + ", " + str(hi) + "], got " + str(value));
}

void check_positive(const char* field, double value) {
  require(value > 0.0, field, "must be positive, got " + str(value));
}

void check_non_negative(const char* field, double value) {
  require(value >= 0.0, field, "must not be negative, got " + str(value));
}

void check_one_of(const char* field, const std::string& value,
                  std::initializer_list<const char*> allowed) {
  std::string list;
  for (const char* a : allowed) {
    if (value == a) return;
    list += list.empty() ? a : std::string(", ") + a;
  }
  throw ConfigError(std::string(field) + ": must be one of {" + list + "}, got '" + value + "'");
}

}  // namespace dtsl
