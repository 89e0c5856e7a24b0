// The baselines that need no normals, through the registry: CGAL's advancing front and scale space
// reconstruct a sampled sphere near its radius; `external` runs a command (stub shell scripts written
// here), reads its mesh back, and fails with a clear message when the program is missing, the command
// fails, or its options are incomplete.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "experiments/plugins.hpp"
#include "framework/config/yaml_options.hpp"
#include "framework/core/error.hpp"
#include "framework/metrics/metrics.hpp"
#include "framework/pipeline/preset.hpp"
#include "framework/pipeline/reconstructor.hpp"
#include "tests/baselines/pipeline_helpers.hpp"

namespace {

using namespace dtsl;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

constexpr double kRadius = 0.9;

PointCloud sphere(std::size_t n) { return test::sampled_sphere(n, kRadius, true, 11); }

using test::create;
using test::set;
using test::signed_volume;

// Mean and worst |‖v‖ - R| over the mesh's vertices and its triangles' centroids (the centroids show
// triangles that bridge across the sphere).
std::pair<double, double> radial_error(const TriangleMesh& m) {
  double sum = 0.0, worst = 0.0;
  for (const Face& f : m.faces) {
    const Vec3 c = (m.vertices[f[0]] + m.vertices[f[1]] + m.vertices[f[2]]) / 3.0;
    const double d = std::abs(c.norm() - kRadius);
    sum += d;
    worst = std::max(worst, d);
  }
  return {sum / std::max<std::size_t>(1, m.faces.size()), worst};
}

/// A directory of its own for a test's scripts, removed at the end.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "dtsl-test-external-XXXXXX").string();
    REQUIRE(mkdtemp(pattern.data()) != nullptr);
    path = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  /// Writes an executable /bin/sh script named `name` with `body`; returns its path.
  std::string script(const std::string& name, const std::string& body) const {
    const fs::path p = path / name;
    std::ofstream(p) << "#!/bin/sh\n" << body;
    chmod(p.c_str(), 0755);
    return p.string();
  }
};

// A stub reconstructor: checks that its input exists and is non-empty, then writes a tetrahedron
// (an OFF file) to its second argument.
const char* kTetrahedronScript =
    "test -s \"$1\" || { echo \"no input $1\" >&2; exit 3; }\n"
    "cat > \"$2\" <<'EOF'\nOFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\nEOF\n";

}  // namespace

TEST_CASE("the unoriented baselines are registered with documented options", "[baselines][unoriented]") {
  for (const std::string name : {"cgal_advancing_front", "cgal_scale_space", "external"}) {
    INFO(name);
    auto r = create(name);
    const auto fields = describe(r->options());
    CHECK(fields.size() >= 2);
    for (const FieldDescription& f : fields) {
      INFO(f.name);
      CHECK(!f.doc.empty());
    }
  }
  CHECK_NOTHROW(create("cgal_advancing_front")->options().check());
  CHECK_NOTHROW(create("cgal_scale_space")->options().check());
  // external has no usable default: its command must be configured.
  CHECK_THROWS_AS(create("external")->options().check(), ConfigError);
}

TEST_CASE("CGAL's interpolating reconstructors mesh a sampled sphere near its radius", "[baselines][unoriented]") {
  struct Case {
    std::string name;
    std::vector<std::pair<std::string, std::string>> options;
  };
  const Case c = GENERATE(Case{"cgal_advancing_front", {}}, Case{"cgal_scale_space", {}},
                          Case{"cgal_scale_space", {{"smoother", "weighted_pca"}, {"mesher", "alpha_shape"}}},
                          Case{"cgal_scale_space", {{"output_points", "smoothed"}, {"max_facet_length", "3"}}});
  auto r = create(c.name);
  std::string label = c.name;
  for (const auto& [key, value] : c.options) {
    set(*r, key, value);
    label += " " + key + "=" + value;
  }
  INFO(label);
  PointCloud cloud = sphere(2000);
  cloud.normals.clear();  // they need none
  const ReconstructionResult result = r->reconstruct(cloud, RunContext{});

  REQUIRE(result.mesh.faces.size() > 1000);
  const auto [mean, worst] = radial_error(result.mesh);
  INFO("mean |r - R| of triangle centroids " << mean << ", worst " << worst);
  // Triangles between neighbouring points of a 2000-point sphere (spacing ~0.07) sag by ~1e-3.
  CHECK(mean < 0.01);
  CHECK(worst < 0.05);
  CHECK(result.summary.at("normals_source") == "none");
  REQUIRE(result.stages.size() == 1);
  CHECK(result.stages[0].name == "reconstruct");
  CHECK(result.stages[0].summary.at("faces") == result.mesh.faces.size());

  const MeshStats s = mesh_stats(result.mesh);
  INFO("boundary edges " << s.boundary_edges << ", non-manifold edges " << s.nonmanifold_edges << ", components "
                         << s.components);
  CHECK(s.nonmanifold_edges <= result.mesh.faces.size() / 100);
  // Outward, and covering nearly all of the sphere (holes would lower the volume).
  const double ball = 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  CHECK(signed_volume(result.mesh) > 0.9 * ball);
  if (c.options.empty() || c.options[0].second != "smoothed") {  // interpolating: vertices are input points
    for (const Vec3& v : result.mesh.vertices) REQUIRE(std::abs(v.norm() - kRadius) < 1e-9);
  }
}

TEST_CASE("the CGAL reconstructors refuse too few or collinear points by name", "[baselines][unoriented]") {
  const std::string name = GENERATE(std::string("cgal_advancing_front"), std::string("cgal_scale_space"));
  INFO(name);
  CHECK_THROWS_WITH(create(name)->reconstruct(sphere(5), RunContext{}), Contains(name) && Contains("got 5"));
  PointCloud line;
  for (int i = 0; i < 100; ++i) line.points.push_back(Vec3(0.01 * i, 0.02 * i, 0.0));
  CHECK_THROWS_WITH(create(name)->reconstruct(line, RunContext{}), Contains("collinear"));
}

TEST_CASE("cgal_advancing_front triangulates exactly coplanar points", "[baselines][unoriented]") {
  // A flat Delaunay triangulation: CGAL lifts it with an extra vertex, which the output must not hold.
  PointCloud plane;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) plane.points.push_back(Vec3(0.05 * i, 0.05 * j, 0.3));
  const ReconstructionResult r = create("cgal_advancing_front")->reconstruct(plane, RunContext{});
  CHECK(r.mesh.faces.size() > 600);  // a 20 x 20 grid has 722 triangles
  CHECK(r.mesh.vertices.size() <= plane.size());
  for (const Vec3& v : r.mesh.vertices) REQUIRE(v.z() == 0.3);
}

TEST_CASE("the CGAL reconstructors check their options by name", "[baselines][unoriented]") {
  const std::string name = GENERATE(std::string("cgal_advancing_front"), std::string("cgal_scale_space"));
  INFO(name);
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"radius_ratio_bound", "0.5"}, {"beta", "-1"}, {"beta", "2"}}) {
    INFO(key << " = " << value);
    CHECK_THROWS_WITH(set(*create(name), key, value), Contains(key));
  }
}

TEST_CASE("cgal_scale_space options are checked by name", "[baselines][unoriented]") {
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"iterations", "-1"}, {"smoother", "laplace"}, {"neighbors", "2"}, {"mesher", "poisson"},
           {"max_facet_length", "-1"}, {"output_points", "both"}}) {
    INFO(key << " = " << value);
    auto r = create("cgal_scale_space");
    CHECK_THROWS_AS(set(*r, key, value), ConfigError);
    CHECK_THROWS_WITH(set(*r, key, value), Contains(key));
  }
}

TEST_CASE("external runs a command and reads its mesh back", "[baselines][unoriented][external]") {
  const ScratchDir dir;
  const std::string stub = dir.script("stub reconstructor.sh", kTetrahedronScript);  // a space in its path
  auto r = create("external");
  set(*r, "command", "\"'" + stub + "' {in} {out}\"");  // YAML double quotes around the shell's single ones
  set(*r, "output", GENERATE(std::string("off"), std::string(".off")));
  set(*r, "input_format", GENERATE(std::string("ply"), std::string("ply_ascii"), std::string("xyz")));
  // The run's temporary directory goes under TMPDIR: this test's own, to see that it is removed.
  const fs::path tmp = dir.path / "tmp";
  fs::create_directory(tmp);
  const char* old_tmpdir = std::getenv("TMPDIR");
  const std::string saved = old_tmpdir ? old_tmpdir : "";
  setenv("TMPDIR", tmp.c_str(), 1);
  ReconstructionResult result;
  try {
    result = r->reconstruct(sphere(200), RunContext{});
  } catch (...) {
    old_tmpdir ? setenv("TMPDIR", saved.c_str(), 1) : unsetenv("TMPDIR");
    throw;
  }
  old_tmpdir ? setenv("TMPDIR", saved.c_str(), 1) : unsetenv("TMPDIR");
  CHECK(result.mesh.vertices.size() == 4);
  CHECK(result.mesh.faces.size() == 4);
  CHECK(mesh_stats(result.mesh).watertight);
  CHECK(result.summary.at("normals_source") == "none");
  CHECK(result.stages.at(0).summary.at("exit_status") == 0);
  CHECK(fs::is_empty(tmp));  // the points, the mesh and the logs are gone
}

TEST_CASE("every pipeline takes the default preset before its options, as a run applies them", "[baselines][preset]") {
  // execute_run applies the `default` preset to every pipeline entry, then the entry's options:
  // `default` sets nothing and must not judge options that come after it (external's command).
  register_all_plugins();
  for (const std::string& type : reconstructors().names()) {
    INFO(type);
    auto r = reconstructors().create(type, "test");
    CHECK_NOTHROW(apply_preset(*r, type, "default", "test"));
  }
  const ScratchDir dir;
  const std::string stub = dir.script("stub.sh", kTetrahedronScript);
  auto r = create("external");
  apply_preset(*r, "external", "default", "test");
  set(*r, "command", stub + " {in} {out}");
  set(*r, "output", "off");
  CHECK(r->reconstruct(sphere(200), RunContext{}).mesh.faces.size() == 4);
}

TEST_CASE("external writes the points (and normals on request) where {in} says", "[baselines][unoriented][external]") {
  const ScratchDir dir;
  const std::string copy = (dir.path / "seen.ply").string();
  // Keeps a copy of its input, then answers with a tetrahedron.
  const std::string stub =
      dir.script("keep.sh", "cp \"$1\" '" + copy + "'\n" + std::string(kTetrahedronScript));
  auto r = create("external");
  set(*r, "command", stub + " {in} {out}");
  set(*r, "output", "off");
  const bool normals = GENERATE(false, true);
  set(*r, "normals", normals ? "true" : "false");
  const PointCloud cloud = sphere(300);
  const ReconstructionResult result = r->reconstruct(cloud, RunContext{});
  CHECK(result.summary.at("normals_source") == (normals ? "ground_truth" : "none"));
  std::ifstream in(copy, std::ios::binary);
  std::string header;
  for (std::string line; std::getline(in, line) && line != "end_header";) header += line + "\n";
  CHECK_THAT(header, Contains("element vertex 300") && Contains("property double x"));
  CHECK((header.find("property double nx") != std::string::npos) == normals);
}

TEST_CASE("external leaves nothing running that its command started", "[baselines][unoriented][external]") {
  const ScratchDir dir;
  const std::string pid_file = (dir.path / "pid").string();
  // Starts a background sleep, records its process id, answers with a tetrahedron and exits.
  const std::string stub = dir.script("daemon.sh", "sleep 30 &\necho $! > '" + pid_file + "'\n" +
                                                       std::string(kTetrahedronScript));
  auto r = create("external");
  set(*r, "command", stub + " {in} {out}");
  set(*r, "output", "off");
  CHECK(r->reconstruct(sphere(100), RunContext{}).mesh.faces.size() == 4);
  int pid = 0;
  std::ifstream(pid_file) >> pid;
  REQUIRE(pid > 0);
  // Gone, or a zombie nobody reaps (a container's init may not): not running either way.
  auto running = [pid] {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string id, name, state;
    return static_cast<bool>(stat >> id >> name >> state) && state != "Z";
  };
  for (int i = 0; i < 100 && running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK(!running());
}

TEST_CASE("external with a missing program says it is skipped and names the program", "[baselines][unoriented][external]") {
  auto r = create("external");
  const std::string missing = GENERATE(std::string("/nonexistent/dtsl-recon"), std::string("dtsl-no-such-program-xyz"));
  set(*r, "command", missing + " --in {in} --out {out}");
  CHECK_THROWS_AS(r->reconstruct(sphere(200), RunContext{}), AlgorithmError);
  CHECK_THROWS_WITH(r->reconstruct(sphere(200), RunContext{}),
                    Contains("skipped") && Contains("'" + missing + "'") && Contains("not found"));
  // A file that exists but cannot be executed is refused the same way.
  const ScratchDir dir;
  const fs::path plain = dir.path / "not-executable";
  std::ofstream(plain) << "data\n";
  set(*r, "command", plain.string() + " {in} {out}");
  CHECK_THROWS_WITH(r->reconstruct(sphere(200), RunContext{}),
                    Contains("skipped") && Contains(plain.string()) && Contains("not executable"));
}

TEST_CASE("external reports a failing command with its status and output", "[baselines][unoriented][external]") {
  const ScratchDir dir;
  auto r = create("external");

  SECTION("non-zero exit") {
    const std::string stub = dir.script("fail.sh", "echo 'cannot converge at depth 8' >&2\nexit 7\n");
    set(*r, "command", stub + " {in} {out}");
    CHECK_THROWS_WITH(r->reconstruct(sphere(200), RunContext{}),
                      Contains("exit status 7") && Contains("fail.sh") && Contains("cannot converge at depth 8"));
  }
  SECTION("killed by a signal") {
    const std::string stub = dir.script("crash.sh", "kill -SEGV $$\n");
    set(*r, "command", stub + " {in} {out}");
    // The shell either execs the script (killed by the signal) or reports 128 + 11.
    CHECK_THROWS_WITH(r->reconstruct(sphere(200), RunContext{}), Contains("signal 11") || Contains("exit status 139"));
  }
  SECTION("timeout") {
    const std::string stub = dir.script("slow.sh", "sleep 30\n");
    set(*r, "command", stub + " {in} {out}");
    set(*r, "timeout_seconds", "0.3");
    const auto start = std::chrono::steady_clock::now();
    CHECK_THROWS_WITH(r->reconstruct(sphere(200), RunContext{}), Contains("timed out") && Contains("slow.sh"));
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));  // the sleep was killed too
  }
  SECTION("no output file") {
    const std::string stub = dir.script("silent.sh", "exit 0\n");
    set(*r, "command", stub + " {in} {out}");
    CHECK_THROWS_WITH(r->reconstruct(sphere(200), RunContext{}), Contains("silent.sh") && Contains("wrote no"));
  }
  SECTION("unreadable output") {
    const std::string stub = dir.script("garbage.sh", "echo 'not a mesh' > \"$2\"\n");
    set(*r, "command", stub + " {in} {out}");
    CHECK_THROWS_WITH(r->reconstruct(sphere(200), RunContext{}), Contains("garbage.sh") && Contains("cannot be read"));
  }
  SECTION("a mesh without triangles") {
    const std::string stub = dir.script("points.sh", "printf 'OFF\\n3 0 0\\n0 0 0\\n1 0 0\\n0 1 0\\n' > \"$2\"\n");
    set(*r, "command", stub + " {in} {out}");
    set(*r, "output", "off");
    CHECK_THROWS_WITH(r->reconstruct(sphere(200), RunContext{}), Contains("no faces") && Contains("points.sh"));
  }
  SECTION("normals requested from a cloud without them") {
    set(*r, "command", "/bin/true {in} {out}");
    set(*r, "normals", "true");
    PointCloud cloud = sphere(200);
    cloud.normals.clear();
    CHECK_THROWS_WITH(r->reconstruct(cloud, RunContext{}), Contains("normals"));
  }
}

TEST_CASE("external's options name the key at fault", "[baselines][unoriented][external]") {
  for (const auto& [command, rule] : std::vector<std::pair<std::string, std::string>>{
           {"", "must be set"}, {"/bin/true {out}", "{in}"}, {"/bin/true {in}", "{out}"}}) {
    INFO("command = '" << command << "'");
    auto r = create("external");
    CHECK_THROWS_AS(set(*r, "command", "'" + command + "'"), ConfigError);
    CHECK_THROWS_WITH(set(*r, "command", "'" + command + "'"), Contains("command") && Contains(rule));
  }
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"input_format", "pcd"}, {"output", "stl"}, {"timeout_seconds", "0"}}) {
    INFO(key << " = " << value);
    auto r = create("external");
    set(*r, "command", "/bin/true {in} {out}");
    CHECK_THROWS_WITH(set(*r, key, value), Contains(key));
  }
  // The default (no command) is refused when the pipeline runs, too.
  CHECK_THROWS_AS(create("external")->reconstruct(sphere(100), RunContext{}), ConfigError);
}
