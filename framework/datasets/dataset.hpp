// Datasets (docs/design.md §7): a shape (synthetic with exact ground truth, a real model from Debian's
// libcgal-demo data, or a file), a sampler that turns it into points, and corruptions applied in
// order, each a plugin with options and a seed. Shape and ground truth are first normalised into
// [-1,1]^3, so every length parameter (noise sigma, hole radius) is in the paper's frame; after
// corruption, points and ground truth are normalised together once more by the points' box, as the
// paper normalises its inputs.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "framework/config/options.hpp"
#include "framework/core/types.hpp"
#include "framework/registry/registry.hpp"

namespace YAML {
class Node;
}

namespace dtsl {

/// What a shape source yields: a surface mesh (ground truth), or just points (a file of points), or both.
struct ShapeData {
  std::optional<TriangleMesh> mesh;   ///< ground-truth surface, with vertex normals if known
  std::optional<PointCloud> points;   ///< ready-made points (file sources); then the sampler must be `none`
  bool exact = false;                 ///< the mesh is a fine tessellation of an analytic surface
};

class ShapeSource {
 public:
  virtual ~ShapeSource() = default;
  virtual Options& options() = 0;
  virtual ShapeData load() = 0;  ///< throws FileError / AlgorithmError
  /// Whether load() will return ready-made points (then the sampler must be `none`); known from the
  /// options alone, so parse_dataset can reject a mismatched sampler before anything is loaded.
  virtual bool supplies_points() const { return false; }
};

class Sampler {
 public:
  virtual ~Sampler() = default;
  virtual Options& options() = 0;
  /// Points (with the ground truth's normals at each point) from `shape`.
  virtual PointCloud sample(const ShapeData& shape, std::mt19937_64& rng) = 0;
};

class Corruption {
 public:
  virtual ~Corruption() = default;
  virtual Options& options() = 0;
  /// Changes `cloud` in place; normals (if any) stay those of the clean surface at each point.
  virtual void apply(PointCloud& cloud, std::mt19937_64& rng) = 0;
  /// What the last apply() did beyond the point counts (e.g. the hole centres), for the dataset's
  /// description; an empty object if nothing.
  virtual nlohmann::json report() const { return nlohmann::json::object(); }
};

Registry<ShapeSource>& shape_sources();
Registry<Sampler>& samplers();
Registry<Corruption>& corruptions();
void register_dataset_plugins();  ///< idempotent

/// A parsed `datasets:` entry of an experiment.
struct DatasetSpec {
  std::string name;
  std::string shape_type, sampler_type;
  std::unique_ptr<ShapeSource> shape;
  std::unique_ptr<Sampler> sampler;
  std::vector<std::pair<std::string, std::unique_ptr<Corruption>>> corruptions;
  int seed_offset = 0;  ///< added to the experiment seed, so datasets differ even with one seed
};

/// Parses one entry; ConfigError naming the key path under `context` (e.g. "datasets[2]") on any
/// unknown key, unknown plugin or bad option. The syntax (a plugin is a bare name, or a map of `type`
/// and that plugin's options):
///
///     name: fandisk_cut            # required; letters, digits, '_', '-', '.'
///     shape: {type: cgal_model, model: fandisk}
///     sampler: vertices            # optional: `none` for shapes that supply points, else `vertices`
///     corruptions:                 # optional; applied in order
///       - {type: plane_cut, normal: [0, 0, 1], offset: 0.3}
///       - {type: noise, sigma: 0.002}
///     seed: 3                      # optional, default 0: added to the experiment seed
DatasetSpec parse_dataset(const YAML::Node& node, const std::string& context);

struct Dataset {
  std::string name;
  PointCloud points;  ///< in [-1,1]^3; normals the ground truth's where known (outliers: random unit)
  std::optional<TriangleMesh> ground_truth;  ///< in the same frame
  nlohmann::json description;                ///< shape, sampler, corruptions with their options; counts; seed
  /// The map from the input's units (the model file's, or a synthetic shape's own) into the frame of
  /// `points` and `ground_truth`: what meshes are mapped back with to be written in the input's units.
  Similarity normalisation;
};

/// Where an experiment's files (dataset points and truth, every mesh and line set of its runs) are:
/// in the input's units (the model file's), or in the [-1,1]^3 frame the methods work and are measured in.
enum class FilesFrame { input, normalised };

/// {"center": [x, y, z], "scale": s}, as dataset descriptions record normalisations.
nlohmann::json to_json(const Similarity& s);

/// Loads, normalises the shape into [-1,1]^3, samples, corrupts, then normalises points and ground
/// truth together by the points' box. Deterministic (for a given standard library, whose random
/// distributions are implementation-defined): the sampler and each corruption get their own
/// generator, seeded in turn from one seeded by seed + spec.seed_offset, so changing one corruption's
/// options does not move the random choices of the others. Throws AlgorithmError naming the dataset
/// if no point remains, a coordinate is not finite, or all points coincide.
Dataset build_dataset(DatasetSpec& spec, std::uint64_t seed);

/// The folder the fetched model data lives in: $DTSL_DATA_DIR, else $XDG_CACHE_HOME/dtsl, else
/// ~/.cache/dtsl.
std::string data_cache_dir();

}  // namespace dtsl
