// Plugin registries: every stage, dataset piece and baseline is created by name. A registry per plugin
// kind (reconstructor, shape, sampler, corruption, velocity, solver, ...) lists its entries with their
// options so `dtsl list` can print them. Registration is explicit (register_*() functions called once
// from plugins.cpp) rather than static initialisers, which static libraries would silently drop.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/core/error.hpp"
#include "framework/core/suggest.hpp"

namespace dtsl {

/// What `dtsl list` needs of any registry, whatever its plugin type.
class RegistryBase {
 public:
  struct Listing {
    std::string name, summary;
    std::function<std::unique_ptr<Options>()> default_options;
  };
  explicit RegistryBase(std::string kind) : kind_(std::move(kind)) {}
  virtual ~RegistryBase() = default;
  const std::string& kind() const { return kind_; }
  virtual std::vector<Listing> listings() const = 0;

  /// Every registry ever constructed, in creation order.
  static std::vector<const RegistryBase*>& all();

 private:
  std::string kind_;
};

/// A plugin type must provide `Options& options()`; its factory returns it with default options.
template <class Plugin>
class Registry final : public RegistryBase {
 public:
  using Factory = std::function<std::unique_ptr<Plugin>()>;

  explicit Registry(std::string kind) : RegistryBase(std::move(kind)) { all().push_back(this); }

  /// Registers `name`; a second registration of the same name is a programming error.
  void add(const std::string& name, const std::string& summary, Factory make) {
    if (entries_.count(name)) throw Error(kind() + " '" + name + "' registered twice");
    entries_[name] = Entry{summary, std::move(make)};
  }

  bool contains(const std::string& name) const { return entries_.count(name) > 0; }

  /// Creates `name` with default options; ConfigError naming `context` and the known names otherwise.
  std::unique_ptr<Plugin> create(const std::string& name, const std::string& context) const {
    auto it = entries_.find(name);
    if (it == entries_.end()) {
      std::string known;
      for (const auto& e : entries_) known += (known.empty() ? "" : ", ") + e.first;
      throw ConfigError(context + ": unknown " + kind() + " '" + name + "'" + did_you_mean(name, names()) + "; known: " +
                        (known.empty() ? "(none registered)" : known));
    }
    return it->second.make();
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : entries_) out.push_back(e.first);
    return out;
  }

  std::vector<Listing> listings() const override {
    std::vector<Listing> out;
    for (const auto& e : entries_) {
      Factory make = e.second.make;
      out.push_back({e.first, e.second.summary, [make]() -> std::unique_ptr<Options> {
                       return std::make_unique<Holder>(make());
                     }});
    }
    return out;
  }

 private:
  struct Entry {
    std::string summary;
    Factory make;
  };
  // Keeps a plugin alive while its options are listed.
  struct Holder final : Options {
    explicit Holder(std::unique_ptr<Plugin> p) : plugin(std::move(p)) {}
    void visit(FieldVisitor& v) override { plugin->options().visit(v); }
    void check() const override { plugin->options().check(); }
    std::unique_ptr<Plugin> plugin;
  };
  std::map<std::string, Entry> entries_;
};

}  // namespace dtsl
