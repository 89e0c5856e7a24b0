// The `dtsl` Python module: reconstruct a numpy point cloud with any registered pipeline, measure a mesh
// against a ground truth, read point and mesh files, and run an experiment config, each through the same
// framework functions the command line uses (reconstruct_command.cpp, run_command.cpp), so results and
// error messages are the same. Arrays are checked before any work; the GIL is released while C++ computes.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "experiments/plugins.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/core/timer.hpp"
#include "framework/io/io.hpp"
#include "framework/metrics/metrics.hpp"
#include "framework/pipeline/experiment.hpp"
#include "framework/pipeline/preset.hpp"
#include "framework/pipeline/reconstructor.hpp"
#include "framework/pipeline/runner.hpp"

namespace py = pybind11;

namespace dtsl::python {

namespace {

// ---- exceptions ---------------------------------------------------------------------------------

// The framework's error family as Python classes (dtsl.Error and subclasses), created once at import.
// ConfigError is also a ValueError and FileError an OSError, so generic Python handlers catch them too.
struct ErrorClasses {
  PyObject* error = nullptr;
  PyObject* config = nullptr;
  PyObject* file = nullptr;
  PyObject* algorithm = nullptr;
};
ErrorClasses g_errors;

PyObject* add_exception(py::module_& m, const char* name, py::tuple bases, const char* doc) {
  const std::string qualified = std::string("dtsl.") + name;
  PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (!cls) throw py::error_already_set();
  m.add_object(name, py::handle(cls));  // the module holds a reference; ours lives as long as the process
  return cls;
}

void register_errors(py::module_& m) {
  g_errors.error = add_exception(m, "Error", py::make_tuple(py::handle(PyExc_RuntimeError)),
                                 "Base of every error dtsl reports (framework/core/error.hpp).");
  const py::handle base(g_errors.error);
  g_errors.config = add_exception(m, "ConfigError", py::make_tuple(base, py::handle(PyExc_ValueError)),
                                  "Unknown key or plugin name, wrong type, value out of range.");
  g_errors.file = add_exception(m, "FileError", py::make_tuple(base, py::handle(PyExc_OSError)),
                                "A file that is missing, unreadable or malformed; the message names it.");
  g_errors.algorithm = add_exception(m, "AlgorithmError", py::make_tuple(base),
                                     "Input a method cannot handle, or a numerical failure.");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ConfigError& e) {
      PyErr_SetString(g_errors.config, e.what());
    } catch (const FileError& e) {
      PyErr_SetString(g_errors.file, e.what());
    } catch (const AlgorithmError& e) {
      PyErr_SetString(g_errors.algorithm, e.what());
    } catch (const Error& e) {
      PyErr_SetString(g_errors.error, e.what());
    }
  });
}

// ---- numpy <-> framework types ------------------------------------------------------------------

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// `object` as a 2-D numpy array with 3 columns whose dtype kind is one of `kinds` ("iuf": numbers);
/// ValueError naming `what` otherwise.
py::array table3(py::handle object, const std::string& what, const char* kinds, const char* expected) {
  py::array a;
  try {
    a = py::module_::import("numpy").attr("asarray")(object);
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_ValueError) && !e.matches(PyExc_TypeError)) throw;
    throw py::value_error(what + ": not convertible to an array: " + std::string(py::str(e.value())));
  }
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw py::value_error(what + ": expected an (n, 3) array, got shape " + shape_text(a));
  const char kind = a.dtype().kind();
  if (std::string(kinds).find(kind) == std::string::npos)
    throw py::value_error(what + ": expected " + expected + ", got dtype " + std::string(py::str(a.dtype())));
  return a;
}

std::string row_text(const double* r) {
  return "(" + std::string(py::str(py::float_(r[0]))) + ", " + std::string(py::str(py::float_(r[1]))) + ", " +
         std::string(py::str(py::float_(r[2]))) + ")";
}

/// An (n, 3) array of numbers (any layout) as points; ValueError naming `what` and the first row with a
/// NaN or infinite coordinate.
std::vector<Vec3> to_points(py::handle object, const std::string& what) {
  const py::array a = table3(object, what, "iuf", "numbers");
  using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
  const Doubles d = Doubles::ensure(a);
  if (!d) throw py::error_already_set();
  const auto n = static_cast<std::size_t>(d.shape(0));
  const double* p = d.data();
  std::vector<Vec3> out(n);
  for (std::size_t i = 0; i < n; ++i, p += 3) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw py::value_error(what + ": row " + std::to_string(i) + " is not finite " + row_text(p));
    out[i] = Vec3(p[0], p[1], p[2]);
  }
  return out;
}

/// A (vertices, faces) pair as a mesh; faces must be integers indexing the vertices.
TriangleMesh to_mesh(py::handle object, const std::string& what) {
  if (!py::isinstance<py::tuple>(object) && !py::isinstance<py::list>(object))
    throw py::value_error(what + ": expected a (vertices, faces) pair, got " +
                          std::string(py::str(py::type::handle_of(object).attr("__name__"))));
  const py::sequence pair = py::reinterpret_borrow<py::sequence>(object);
  if (pair.size() != 2)
    throw py::value_error(what + ": expected a (vertices, faces) pair, got " + std::to_string(pair.size()) +
                          " items");
  TriangleMesh mesh;
  mesh.vertices = to_points(pair[0], what + " vertices");
  const py::array f = table3(pair[1], what + " faces", "iu", "integers");
  using Indices = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
  const Indices idx = Indices::ensure(f);
  if (!idx) throw py::error_already_set();
  const std::int64_t nv = static_cast<std::int64_t>(mesh.vertices.size());
  const std::int64_t* q = idx.data();
  mesh.faces.resize(static_cast<std::size_t>(idx.shape(0)));
  for (std::size_t i = 0; i < mesh.faces.size(); ++i, q += 3)
    for (int c = 0; c < 3; ++c) {
      if (q[c] < 0 || q[c] >= nv)
        throw py::value_error(what + " faces: row " + std::to_string(i) + " has index " + std::to_string(q[c]) +
                              ", outside [0, " + std::to_string(nv) + ")");
      mesh.faces[i][c] = static_cast<int>(q[c]);
    }
  return mesh;
}

py::array_t<double> to_array(const std::vector<Vec3>& v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  double* p = a.mutable_data();
  for (const Vec3& x : v) {
    *p++ = x.x();
    *p++ = x.y();
    *p++ = x.z();
  }
  return a;
}

py::array_t<std::int64_t> to_array(const std::vector<Face>& faces) {
  py::array_t<std::int64_t> a({static_cast<py::ssize_t>(faces.size()), py::ssize_t{3}});
  std::int64_t* p = a.mutable_data();
  for (const Face& f : faces)
    for (int c : f) *p++ = c;
  return a;
}

py::object to_python(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null: return py::none();
    case nlohmann::json::value_t::boolean: return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(j.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(j.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: return py::float_(j.get<double>());
    case nlohmann::json::value_t::string: return py::str(j.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list out;
      for (const auto& x : j) out.append(to_python(x));
      return std::move(out);
    }
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (auto it = j.begin(); it != j.end(); ++it) out[py::str(it.key())] = to_python(it.value());
      return std::move(out);
    }
    default: return py::none();  // binary and discarded values never occur in dtsl's records
  }
}

// ---- options ------------------------------------------------------------------------------------

/// A keyword argument's value as the YAML node `--set KEY=VALUE` would have produced from its text, so
/// apply_yaml reports wrong types and ranges in the same words.
YAML::Node to_yaml(py::handle value, const std::string& key) {
  const py::module_ np = py::module_::import("numpy");
  if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
  if (py::isinstance<py::bool_>(value) || py::isinstance(value, np.attr("bool_")))
    return YAML::Node(value.cast<bool>() ? "true" : "false");
  if (py::isinstance<py::int_>(value) || py::isinstance(value, np.attr("integer")))
    return YAML::Node(std::string(py::str(py::int_(py::reinterpret_borrow<py::object>(value)))));
  if (py::isinstance<py::float_>(value) || py::isinstance(value, np.attr("floating")))
    return YAML::Node(std::string(py::str(py::float_(value.cast<double>()))));  // shortest round trip; "nan"
  if (py::isinstance<py::str>(value)) return YAML::Node(value.cast<std::string>());
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value) || py::isinstance<py::array>(value)) {
    YAML::Node seq(YAML::NodeType::Sequence);
    for (py::handle item : py::iter(value)) seq.push_back(to_yaml(item, key));
    return seq;
  }
  throw py::type_error("option '" + key + "': a " +
                       std::string(py::str(py::type::handle_of(value).attr("__name__"))) +
                       " cannot be an option value; use bool, int, float, str or a list of numbers");
}

/// Applies every option at once (one check() at the end, so interdependent options can be given in any
/// order); ConfigError "options.<key>: ..." as `--set` gives "--set.<key>: ...".
void apply_options(Options& options, const py::dict& kwargs) {
  YAML::Node map(YAML::NodeType::Map);
  for (auto item : kwargs) {
    const std::string key = py::str(item.first);
    map[key] = to_yaml(item.second, key);
  }
  apply_yaml(options, map, "options");
}

// ---- the module's functions ---------------------------------------------------------------------

/// f() with the GIL released: Python threads run while C++ computes (f must not touch Python objects).
template <class F>
auto without_gil(F&& f) {
  py::gil_scoped_release unlocked;
  return f();
}

std::uint64_t checked_seed(std::int64_t seed) {
  if (seed < 0) throw py::value_error("seed: expected a non-negative integer, got " + std::to_string(seed));
  return static_cast<std::uint64_t>(seed);
}

std::unique_ptr<Reconstructor> make_pipeline(const std::string& name) {
  return reconstructors().create(name, "pipeline");
}

/// `threads` and `seed` set the RunContext; every other keyword is an option (no pipeline has an option of
/// those two names: python/tests/test_dtsl.py checks every registered one).
py::tuple reconstruct(py::handle points, const std::string& pipeline_name, const std::optional<std::string>& preset,
                      int threads, std::int64_t seed, const py::kwargs& kwargs) {
  auto pipeline = make_pipeline(pipeline_name);
  apply_preset(*pipeline, pipeline_name, preset.value_or("default"), "preset");
  apply_options(pipeline->options(), kwargs);
  if (threads < 1) throw py::value_error("threads: expected at least 1, got " + std::to_string(threads));
  const std::uint64_t context_seed = checked_seed(seed);
  PointCloud cloud;
  cloud.points = to_points(points, "points");
  // As `dtsl reconstruct`: methods work in the paper's [-1,1]^3 frame; the mesh is mapped back.
  const Similarity frame = unit_cube_normalisation(cloud.points, "points");
  transform(cloud, frame);
  RunContext context;
  context.threads = threads;
  context.seed = context_seed;

  Stopwatch clock;
  ReconstructionResult result = without_gil([&] {
    ReconstructionResult r = pipeline->reconstruct(cloud, context);
    for (Vec3& v : r.mesh.vertices) v = frame.invert(v);
    return r;
  });
  const double seconds = clock.seconds();

  py::list stages;
  for (const StageRecord& s : result.stages) {
    py::dict stage;
    stage["name"] = s.name;
    stage["seconds"] = s.seconds;
    if (s.mesh) {
      stage["mesh_label"] = s.mesh_label.empty() ? s.name : s.mesh_label;
      stage["vertices"] = s.mesh->vertices.size();
      stage["faces"] = s.mesh->faces.size();
    }
    stage["summary"] = to_python(s.summary);
    stages.append(stage);
  }
  py::dict summary;
  summary["pipeline"] = pipeline_name;
  summary["preset"] = preset.value_or("default");
  summary["options"] = to_python(to_json(pipeline->options()));
  summary["points"] = cloud.size();
  summary["vertices"] = result.mesh.vertices.size();
  summary["faces"] = result.mesh.faces.size();
  summary["seconds"] = seconds;
  summary["summary"] = to_python(result.summary);
  summary["stages"] = stages;
  return py::make_tuple(to_array(result.mesh.vertices), to_array(result.mesh.faces), summary);
}

py::dict evaluate(py::handle mesh_object, py::handle truth_object, int samples, double tau_ratio,
                  std::int64_t seed) {
  MetricsOptions metrics;  // the experiment's defaults and ranges (experiment.hpp)
  metrics.samples = samples;
  metrics.fscore_tau_ratio = tau_ratio;
  metrics.check();
  const std::uint64_t sample_seed = checked_seed(seed);
  const TriangleMesh mesh = to_mesh(mesh_object, "mesh");
  const TriangleMesh truth = to_mesh(truth_object, "truth");
  const nlohmann::json record = without_gil([&] {
    nlohmann::json j = to_json(mesh_stats(mesh));
    if (!mesh.faces.empty())  // as measure_mesh (run_one.cpp): no surface metrics of an empty result
      j.update(to_json(compare_surfaces(mesh, truth, static_cast<std::size_t>(metrics.samples),
                                        metrics.fscore_tau_ratio, sample_seed)));
    return j;
  });
  return to_python(record);
}

std::string run(const std::filesystem::path& config, const std::filesystem::path& results,
                const std::optional<std::string>& run_id, int jobs, const std::vector<std::string>& overrides,
                bool progress) {
  if (jobs < 1) throw py::value_error("jobs: expected at least 1, got " + std::to_string(jobs));
  RunnerOptions options;
  options.results_root = results.string();
  options.jobs = jobs;
  options.progress = progress;
  if (run_id) {
    if (run_id->empty() ||
        run_id->find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") !=
            std::string::npos)
      throw py::value_error("run_id: use letters, digits, '_', '-', '.', got '" + *run_id + "'");
    options.run_id = *run_id;
  }
  options.command_line = {"dtsl.run", config.string(), "--results", options.results_root, "--jobs",
                          std::to_string(jobs)};
  if (run_id) options.command_line.insert(options.command_line.end(), {"--run-id", *run_id});
  for (const std::string& o : overrides) options.command_line.insert(options.command_line.end(), {"--set", o});

  const Experiment experiment = load_experiment(config.string(), overrides);
  const RunnerSummary summary = without_gil([&] { return run_experiment(experiment, options); });
  if (summary.failed > 0) {
    const std::string text = std::to_string(summary.failed) + " of " + std::to_string(summary.total) +
                             " runs failed (their rows in " + summary.directory + "/table.md say why)";
    if (PyErr_WarnEx(PyExc_RuntimeWarning, text.c_str(), 1) < 0) throw py::error_already_set();
  }
  return summary.directory;
}

py::list pipelines() {
  py::list out;
  for (const std::string& name : reconstructors().names()) out.append(name);
  return out;
}

}  // namespace
}  // namespace dtsl::python

PYBIND11_MODULE(dtsl, m) {
  using namespace dtsl;
  using namespace dtsl::python;
  register_all_plugins();
  register_errors(m);
  m.doc() = "Surface reconstruction from unorganised points with displaced T-spline level sets (dtsl).";
  m.attr("__version__") = DTSL_VERSION;

  m.def("pipelines", &pipelines, "Names of the registered reconstruction pipelines (`dtsl list pipeline`).");

  m.def(
      "presets",
      [](const std::string& name) {
        make_pipeline(name);  // an unknown pipeline is a ConfigError, not an empty answer
        py::dict out;
        for (const Preset& p : presets(name)) {
          py::dict values;
          for (const PresetValue& v : p.values) values[py::str(v.key)] = v.value;
          out[py::str(p.name)] = py::dict(py::arg("description") = p.description, py::arg("values") = values);
        }
        return out;
      },
      py::arg("pipeline") = "dtsl",
      "The presets of a pipeline (`dtsl list preset`): {name: {description, values: {option: value text}}}; "
      "every pipeline has 'default'.");

  m.def(
      "pipeline_options",
      [](const std::string& name) { return to_python(to_json(make_pipeline(name)->options())); },
      py::arg("pipeline"),
      "The options of a pipeline with their default values, as a dict (`dtsl list pipeline NAME`).");

  m.def("reconstruct", &reconstruct, py::arg("points"), py::arg("pipeline") = "dtsl", py::kw_only(),
        py::arg("preset") = py::none(), py::arg("threads") = 1, py::arg("seed") = 1,
        R"(Reconstructs a mesh from an (n, 3) array of points, as `dtsl reconstruct` does.

The points are mapped into [-1, 1]^3, reconstructed, and the mesh is mapped back: the vertices are in
the input's units. `preset` names the option values to start from (None: 'default'; presets(pipeline)
lists them, e.g. dtsl's 'paper'). Every other keyword is an option of the pipeline over the preset (see
pipeline_options(pipeline)), checked as `--set KEY=VALUE` is: bool, int, float, str or a list of numbers. `threads` (threads of the
baselines' PCL stages) and `seed` go to the run context. Pipelines that need normals estimate them.

Returns (vertices, faces, summary): an (m, 3) float64 array, a (k, 3) int64 array and a dict with the
pipeline, its options, the counts, seconds and each stage's name, seconds and summary.
Raises ValueError for a bad array (shape, dtype, NaN/inf row), dtsl.ConfigError for an unknown
pipeline or option or a bad option value, dtsl.AlgorithmError for input the pipeline cannot handle.)");

  m.def("evaluate", &evaluate, py::arg("mesh"), py::arg("truth"), py::kw_only(),
        py::arg("samples") = MetricsOptions{}.samples, py::arg("tau_ratio") = MetricsOptions{}.fscore_tau_ratio,
        py::arg("seed") = 1,
        R"(Measures mesh against truth, both (vertices, faces) pairs, as the experiment tables do.

Returns a dict of the mesh's statistics (vertices, faces, boundary_edges, watertight, components,
euler_characteristic, genus, min angles, ...) and, for a mesh with faces, the surface metrics with
`samples` area-uniform samples on each (accuracy, completeness, chamfer, hausdorff,
normal_consistency, precision, recall, fscore, tau = tau_ratio x truth's bbox diagonal).
Undefined values (genus of an open mesh) are None.)");

  m.def(
      "read_points",
      [](const std::filesystem::path& path) {
        return to_array(without_gil([&] { return read_points(path.string()); }).points);
      },
      py::arg("path"), "The points of a .ply/.obj/.off/.xyz/.pcd file as an (n, 3) float64 array.");

  m.def(
      "read_mesh",
      [](const std::filesystem::path& path) {
        const TriangleMesh mesh = without_gil([&] { return read_mesh(path.string()); });
        return py::make_tuple(to_array(mesh.vertices), to_array(mesh.faces));
      },
      py::arg("path"), "A .ply/.obj/.off mesh as (vertices (m, 3) float64, faces (k, 3) int64).");

  m.def("run", &run, py::arg("config"), py::kw_only(), py::arg("results") = "results",
        py::arg("run_id") = py::none(), py::arg("jobs") = 1, py::arg("overrides") = std::vector<std::string>{},
        py::arg("progress") = true,
        R"(Runs an experiment config as `dtsl run` does and returns its result directory.

overrides are "key=value" strings as `--set`. Failed runs are results (their table rows say why) and
raise a RuntimeWarning; config errors raise before any run starts. Ctrl-C stops the runs (dtsl.Error);
running again resumes. Each run is a forked process; once this process has threads (any earlier dtsl
call that ran in parallel, e.g. evaluate), each run uses one thread, as OpenMP's pool does not survive
a fork: call run first, or use `jobs`, or `dtsl run` from the shell, to use every free core.)");
}
