// A dataset entry of an experiment: parsing it from YAML, and building its points and ground truth.
#include "framework/datasets/dataset.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <tuple>

#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/datasets/internal.hpp"

namespace dtsl {

namespace {

std::string shown(const YAML::Node& n) {
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  return "nothing";
}

template <class Plugin>
std::string known_names(const Registry<Plugin>& registry) {
  std::string s;
  for (const std::string& n : registry.names()) s += (s.empty() ? "" : ", ") + n;
  return s;
}

/// A plugin given as a bare name ("vertices") or as a map of `type` and that plugin's options
/// ({type: area, count: 5000}). Returns its type and the plugin with its options applied and checked.
template <class Plugin>
std::pair<std::string, std::unique_ptr<Plugin>> parse_plugin(const Registry<Plugin>& registry,
                                                             const YAML::Node& node, const std::string& key) {
  if (node.IsScalar()) {
    std::unique_ptr<Plugin> plugin = registry.create(node.Scalar(), key);
    apply_yaml(plugin->options(), YAML::Node(), key);  // check() the defaults, for uniformity
    return {node.Scalar(), std::move(plugin)};
  }
  if (!node.IsMap())
    throw ConfigError(key + ": expected a " + registry.kind() + " name or a map with 'type' and options, got " +
                      shown(node));
  const YAML::Node type = node["type"];
  if (!type.IsDefined())
    throw ConfigError(key + ": missing 'type' (one of: " + known_names(registry) + ")");
  if (!type.IsScalar()) throw ConfigError(key + ".type: expected a " + registry.kind() + " name, got " + shown(type));
  std::unique_ptr<Plugin> plugin = registry.create(type.Scalar(), key + ".type");
  // The options sit beside `type`; everything else must be an option of this plugin.
  YAML::Node options(YAML::NodeType::Map);
  for (auto it = node.begin(); it != node.end(); ++it) {
    if (!it->first.IsScalar()) throw ConfigError(key + ": a key is " + shown(it->first) + ", not a name");
    if (it->first.Scalar() != "type") options[it->first] = it->second;
  }
  apply_yaml(plugin->options(), options, key);
  return {type.Scalar(), std::move(plugin)};
}

/// Dataset names become folder and table-row names: keep them to a portable set of characters.
void check_name(const std::string& name, const std::string& key) {
  bool ok = !name.empty() && name[0] != '.' && name.size() <= 128;
  for (const char c : name)
    ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.');
  if (!ok)
    throw ConfigError(key + ": must be 1-128 characters of letters, digits, '_', '-', '.' (not starting "
                            "with '.'), got '" + name + "'");
}

int parse_int(const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar()) throw ConfigError(key + ": expected an integer, got " + shown(n));
  const std::string& s = n.Scalar();
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE)
    throw ConfigError(key + ": expected an integer, got '" + s + "'");
  if (v < -1000000000LL || v > 1000000000LL)
    throw ConfigError(key + ": must be in [-1000000000, 1000000000], got " + s);
  return static_cast<int>(v);
}

/// The vertices a shape's box should be taken from: those of some face (a stray vertex far away would
/// otherwise shrink the shape), or all of them for a mesh without faces.
std::vector<Vec3> surface_vertices(const TriangleMesh& mesh) {
  if (mesh.faces.empty()) return mesh.vertices;
  const std::vector<bool> used = dataset_detail::referenced_vertices(mesh);
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) out.push_back(mesh.vertices[i]);
  return out;
}

}  // namespace

nlohmann::json to_json(const Similarity& s) {
  return {{"center", {s.center.x(), s.center.y(), s.center.z()}}, {"scale", s.scale}};
}

DatasetSpec parse_dataset(const YAML::Node& node, const std::string& context) {
  register_dataset_plugins();
  if (!node.IsMap())
    throw ConfigError(context + ": expected a map with name, shape, sampler, corruptions, seed; got " +
                      shown(node));
  static const char* const keys[] = {"name", "shape", "sampler", "corruptions", "seed"};
  for (auto it = node.begin(); it != node.end(); ++it) {
    if (!it->first.IsScalar()) throw ConfigError(context + ": a key is " + shown(it->first) + ", not a name");
    const std::string k = it->first.Scalar();
    if (std::find(std::begin(keys), std::end(keys), k) == std::end(keys))
      throw ConfigError(context + "." + k + ": unknown key; known keys: name, shape, sampler, corruptions, seed");
  }

  DatasetSpec spec;
  const YAML::Node name = node["name"];
  if (!name.IsDefined() || name.IsNull())
    throw ConfigError(context + ".name: missing (every dataset needs a name: it names its results)");
  if (!name.IsScalar()) throw ConfigError(context + ".name: expected a string, got " + shown(name));
  spec.name = name.Scalar();
  check_name(spec.name, context + ".name");

  const YAML::Node shape = node["shape"];
  if (!shape.IsDefined() || shape.IsNull())
    throw ConfigError(context + ".shape: missing (one of: " + known_names(shape_sources()) + ")");
  std::tie(spec.shape_type, spec.shape) = parse_plugin(shape_sources(), shape, context + ".shape");

  // The sampler must match what the shape gives: its own points (only `none` passes them on) or a
  // surface to draw from (anything but `none`).
  const bool own_points = spec.shape->supplies_points();
  const YAML::Node sampler = node["sampler"];
  if (sampler.IsDefined() && !sampler.IsNull()) {
    std::tie(spec.sampler_type, spec.sampler) = parse_plugin(samplers(), sampler, context + ".sampler");
  } else {
    spec.sampler_type = own_points ? "none" : "vertices";
    spec.sampler = samplers().create(spec.sampler_type, context + ".sampler");
  }
  if (own_points && spec.sampler_type != "none")
    throw ConfigError(context + ".sampler: shape '" + spec.shape_type +
                      "' supplies its own points (`points` is set), so the sampler must be 'none', got '" +
                      spec.sampler_type + "'");
  if (!own_points && spec.sampler_type == "none")
    throw ConfigError(context + ".sampler: 'none' passes on the shape's own points, but shape '" +
                      spec.shape_type + "' has none; use a sampler of its surface (" +
                      known_names(samplers()) + ")");

  if (const YAML::Node list = node["corruptions"]; list.IsDefined() && !list.IsNull()) {
    if (!list.IsSequence())
      throw ConfigError(context + ".corruptions: expected a list of corruptions, got " + shown(list));
    for (std::size_t i = 0; i < list.size(); ++i)
      spec.corruptions.push_back(
          parse_plugin(corruptions(), list[i], context + ".corruptions[" + std::to_string(i) + "]"));
  }

  if (const YAML::Node seed = node["seed"]; seed.IsDefined() && !seed.IsNull())
    spec.seed_offset = parse_int(seed, context + ".seed");
  return spec;
}

Dataset build_dataset(DatasetSpec& spec, std::uint64_t seed) {
  const std::string what = "dataset '" + spec.name + "'";
  // Plugins report problems without knowing the dataset; name it for the user.
  auto named = [&](const auto& step) {
    try {
      return step();
    } catch (const AlgorithmError& e) {
      throw AlgorithmError(what + ": " + e.what());
    }
  };

  ShapeData shape = named([&] { return spec.shape->load(); });
  if (!shape.mesh && !shape.points) throw AlgorithmError(what + ": shape '" + spec.shape_type + "' gave nothing");
  if (shape.mesh) check_finite(*shape.mesh, what + ", ground truth");
  if (shape.points) check_finite(*shape.points, what + ", input points");

  // Into [-1,1]^3 before sampling, so every length option below is in the paper's frame whatever the
  // model's units (armadillo spans about 100, fandisk about 0.3).
  const Similarity to_shape_frame = unit_cube_normalisation(
      shape.mesh ? surface_vertices(*shape.mesh) : shape.points->points, what + ", shape");
  if (shape.mesh) transform(*shape.mesh, to_shape_frame);
  if (shape.points) transform(*shape.points, to_shape_frame);

  // One generator per stage, each seeded from the dataset's generator in turn: a stage's random
  // choices depend on the seed and its position only, not on how many numbers earlier stages drew.
  const std::uint64_t effective_seed = seed + static_cast<std::uint64_t>(static_cast<std::int64_t>(spec.seed_offset));
  std::seed_seq seq{static_cast<std::uint32_t>(effective_seed), static_cast<std::uint32_t>(effective_seed >> 32)};
  std::mt19937_64 dataset_rng(seq);

  nlohmann::json d;
  d["name"] = spec.name;
  d["seed"] = effective_seed;
  d["experiment_seed"] = seed;
  d["seed_offset"] = spec.seed_offset;
  d["shape"] = {{"type", spec.shape_type}, {"options", to_json(spec.shape->options())}, {"exact", shape.exact}};
  if (shape.mesh)
    d["shape"]["ground_truth"] = {{"vertices", shape.mesh->vertices.size()}, {"faces", shape.mesh->faces.size()}};
  if (shape.points) d["shape"]["points"] = shape.points->size();

  std::mt19937_64 sampler_rng(dataset_rng());
  PointCloud cloud = named([&] { return spec.sampler->sample(shape, sampler_rng); });
  d["sampler"] = {{"type", spec.sampler_type}, {"options", to_json(spec.sampler->options())}, {"points", cloud.size()}};
  if (cloud.empty()) throw AlgorithmError(what + ": sampler '" + spec.sampler_type + "' gave no point");

  d["corruptions"] = nlohmann::json::array();
  for (std::size_t i = 0; i < spec.corruptions.size(); ++i) {
    // Not a structured binding: C++17 lambdas cannot capture those (clang refuses; gcc allows).
    const std::string& type = spec.corruptions[i].first;
    auto& corruption = spec.corruptions[i].second;
    std::mt19937_64 rng(dataset_rng());
    const std::size_t before = cloud.size();
    named([&] {
      corruption->apply(cloud, rng);
      return 0;
    });
    nlohmann::json c = {{"type", type}, {"options", to_json(corruption->options())},
                        {"points_before", before}, {"points_after", cloud.size()}};
    const nlohmann::json report = corruption->report();
    if (!report.empty()) c["report"] = report;
    d["corruptions"].push_back(c);
    if (cloud.empty())
      throw AlgorithmError(what + ": no point remains after corruption '" + type + "' (corruptions[" +
                           std::to_string(i) + "]), which removed all " + std::to_string(before));
  }
  check_finite(cloud, what);

  // As the paper normalises its inputs: by the points' box, the ground truth moved with them.
  const Similarity to_points_frame = unit_cube_normalisation(cloud.points, what);
  transform(cloud, to_points_frame);
  if (shape.mesh) transform(*shape.mesh, to_points_frame);

  d["points"] = cloud.size();
  d["normals"] = cloud.has_normals() ? "ground_truth" : "none";
  const Similarity normalisation = to_shape_frame.then(to_points_frame);
  d["normalisation"] = {{"shape", to_json(to_shape_frame)}, {"points", to_json(to_points_frame)},
                        {"input_to_points", to_json(normalisation)}};

  Dataset out;
  out.name = spec.name;
  out.points = std::move(cloud);
  out.ground_truth = std::move(shape.mesh);
  out.description = std::move(d);
  out.normalisation = normalisation;
  return out;
}

}  // namespace dtsl
