// The command line end to end: a tiny experiment runs, resumes and re-tables; bad input of every kind
// exits non-zero with a message naming the problem and leaves no output behind.
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/run_dtsl.hpp"

namespace fs = std::filesystem;

namespace {

using dtsl_cli_test::dtsl;
using dtsl_cli_test::Outcome;

struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("dtsl_cli_" + std::to_string(::getpid()) + "_" + std::to_string(counter()++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  static int& counter() {
    static int c = 0;
    return c;
  }
  std::string file(const std::string& name, const std::string& content) const {
    const fs::path p = path / name;
    std::ofstream(p) << content;
    return p.string();
  }
};

const char* kTinyExperiment = R"(experiment: tiny
seed: 3
metrics: {samples: 2000}
datasets:
  - name: ball
    shape: {type: sphere}
    sampler: {type: area, count: 800}
pipelines:
  - name: poisson
    type: pcl_poisson
    options: {depth: 5}
)";

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

}  // namespace

TEST_CASE("dtsl help and unknown commands") {
  CHECK(dtsl("help").code == 0);
  const Outcome o = dtsl("frobnicate");
  CHECK(o.code == 2);
  CHECK(contains(o.output, "frobnicate"));
}

TEST_CASE("dtsl list names every registered kind and the baselines") {
  const Outcome o = dtsl("list");
  REQUIRE(o.code == 0);
  for (const char* name : {"pcl_poisson", "pcl_mc_hoppe", "pcl_mc_rbf", "pcl_gp3", "pcl_grid", "sphere", "noise",
                           "marching_triangulation", "marching_cubes", "gaussian"})
    CHECK(contains(o.output, name));
  CHECK(dtsl("list pipeline").code == 0);
  CHECK(dtsl("list nonsense").code == 2);
}

TEST_CASE("dtsl list keeps an option's name apart from its type, however long the name") {
  const Outcome o = dtsl("list pipeline dtsl");
  REQUIRE(o.code == 0);
  // The dtsl pipeline's longest names once ran into their type.
  for (const char* name : {"evolution_fine_velocity_open_gap", "bilateral_sharp_normal_variation_deg",
                           "bilateral_min_relative_decrease", "evolution_final_refinement"}) {
    INFO(name);
    CHECK(contains(o.output, std::string(name) + " "));
  }
  CHECK_FALSE(contains(o.output, "tolerancedouble"));
}

TEST_CASE("a tiny experiment runs, resumes and regenerates its tables") {
  TempDir tmp;
  const std::string config = tmp.file("tiny.yaml", kTinyExperiment);
  const std::string results = (tmp.path / "results").string();
  const Outcome first = dtsl("run " + config + " --results " + results + " --run-id r1");
  INFO(first.output);
  REQUIRE(first.code == 0);
  const fs::path dir = tmp.path / "results" / "tiny" / "r1";
  for (const char* f : {"config.yaml", "provenance.json", "table.md", "table.csv", "table.tex",
                        "runs/ball__poisson/metrics.json", "runs/ball__poisson/final.ply",
                        "datasets/ball/points.ply", "datasets/ball/ground_truth.ply"})
    CHECK(fs::exists(dir / f));
  std::ifstream md(dir / "table.md");
  const std::string table((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  CHECK(contains(table, "ball"));
  CHECK(contains(table, "poisson"));

  // Started again: the finished run is skipped, not redone.
  const auto stamp = fs::last_write_time(dir / "runs/ball__poisson/metrics.json");
  const Outcome again = dtsl("run " + config + " --results " + results + " --run-id r1");
  INFO(again.output);
  CHECK(again.code == 0);
  CHECK(contains(again.output, "1 already done"));
  CHECK(fs::last_write_time(dir / "runs/ball__poisson/metrics.json") == stamp);

  // A run whose record is missing is redone; the tables come back from the JSON alone.
  fs::remove(dir / "table.md");
  CHECK(dtsl("table " + dir.string()).code == 0);
  CHECK(fs::exists(dir / "table.md"));

  // The same run-id with a different configuration is refused.
  const Outcome clash = dtsl("run " + config + " --results " + results + " --run-id r1 --set seed=4");
  CHECK(clash.code == 1);
  CHECK(contains(clash.output, "different configuration"));
}

TEST_CASE("bad experiment files are rejected by name and leave nothing behind") {
  TempDir tmp;
  const std::string results = (tmp.path / "results").string();
  struct Case {
    const char* what;
    std::string yaml;
    const char* expected;
  };
  const std::string base = kTinyExperiment;
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = base;
    s.replace(s.find(from), from.size(), to);
    return s;
  };
  const std::vector<Case> cases = {
      {"syntax error", "experiment: [unclosed\n", "YAML syntax error"},
      {"unknown top-level key", base + "colour: red\n", "colour"},
      {"unknown pipeline", replace("type: pcl_poisson", "type: pcl_nonexistent"), "pcl_nonexistent"},
      {"unknown option", replace("{depth: 5}", "{depht: 5}"), "depht"},
      {"wrong type", replace("{depth: 5}", "{depth: deep}"), "depth"},
      {"out of range", replace("{depth: 5}", "{depth: 99}"), "depth"},
      {"unknown shape", replace("type: sphere", "type: dodecahedron"), "dodecahedron"},
      {"empty file", "", "expected"},
      {"no datasets", "experiment: x\npipelines: [{type: pcl_poisson}]\n", "datasets"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    const std::string config = tmp.file("bad.yaml", c.yaml);
    const Outcome o = dtsl("run " + config + " --results " + results);
    INFO(o.output);
    CHECK(o.code != 0);
    CHECK(o.code < 128);  // an error exit, not a crash
    CHECK(contains(o.output, c.expected));
    CHECK(!fs::exists(tmp.path / "results" / "tiny"));
  }
  const Outcome missing = dtsl("run " + (tmp.path / "nope.yaml").string());
  CHECK(missing.code == 1);
  CHECK(contains(missing.output, "nope.yaml"));
  const Outcome bad_set = dtsl("run " + tmp.file("ok.yaml", kTinyExperiment) + " --results " + results +
                               " --set pipelines.poisson.options.depth=-3");
  CHECK(bad_set.code == 1);
  CHECK(contains(bad_set.output, "depth"));
  CHECK(!fs::exists(tmp.path / "results" / "tiny"));
}

TEST_CASE("dtsl reconstruct: one file in, one mesh out; bad files rejected without output") {
  TempDir tmp;
  // A small sphere of points with normals, written as XYZ.
  std::string xyz;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const double th = 3.14159265 * (i + 0.5) / 40, ph = 2 * 3.14159265 * j / 40;
      const double x = std::sin(th) * std::cos(ph), y = std::sin(th) * std::sin(ph), z = std::cos(th);
      xyz += std::to_string(10 + 3 * x) + " " + std::to_string(3 * y) + " " + std::to_string(3 * z) + " " +
             std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
    }
  const std::string in = tmp.file("ball.xyz", xyz);
  const std::string out = (tmp.path / "ball.ply").string();
  const Outcome ok = dtsl("reconstruct " + in + " " + out + " --pipeline pcl_poisson --set depth=5");
  INFO(ok.output);
  REQUIRE(ok.code == 0);
  CHECK(fs::file_size(out) > 0);
  // The default pipeline is the method, `dtsl`; its options are reached the same way.
  const std::string method_out = (tmp.path / "ball_dtsl.off").string();
  const Outcome method = dtsl("reconstruct " + in + " " + method_out + " --set sharpen=false");
  INFO(method.output);
  REQUIRE(method.code == 0);
  CHECK(fs::file_size(method_out) > 0);
  const std::string never = (tmp.path / "never.off").string();
  CHECK(dtsl("reconstruct " + in + " " + never + " --set depth=5").code != 0);  // not an option of dtsl
  CHECK(!fs::exists(never));

  struct Case {
    std::string content;
    const char* expected;
  };
  const std::vector<Case> bad = {{"", "bad.xyz"}, {"1 2 nan\n0 0 0\n1 1 1\n", "bad.xyz"}, {"1 2\n", "bad.xyz"},
                                 {"0 0 0\n", "bad.xyz"}};
  for (const Case& c : bad) {
    const std::string path = tmp.file("bad.xyz", c.content);
    const std::string target = (tmp.path / "bad_out.ply").string();
    const Outcome o = dtsl("reconstruct " + path + " " + target);
    INFO(c.content << o.output);
    CHECK(o.code == 1);
    CHECK(contains(o.output, c.expected));
    CHECK(!fs::exists(target));
  }
  CHECK(dtsl("reconstruct " + (tmp.path / "missing.ply").string() + " " + out).code == 1);
  const Outcome unknown = dtsl("reconstruct " + in + " " + out + " --pipeline nope");
  CHECK(unknown.code == 1);
  CHECK(contains(unknown.output, "nope"));
  CHECK(dtsl("reconstruct " + in + " " + (tmp.path / "x.xyz").string()).code == 2);
  const Outcome badset = dtsl("reconstruct " + in + " " + out + " --set depth=abc");
  CHECK(badset.code == 1);
  CHECK(contains(badset.output, "depth"));
}

TEST_CASE("the dtsl pipeline writes every stage's mesh and the paper's per-stage errors") {
  TempDir tmp;
  const std::string config = tmp.file("method.yaml", R"(experiment: method
metrics: {samples: 2000}
datasets:
  - {name: torus, shape: torus, sampler: {type: area, count: 3000, density_ratio: 6}}
pipelines:
  - {name: dtsl, type: dtsl}
table: {columns: [dataset, e_avr@MI, e_avr@MD, e_avr@MS, time@TL, time@MT, time@D-Map, time@B-Evl, genus,
                  stage@B-Evl.iterations, stage@B-Evl.stop_reason, stage@TL.best_iteration,
                  stage@B-Evl.degenerate_removal.collapsed, chamfer@MI]}
)");
  const Outcome o = dtsl("run " + config + " --results " + (tmp.path / "results").string() + " --run-id r");
  INFO(o.output);
  REQUIRE(o.code == 0);
  const fs::path run = tmp.path / "results/method/r/runs/torus__dtsl";
  for (const char* f : {"stage_MI.ply", "stage_MD.ply", "stage_MS.ply", "final.ply", "metrics.json"})
    CHECK(fs::exists(run / f));
  std::ifstream in(run / "metrics.json");
  const std::string record((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // A genus-1 torus from non-uniform points, closed (the level set changed topology by itself).
  CHECK(contains(record, "\"genus\": 1.0"));
  CHECK(contains(record, "\"watertight\": true"));
  // The table has one number per stage column (no "–" for a stage that ran).
  std::ifstream md(tmp.path / "results/method/r/table.md");
  std::string table((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  // ... but the stages' chamfer, which only metrics.stage_surfaces computes: the last column.
  std::string row = table.substr(table.rfind("| torus"));
  row = row.substr(0, row.find('\n'));
  CHECK(row.substr(row.rfind('|', row.size() - 2)) == "| – |");
  CHECK(!contains(row.substr(0, row.rfind('|', row.size() - 2)), "–"));
  // A stage column without a key (or with an empty one) is an error naming it, before anything runs.
  for (const char* bad : {"stage@B-Evl", "stage@B-Evl.", "stage@.iterations", "stage@B-Evl..x"}) {
    const std::string config_bad = tmp.file("bad.yaml", std::string(R"(experiment: bad
datasets:
  - {name: torus, shape: torus, sampler: {type: area, count: 300}}
pipelines:
  - {name: dtsl, type: dtsl}
table: {columns: [dataset, ")") + bad + "\"]}\n");
    const Outcome b = dtsl("run " + config_bad + " --results " + (tmp.path / "results").string() + " --run-id b");
    INFO(bad << ": " << b.output);
    CHECK(b.code == 1);
    CHECK(contains(b.output, bad));
  }
}

TEST_CASE("metrics.stage_surfaces compares every stage's mesh with the truth") {
  TempDir tmp;
  const std::string body = R"(
datasets:
  - {name: torus, shape: torus, sampler: {type: area, count: 2000}}
pipelines:
  - {name: dtsl, type: dtsl, options: {evolution_tmesh_max_depth: 4}}   # coarse: cheap under the sanitizers
table: {columns: [dataset, chamfer@MI, accuracy@MD, completeness@MS, chamfer@final, chamfer]}
)";
  const std::string config = tmp.file("with.yaml", "experiment: with\nmetrics: {samples: 2000, stage_surfaces: true}" + body);
  const Outcome o = dtsl("run " + config + " --results " + (tmp.path / "results").string() + " --run-id r");
  INFO(o.output);
  REQUIRE(o.code == 0);
  std::ifstream md(tmp.path / "results/with/r/table.md");
  const std::string table((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  std::stringstream line(table.substr(table.rfind("| torus")));
  std::string row;
  std::getline(line, row);
  std::vector<std::string> cells;
  std::stringstream cut(row);
  for (std::string c; std::getline(cut, c, '|');)
    if (c.find_first_not_of(' ') != std::string::npos) cells.push_back(c.substr(1, c.size() - 2));
  REQUIRE(cells.size() == 6);
  for (int k = 1; k <= 5; ++k) CHECK(cells[k] != "–");
  // The last stage's mesh is the result: the same chamfer either way it is asked for.
  CHECK(cells[4] == cells[5]);
  // The displaced, sharpened mesh is closer to the truth than the initial one (a torus: exact truth).
  CHECK(std::stod(cells[1]) > std::stod(cells[4]));
  // A typo in the key is an error naming it (before anything runs).
  const std::string typo = tmp.file("typo.yaml", "experiment: typo\nmetrics: {stage_surface: true}" + body);
  const Outcome bad = dtsl("run " + typo + " --results " + (tmp.path / "results").string() + " --run-id r");
  CHECK(bad.code == 1);
  CHECK(contains(bad.output, "stage_surface"));
}

TEST_CASE("a sweep names its value in every run it addresses, the config's own value included") {
  TempDir tmp;
  const std::string config = tmp.file("sweep.yaml", std::string(kTinyExperiment) +
                                                         "  - {name: hoppe, type: pcl_mc_hoppe, options: {grid_resolution: 30}}\n"
                                                         "sweep: {key: pipelines.poisson.options.depth, values: [5, 6]}\n");
  const Outcome o = dtsl("run " + config + " --results " + (tmp.path / "results").string() + " --run-id s");
  INFO(o.output);
  REQUIRE(o.code == 0);
  const fs::path runs = tmp.path / "results/tiny/s/runs";
  // depth 5 is also the config's own value: it still gets its own, named run.
  CHECK(fs::exists(runs / "ball__poisson__pipelines.poisson.options.depth_6/metrics.json"));
  CHECK(fs::exists(runs / "ball__poisson__pipelines.poisson.options.depth_5/metrics.json"));
  // The pipeline the sweep does not address runs once.
  CHECK(fs::exists(runs / "ball__hoppe/metrics.json"));
  CHECK(std::distance(fs::directory_iterator(runs), fs::directory_iterator()) == 3);
}

TEST_CASE("truth_genus, truth_components and topology_ok compare each result with its ground truth") {
  TempDir tmp;
  // A torus (genus 1) and two spheres (2 components); Poisson closes its meshes, greedy projection
  // usually leaves gaps, so the column is exercised both ways whatever each gives.
  const std::string config = tmp.file("truth.yaml", R"(experiment: truth
seed: 1
metrics: {samples: 2000}
datasets:
  - name: ring
    shape: {type: torus, major_segments: 96, minor_segments: 32}
    sampler: {type: area, count: 1500}
  - name: balls
    shape: {type: two_spheres, subdivisions: 3}
    sampler: {type: area, count: 1500}
pipelines:
  - {name: poisson, type: pcl_poisson, options: {depth: 6}}
  - {name: gp3, type: pcl_gp3}
table:
  columns: [dataset, pipeline, genus, components, truth_genus, truth_components, topology_ok]
)");
  const Outcome o = dtsl("run " + config + " --results " + (tmp.path / "results").string() + " --run-id r");
  INFO(o.output);
  REQUIRE(o.code == 0);
  const fs::path dir = tmp.path / "results" / "truth" / "r";
  std::ifstream csv(dir / "table.csv");
  std::string line;
  REQUIRE(std::getline(csv, line));
  CHECK(line == "dataset,pipeline,genus,comp.,truth genus,truth comp.,topology ok");
  int rows = 0;
  while (std::getline(csv, line)) {
    INFO(line);
    std::vector<std::string> cell;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cell.push_back(c);
    if (line.back() == ',') cell.push_back("");
    REQUIRE(cell.size() == 7);
    const bool ring = cell[0] == "ring";
    CHECK(cell[4] == (ring ? "1" : "0"));  // measured on the ground truth, once per dataset
    CHECK(cell[5] == (ring ? "1" : "2"));
    CHECK(cell[6] == (cell[2] == cell[4] && cell[3] == cell[5] ? "1" : "0"));
    ++rows;
  }
  CHECK(rows == 4);
  std::ifstream meta(dir / "datasets" / "ring" / "dataset.json");
  const std::string text((std::istreambuf_iterator<char>(meta)), std::istreambuf_iterator<char>());
  CHECK(contains(text, "\"ground_truth_mesh\""));
}
