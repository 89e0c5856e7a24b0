// Sharding, merging and reporting end to end: an experiment run whole and run as 2 shards + merge
// gives the same tables; every kind of bad input (shard spec, mismatched or incomplete shards, a
// directory that is not a result) exits non-zero with a message naming the problem and writes nothing.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include "tests/cli/run_dtsl.hpp"

namespace fs = std::filesystem;

namespace {

using dtsl_cli_test::dtsl;
using dtsl_cli_test::Outcome;

bool contains(const std::string& haystack, const std::string& needle) { return haystack.find(needle) != std::string::npos; }

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// table.md without its title line (which names the run id).
std::string table_body(const fs::path& dir) {
  const std::string md = slurp(dir / "table.md");
  return md.substr(md.find('\n') + 1);
}

// 2 datasets x (1 pipeline x 2 sweep values + 1 pipeline) = 6 runs; no time columns, so tables of
// separate executions are comparable.
const char* kExperiment = R"(experiment: sharded
seed: 5
metrics: {samples: 1500}
datasets:
  - name: ball
    shape: sphere
    sampler: {type: area, count: 600}
  - name: ring
    shape: torus
    sampler: {type: area, count: 700}
pipelines:
  - {name: poisson, type: pcl_poisson, options: {depth: 5}}
  - {name: gp3, type: pcl_gp3}
sweep:
  - {key: pipelines.poisson.options.depth, values: [5, 6]}
table: {columns: [dataset, pipeline, np, nv, nf, e_avr, e_max, chamfer, fscore, watertight, genus, status]}
)";

struct Fixture {
  fs::path root;
  std::string config, results;
  Fixture() {
    root = fs::temp_directory_path() / ("dtsl_shard_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root);
    config = (root / "sharded.yaml").string();
    std::ofstream(config) << kExperiment;
    results = (root / "results").string();
  }
  ~Fixture() { fs::remove_all(root); }
  fs::path dir(const std::string& id) const { return root / "results" / "sharded" / id; }
  Outcome run(const std::string& extra) const { return dtsl("run " + config + " --quiet --results " + results + " " + extra); }
};

}  // namespace

TEST_CASE("run --dry-run lists the runs of the whole experiment and of a shard, writing nothing") {
  Fixture f;
  const Outcome all = f.run("--dry-run");
  INFO(all.output);
  REQUIRE(all.code == 0);
  CHECK(contains(all.output, "6 of 6 runs"));
  std::set<std::string> ids;
  for (int i = 1; i <= 2; ++i) {
    const Outcome part = f.run("--dry-run --shard " + std::to_string(i) + "/2");
    INFO(part.output);
    REQUIRE(part.code == 0);
    CHECK(contains(part.output, "3 of 6 runs"));
    std::smatch m;
    std::string rest = part.output;
    const std::regex line("\n[0-9]+\t([^\n]+)");
    while (std::regex_search(rest, m, line)) {
      CHECK(ids.insert(m[1]).second);  // disjoint
      rest = m.suffix();
    }
  }
  CHECK(ids.size() == 6);  // and covering
  CHECK(!fs::exists(f.root / "results"));
}

TEST_CASE("bad --shard specifications are usage errors that write nothing") {
  Fixture f;
  for (const char* bad : {"0/2", "3/2", "2", "a/b", "1/0", "-1/2", "1/2/3", "/2"}) {
    const Outcome o = f.run(std::string("--shard ") + bad);
    INFO(bad << ": " << o.output);
    CHECK(o.code == 2);
    CHECK(contains(o.output, "--shard"));
  }
  CHECK(!fs::exists(f.root / "results"));
}

TEST_CASE("two shards merged give the tables of the unsharded run; merge and report check their input") {
  Fixture f;
  const Outcome whole = f.run("--run-id whole");
  INFO(whole.output);
  REQUIRE(whole.code == 0);
  const Outcome s1 = f.run("--shard 1/2 --run-id s1");
  INFO(s1.output);
  REQUIRE(s1.code == 0);
  const Outcome s2 = f.run("--shard 2/2 --run-id s2");
  INFO(s2.output);
  REQUIRE(s2.code == 0);
  // Shards are disjoint and each holds only the datasets its runs use.
  std::set<std::string> in1, in2;
  for (const auto& e : fs::directory_iterator(f.dir("s1") / "runs")) in1.insert(e.path().filename().string());
  for (const auto& e : fs::directory_iterator(f.dir("s2") / "runs")) in2.insert(e.path().filename().string());
  CHECK(in1.size() == 3);
  CHECK(in2.size() == 3);
  for (const std::string& id : in1) CHECK(!in2.count(id));
  CHECK(contains(slurp(f.dir("s1") / "provenance.json"), "\"shard\""));
  // A directory holds one shard (or the whole run): another shard into it is refused.
  const Outcome mixed = f.run("--shard 2/2 --run-id s1");
  CHECK(mixed.code == 1);
  CHECK(contains(mixed.output, "holds shard 1/2"));
  CHECK(f.run("--run-id s1").code == 1);
  CHECK(f.run("--shard 1/2 --run-id s1").code == 0);  // the same shard resumes

  const fs::path merged = f.root / "results" / "sharded" / "merged";
  const Outcome m = dtsl("merge " + merged.string() + " " + f.dir("s1").string() + " " + f.dir("s2").string());
  INFO(m.output);
  REQUIRE(m.code == 0);
  CHECK(slurp(merged / "table.csv") == slurp(f.dir("whole") / "table.csv"));
  CHECK(table_body(merged) == table_body(f.dir("whole")));
  CHECK(slurp(merged / "config.yaml") == slurp(f.dir("whole") / "config.yaml"));
  for (const auto& e : fs::directory_iterator(f.dir("whole") / "runs")) {
    CHECK(fs::exists(merged / "runs" / e.path().filename() / "metrics.json"));
    CHECK(fs::exists(merged / "runs" / e.path().filename() / "final.ply"));
  }
  for (const char* d : {"ball", "ring"}) CHECK(fs::exists(merged / "datasets" / d / "points.ply"));
  CHECK(contains(slurp(merged / "provenance.json"), "merged_from"));
  // `dtsl table` on the merged directory reproduces the same table.
  REQUIRE(dtsl("table " + merged.string()).code == 0);
  CHECK(slurp(merged / "table.csv") == slurp(f.dir("whole") / "table.csv"));

  {  // merge refuses incomplete, overlapping, mismatched shards and an existing target
    const fs::path out = f.root / "out";
    Outcome o = dtsl("merge " + out.string() + " " + f.dir("s1").string());
    CHECK(o.code == 1);
    CHECK(contains(o.output, "3 of 6 runs"));
    CHECK(contains(o.output, "in none of the directories"));

    o = dtsl("merge " + out.string() + " " + f.dir("s1").string() + " " + f.dir("s1").string());
    CHECK(o.code == 1);
    CHECK(contains(o.output, "given twice"));

    fs::copy(f.dir("s1"), f.root / "s1copy", fs::copy_options::recursive);
    o = dtsl("merge " + out.string() + " " + f.dir("s1").string() + " " + (f.root / "s1copy").string() + " " +
             f.dir("s2").string());
    CHECK(o.code == 1);
    CHECK(contains(o.output, "are both shard 1/2"));

    o = dtsl("merge " + out.string() + " " + f.dir("s1").string() + " " + f.dir("whole").string());
    CHECK(o.code == 1);
    CHECK(contains(o.output, "in both"));

    const Outcome other = f.run("--shard 2/2 --run-id other --set seed=6");
    REQUIRE(other.code == 0);
    o = dtsl("merge " + out.string() + " " + f.dir("s1").string() + " " + f.dir("other").string());
    CHECK(o.code == 1);
    CHECK(contains(o.output, "different configuration"));

    o = dtsl("merge " + out.string() + " " + f.dir("s1").string() + " " + (f.root / "nowhere").string());
    CHECK(o.code == 1);
    CHECK(contains(o.output, "not a result directory"));

    o = dtsl("merge " + merged.string() + " " + f.dir("s1").string() + " " + f.dir("s2").string());
    CHECK(o.code == 1);
    CHECK(contains(o.output, "already exists"));

    CHECK(!fs::exists(out));
    for (const auto& e : fs::directory_iterator(f.root))  // no temporary left behind
      CHECK(!contains(e.path().filename().string(), ".tmp-merge-"));
  }

  {  // report writes figures and a report.md that shows them
    const Outcome r = dtsl("report " + merged.string() + " --quiet --size 96 --views 1");
    INFO(r.output);
    REQUIRE(r.code == 0);
    const std::string md = slurp(merged / "report.md");
    CHECK(contains(md, table_body(merged).substr(0, 40)));
    std::smatch m;
    std::string rest = md;
    int images = 0;
    while (std::regex_search(rest, m, std::regex(R"(\]\((figures/[^)]+\.png)\))"))) {
      const fs::path png = merged / m[1].str();
      CHECK(fs::exists(png));
      CHECK(fs::file_size(png) > 100);
      ++images;
      rest = m.suffix();
    }
    CHECK(images >= 6 + 2);  // a render per run, the time overview, the sweep
    CHECK(fs::exists(merged / "figures" / "ball__gp3" / "renders.png"));
    CHECK(fs::exists(merged / "figures" / "compare_ring.png"));  // every run's final mesh on one dataset
  }

  {  // report refuses what is not a result directory, and bad options, writing nothing
    Outcome o = dtsl("report " + f.root.string());
    CHECK(o.code == 1);
    CHECK(contains(o.output, "not a result directory"));
    CHECK(!fs::exists(f.root / "report.md"));
    CHECK(!fs::exists(f.root / "figures"));
    o = dtsl("report " + (f.root / "nowhere").string());
    CHECK(o.code == 1);
    const std::string before = slurp(merged / "report.md");
    o = dtsl("report " + merged.string() + " --views 9");
    CHECK(o.code == 2);
    CHECK(contains(o.output, "--views"));
    o = dtsl("report " + merged.string() + " --up w");
    CHECK(o.code == 2);
    CHECK(slurp(merged / "report.md") == before);
  }
}
