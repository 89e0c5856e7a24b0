// Shapes read from files: the real models of Debian's libcgal-demo data (fetched into a cache by
// scripts/fetch_data.sh, docs/design.md §7) and arbitrary point / mesh files.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "framework/core/error.hpp"
#include "framework/datasets/dataset.hpp"
#include "framework/datasets/internal.hpp"
#include "framework/io/io.hpp"

namespace dtsl {

std::string data_cache_dir() {
  // Same order and the same "empty counts as unset" rule as scripts/fetch_data.sh's
  // ${DTSL_DATA_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/dtsl}.
  auto env = [](const char* name) -> std::string {
    const char* v = std::getenv(name);
    return v ? std::string(v) : std::string();
  };
  if (const std::string d = env("DTSL_DATA_DIR"); !d.empty()) return d;
  if (const std::string x = env("XDG_CACHE_HOME"); !x.empty()) return x + "/dtsl";
  if (const std::string home = env("HOME"); !home.empty()) return home + "/.cache/dtsl";
  throw FileError("$HOME", "not set, so the data cache has no default place; set DTSL_DATA_DIR");
}

namespace dataset_detail {

namespace {

namespace fs = std::filesystem;

bool is_file(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

/// Names of the *.off files in `dir`, sorted; empty if the folder cannot be read.
std::vector<std::string> off_models(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".off") names.push_back(it->path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// A relative path is taken from the working directory if it exists there, else from the repository
/// root, so the configs under configs/ can name files of the repository whatever directory dtsl runs in.
std::string resolve(const std::string& path) {
  if (path.empty() || path[0] == '/' || is_file(path)) return path;
#ifdef DTSL_SOURCE_DIR
  const std::string in_repo = std::string(DTSL_SOURCE_DIR) + "/" + path;
  if (is_file(in_repo)) return in_repo;
#endif
  return path;  // reading it reports the missing file under the name the user wrote
}

/// Ground truth read from a file: outward orientation (a model stored inside-out would give every
/// baseline that uses ground-truth normals inverted normals), vertex normals kept if the file has them.
TriangleMesh read_ground_truth(const std::string& path) {
  TriangleMesh mesh = read_mesh(path);
  if (mesh.faces.empty()) throw FileError(path, "has no faces: a ground truth must be a surface mesh");
  orient_outward(mesh);
  return mesh;
}

// ---- cgal_model -------------------------------------------------------------------------------

struct CgalModelOptions final : Options {
  std::string model = "fandisk";

  void visit(FieldVisitor& v) override {
    v.field("model", model,
            "name of a mesh in libcgal-demo's data/meshes/<model>.off (fandisk, bunny00, armadillo, knot, "
            "elephant-with-holes, blade, ...); run scripts/fetch_data.sh once to download them");
  }
  void check() const override {
    require(!model.empty(), "model", "must name a model, got ''");
    require(model.find('/') == std::string::npos && model != "." && model != "..", "model",
            "must be a bare model name without '/', got '" + model + "'");
  }
};

class CgalModel final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  ShapeData load() override {
    const std::string dir = data_cache_dir() + "/cgal-demo/data/meshes";
    const std::string path = dir + "/" + o_.model + ".off";
    if (!is_file(path)) {
      const std::vector<std::string> known = off_models(dir);
      if (known.empty())
        throw FileError(path, "not found: the libcgal-demo models are not in the data cache; run "
                              "scripts/fetch_data.sh (it needs no root) to download them");
      std::string list;
      for (const std::string& n : known) list += (list.empty() ? "" : ", ") + n;
      throw FileError(path, "not found: no model '" + o_.model + "' in the data cache; known: " + list);
    }
    ShapeData d;
    d.mesh = read_ground_truth(path);
    d.exact = false;
    return d;
  }

 private:
  CgalModelOptions o_;
};

// ---- file -------------------------------------------------------------------------------------

struct FileOptions final : Options {
  std::string points;
  std::string ground_truth;

  void visit(FieldVisitor& v) override {
    v.field("points", points,
            "point file (.ply .obj .off .xyz .pcd; a mesh file's vertices); its normals are kept if it "
            "has them. Relative paths: from the working directory, else from the repository root");
    v.field("ground_truth", ground_truth,
            "optional mesh file (.ply .obj .off) of the true surface, for the metrics; without `points` "
            "it is the surface a sampler draws from");
  }
  void check() const override {
    require(!points.empty() || !ground_truth.empty(), "points",
            "is required unless ground_truth is given (then a sampler draws the points from it)");
  }
};

class File final : public ShapeSource {
 public:
  Options& options() override { return o_; }
  bool supplies_points() const override { return !o_.points.empty(); }
  ShapeData load() override {
    ShapeData d;
    if (!o_.points.empty()) d.points = read_points(resolve(o_.points));
    if (!o_.ground_truth.empty()) d.mesh = read_ground_truth(resolve(o_.ground_truth));
    d.exact = false;
    return d;
  }

 private:
  FileOptions o_;
};

}  // namespace

void register_model_shapes() {
  shape_sources().add("cgal_model", "a mesh of Debian's libcgal-demo data (scripts/fetch_data.sh)",
                      [] { return std::make_unique<CgalModel>(); });
  shape_sources().add("file", "points from a file, with an optional ground-truth mesh file",
                      [] { return std::make_unique<File>(); });
}

}  // namespace dataset_detail
}  // namespace dtsl
