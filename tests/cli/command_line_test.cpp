// The command line talks: --help on every command, --version, a short `list`, "did you mean" for
// typos, and `reconstruct` that checks its outputs before computing, shows its stages, and keeps stage
// meshes and metrics on request.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <array>
#include <vector>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/cli/run_dtsl.hpp"

namespace fs = std::filesystem;
using dtsl_cli_test::dtsl;
using dtsl_cli_test::Outcome;

namespace {

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

struct Scratch {
  fs::path path = fs::temp_directory_path() / ("dtsl_command_line_" + std::to_string(::getpid()));
  Scratch() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Scratch() { fs::remove_all(path); }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

/// A sphere of radius 3 around (10, 0, 0), `n` x `n` points on latitude/longitude lines with their
/// normals (for the baseline that needs them), as XYZ.
std::string sphere_file(const Scratch& s, int n) {
  std::ostringstream xyz;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double th = M_PI * (i + 0.5) / n, ph = 2 * M_PI * j / n;
      const double x = std::sin(th) * std::cos(ph), y = std::sin(th) * std::sin(ph), z = std::cos(th);
      xyz << 10 + 3 * x << " " << 3 * y << " " << 3 * z << " " << x << " " << y << " " << z << "\n";
    }
  const std::string path = s / "sphere.xyz";
  std::ofstream(path) << xyz.str();
  return path;
}

}  // namespace

TEST_CASE("every command has --help with its usage and an example; --version names the commit") {
  for (const char* command : {"run", "report", "table", "merge", "reconstruct", "list"}) {
    INFO(command);
    for (const char* flag : {"--help", "-h"}) {
      const Outcome o = dtsl(std::string(command) + " " + flag);
      CHECK(o.code == 0);
      CHECK(contains(o.output, std::string("usage: dtsl ") + command));
      CHECK(contains(o.output, "example:"));
    }
    CHECK(dtsl(std::string("help ") + command).code == 0);
  }
  const Outcome overview = dtsl("help");
  CHECK(overview.code == 0);
  CHECK(contains(overview.output, "reconstruct"));
  const Outcome version = dtsl("--version");
  CHECK(version.code == 0);
  CHECK(contains(version.output, "dtsl "));
  CHECK(contains(version.output, "git commit"));
  CHECK(contains(version.output, "CGAL"));
}

TEST_CASE("typos get a suggestion") {
  const Outcome command = dtsl("reconstuct a.xyz b.ply");
  CHECK(command.code == 2);
  CHECK(contains(command.output, "did you mean 'reconstruct'?"));
  const Outcome option = dtsl("run configs/quick.yaml --dry-rn");
  CHECK(option.code == 2);
  CHECK(contains(option.output, "did you mean '--dry-run'?"));
  const Outcome kind = dtsl("list pipelnes");
  CHECK(kind.code == 2);
  CHECK(contains(kind.output, "did you mean 'pipeline'?"));
  const Outcome plugin = dtsl("list pipeline dtls");
  CHECK(plugin.code == 2);
  CHECK(contains(plugin.output, "did you mean 'dtsl'?"));
  const Outcome key = dtsl("reconstruct in.xyz out.ply --set evolution_velocty=geodesic");
  CHECK(key.code == 1);
  CHECK(contains(key.output, "did you mean 'evolution_velocity'?"));
  // Nothing close: no suggestion.
  CHECK_FALSE(contains(dtsl("frobnicate").output, "did you mean"));
}

TEST_CASE("dtsl list is short; a plugin's options on demand, wrapped") {
  const Outcome all = dtsl("list");
  REQUIRE(all.code == 0);
  std::istringstream lines(all.output);
  std::string line;
  int count = 0;
  while (std::getline(lines, line)) {
    ++count;
    CHECK(line.size() <= 100);
  }
  CHECK(count < 40);
  CHECK(contains(all.output, "velocities:"));
  CHECK_FALSE(contains(all.output, "velocitys"));
  const Outcome one = dtsl("list pipeline dtsl");
  REQUIRE(one.code == 0);
  CHECK(contains(one.output, "evolution_velocity"));
  std::istringstream option_lines(one.output);
  while (std::getline(option_lines, line)) CHECK(line.size() <= 100);
  CHECK(dtsl("list columns").code == 0);
  CHECK(dtsl("list pipelines").code == 0);  // the plural names the kind too
}

TEST_CASE("reconstruct checks its outputs before any work, and writes nothing on a bad one") {
  Scratch s;
  const std::string in = sphere_file(s, 30);
  struct Case {
    std::string arguments, expected;
  };
  const std::vector<Case> cases = {
      {in + " /nonexistent/out.ply", "/nonexistent"},
      {in + " " + s / "out.stl", ".ply, .obj or .off"},
      {in + " " + s / "out.ply --metrics " + s / "m.txt", "--metrics"},
      {in + " " + s / "out.ply --metrics /nonexistent/m.json", "/nonexistent"},
      {in + " " + s / "out.ply --stages /nonexistent/deeper/stages", "/nonexistent"},
      {in + " " + s / "out.ply --truth " + in, "--truth"},
      {in + " " + s / "out.ply --threads 0", "--threads"},
      {in + " " + s / "out.ply --threads two", "--threads"},
  };
  for (const Case& c : cases) {
    INFO(c.arguments);
    const Outcome o = dtsl("reconstruct " + c.arguments);
    INFO(o.output);
    CHECK(o.code == 2);
    CHECK(contains(o.output, c.expected));
    CHECK_FALSE(contains(o.output, "stage 1"));  // failed before the reconstruction started
  }
  CHECK_FALSE(fs::exists(s / "out.ply"));
  // Fewer points than the pipeline needs: an error naming the file and the minimum.
  const std::string three = s / "three.xyz";
  std::ofstream(three) << "0 0 0\n1 0 0\n0 1 0\n";
  const Outcome few = dtsl("reconstruct " + three + " " + s / "few.ply");
  CHECK(few.code == 1);
  CHECK(contains(few.output, "three.xyz"));
  CHECK(contains(few.output, "needs at least 4"));
  CHECK_FALSE(fs::exists(s / "few.ply"));
}

TEST_CASE("reconstruct shows its stages, keeps stage meshes and metrics, in the input's units") {
  Scratch s;
  const std::string in = sphere_file(s, 24);
  const std::string out = s / "out.obj", stages = s / "stages", metrics = s / "metrics.json";
  // The truth: the same sphere as a mesh (the baseline's output is close enough to serve).
  const Outcome truth = dtsl("reconstruct " + in + " " + s / "truth.ply --pipeline pcl_poisson --set depth=5 --quiet");
  REQUIRE(truth.code == 0);
  CHECK(truth.output.empty());  // --quiet
  const Outcome o = dtsl("reconstruct " + in + " " + out + " --set sharpen=false --stages " + stages + " --metrics " +
                         metrics + " --truth " + s / "truth.ply --threads 1");
  INFO(o.output);
  REQUIRE(o.code == 0);
  CHECK(contains(o.output, "[stage 1] TL"));  // not a terminal: a plain line per stage
  CHECK(contains(o.output, "[stage 2] MT"));
  CHECK(fs::exists(fs::path(stages) / "stage_MI.ply"));
  CHECK(fs::exists(fs::path(stages) / "stage_MD.ply"));
  CHECK(fs::exists(fs::path(stages) / "tmesh.obj"));
  std::ifstream file(metrics);
  const nlohmann::json m = nlohmann::json::parse(file);
  CHECK(m["points"] == 576);
  CHECK(m["threads"] == 1);
  CHECK(m["time_total"].get<double>() > 0.0);
  REQUIRE(m["stages"].size() >= 3);
  CHECK(m["stages"][0]["name"] == "TL");
  CHECK(m["final"]["mesh"]["watertight"] == true);
  CHECK(m["final"]["surface"]["chamfer"].get<double>() < 0.05);  // the [-1,1] frame
  // The mesh is in the input's units: around (10, 0, 0) with radius about 3; with --normalised, in
  // the [-1,1] frame.
  auto obj_vertices = [](const std::string& path) {
    std::ifstream obj(path);
    std::vector<std::array<double, 3>> v;
    std::string tag;
    double x, y, z;
    while (obj >> tag) {
      if (tag == "v" && obj >> x >> y >> z) v.push_back({x, y, z});
      else std::getline(obj, tag);
    }
    return v;
  };
  const auto input_units = obj_vertices(out);
  REQUIRE(!input_units.empty());
  for (const auto& p : input_units) CHECK(std::hypot(p[0] - 10, p[1], p[2]) == Approx(3.0).epsilon(0.05));
  const Outcome normalised = dtsl("reconstruct " + in + " " + s / "unit.obj --set sharpen=false --normalised --quiet");
  REQUIRE(normalised.code == 0);
  double max_abs = 0.0;
  for (const auto& p : obj_vertices(s / "unit.obj"))
    max_abs = std::max({max_abs, std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
  CHECK(max_abs < 1.1);
  CHECK(max_abs > 0.9);
}
