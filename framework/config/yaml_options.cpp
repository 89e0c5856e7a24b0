#include "framework/config/yaml_options.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "framework/core/error.hpp"
#include "framework/core/suggest.hpp"

namespace dtsl {

namespace {

std::string scalar_text(const YAML::Node& n) {
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  return "nothing";
}

[[noreturn]] void type_error(const std::string& key, const char* expected, const YAML::Node& n) {
  throw ConfigError(key + ": expected " + expected + ", got " + scalar_text(n));
}

double parse_double(const std::string& key, const YAML::Node& n) {
  if (!n.IsScalar()) type_error(key, "a number", n);
  const std::string& s = n.Scalar();
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v)) type_error(key, "a finite number", n);
  return v;
}

/// Applies YAML values to fields, remembering which keys were used.
class YamlReader final : public FieldVisitor {
 public:
  YamlReader(const YAML::Node& node, std::string context) : node_(node), context_(std::move(context)) {}

  void field(const char* name, bool& value, const char* /*doc*/) override {
    if (const YAML::Node n = take(name)) {
      const std::string s = n.IsScalar() ? n.Scalar() : "";
      if (s == "true" || s == "True" || s == "yes" || s == "on") value = true;
      else if (s == "false" || s == "False" || s == "no" || s == "off") value = false;
      else type_error(key(name), "true or false", n);
    }
  }
  void field(const char* name, int& value, const char* /*doc*/) override {
    if (const YAML::Node n = take(name)) {
      double v = 0.5;
      try {
        v = parse_double(key(name), n);
      } catch (const ConfigError&) {
      }
      if (v != std::floor(v) || std::abs(v) > 2e9) type_error(key(name), "an integer", n);
      value = static_cast<int>(v);
    }
  }
  void field(const char* name, double& value, const char* /*doc*/) override {
    if (const YAML::Node n = take(name)) value = parse_double(key(name), n);
  }
  void field(const char* name, std::string& value, const char* /*doc*/) override {
    if (const YAML::Node n = take(name)) {
      if (!n.IsScalar()) type_error(key(name), "a string", n);
      value = n.Scalar();
    }
  }
  void field(const char* name, std::vector<double>& value, const char* /*doc*/) override {
    if (const YAML::Node n = take(name)) {
      if (n.IsScalar()) {
        value = {parse_double(key(name), n)};
        return;
      }
      if (!n.IsSequence()) type_error(key(name), "a list of numbers", n);
      value.clear();
      for (std::size_t i = 0; i < n.size(); ++i)
        value.push_back(parse_double(key(name) + "[" + std::to_string(i) + "]", n[i]));
    }
  }

  void finish() const {
    for (auto it = node_.begin(); it != node_.end(); ++it) {
      if (!it->first.IsScalar())
        throw ConfigError((context_.empty() ? std::string("options") : context_) + ": a key is " +
                          scalar_text(it->first) + ", not an option name");
      const std::string k = it->first.Scalar();
      if (!used_.count(k)) {
        std::string known;
        for (const std::string& n : names_) known += (known.empty() ? "" : ", ") + n;
        throw ConfigError(key(k.c_str()) + ": unknown key" + did_you_mean(k, names_) +
                          (known.empty() ? " (this plugin has no options)" : "; known keys: " + known));
      }
    }
  }

 private:
  YAML::Node take(const char* name) {
    names_.push_back(name);
    const YAML::Node n = node_[name];
    if (!n.IsDefined()) return YAML::Node(YAML::NodeType::Undefined);
    used_.insert(name);
    if (n.IsNull()) type_error(key(name), "a value", n);
    return n;
  }
  std::string key(const char* name) const { return context_.empty() ? name : context_ + "." + name; }

  const YAML::Node& node_;
  std::string context_;
  std::set<std::string> used_;
  std::vector<std::string> names_;
};

class JsonWriter final : public FieldVisitor {
 public:
  nlohmann::json out = nlohmann::json::object();
  void field(const char* n, bool& v, const char*) override { out[n] = v; }
  void field(const char* n, int& v, const char*) override { out[n] = v; }
  void field(const char* n, double& v, const char*) override { out[n] = v; }
  void field(const char* n, std::string& v, const char*) override { out[n] = v; }
  void field(const char* n, std::vector<double>& v, const char*) override { out[n] = v; }
};

class Describer final : public FieldVisitor {
 public:
  std::vector<FieldDescription> out;
  void field(const char* n, bool& v, const char* d) override { out.push_back({n, "bool", v ? "true" : "false", d}); }
  void field(const char* n, int& v, const char* d) override { out.push_back({n, "int", std::to_string(v), d}); }
  void field(const char* n, double& v, const char* d) override { out.push_back({n, "double", num(v), d}); }
  void field(const char* n, std::string& v, const char* d) override { out.push_back({n, "string", "'" + v + "'", d}); }
  void field(const char* n, std::vector<double>& v, const char* d) override {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + num(v[i]);
    out.push_back({n, "list", s + "]", d});
  }

 private:
  static std::string num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }
};

}  // namespace

void apply_yaml(Options& options, const YAML::Node& node, const std::string& context) {
  if (node.IsDefined() && !node.IsNull()) {
    if (!node.IsMap()) throw ConfigError(context + ": expected a map of options, got " + scalar_text(node));
    YamlReader reader(node, context);
    options.visit(reader);
    reader.finish();
  }
  try {
    options.check();
  } catch (const ConfigError& e) {
    throw ConfigError(context.empty() ? e.what() : context + "." + e.what());
  }
}

void apply_assignment(Options& options, const std::string& key, const std::string& value,
                      const std::string& context) {
  YAML::Node parsed;
  try {
    parsed = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    throw ConfigError(context + "." + key + ": cannot parse value '" + value + "'");
  }
  YAML::Node map(YAML::NodeType::Map);
  map[key] = parsed;
  apply_yaml(options, map, context);
}

nlohmann::json to_json(Options& options) {
  JsonWriter w;
  options.visit(w);
  return w.out;
}

std::vector<FieldDescription> describe(Options& options) {
  Describer d;
  options.visit(d);
  return d.out;
}

}  // namespace dtsl
