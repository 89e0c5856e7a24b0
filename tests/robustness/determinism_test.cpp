// Determinism: the same input, config and seed give byte-identical meshes and the same metrics (all
// but the timings and the peak memory), run after run and whatever the number of OpenMP threads.
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/robustness/process.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace dtsl::test;

namespace {

const char* kExperiment = R"(experiment: determinism
seed: 11
metrics: {samples: 3000}
datasets:
  - name: torus
    shape: torus
    sampler: {type: area, count: 800, density_ratio: 4}
    corruptions: [{type: noise, sigma: 0.002}, {type: holes, count: 2}]
pipelines:
  - {name: poisson, type: pcl_poisson, options: {depth: 5, normals: jet_mst}}
  - {name: dtsl, type: dtsl}
)";

// Timings and memory vary from run to run by nature; everything else must not.
bool varies_by_nature(const std::string& key) {
  const auto ends_with = [&](const std::string& s) {
    return key.size() >= s.size() && key.compare(key.size() - s.size(), s.size(), s) == 0;
  };
  return key == "seconds" || ends_with("_seconds") || ends_with("per_second") || ends_with("timings") ||
         key == "time_total" || key == "time_wall" || key == "peak_memory_mib";
}

json without_timings(const json& j) {
  if (j.is_object()) {
    json out = json::object();
    for (auto it = j.begin(); it != j.end(); ++it)
      if (!varies_by_nature(it.key())) out[it.key()] = without_timings(it.value());
    return out;
  }
  if (j.is_array()) {
    json out = json::array();
    for (const json& v : j) out.push_back(without_timings(v));
    return out;
  }
  return j;
}

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  REQUIRE(in);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Runs the experiment into `results` with OMP_NUM_THREADS=threads; returns its runs folder.
fs::path run_with_threads(const ScratchDir& dir, const std::string& config, const std::string& id, int threads) {
  const Outcome o = run_process({DTSL_EXECUTABLE, "run", config, "--results", (dir.path() / "results").string(),
                                 "--run-id", id, "--jobs", "2", "--quiet"},
                                command_timeout(600), {"OMP_NUM_THREADS=" + std::to_string(threads)});
  INFO(o.describe() << "\n" << o.output);
  REQUIRE(o.exit_code == 0);
  return dir.path() / "results" / "determinism" / id / "runs";
}

}  // namespace

TEST_CASE("same input, config and seed: identical meshes and metrics, with 1 or 2 threads", "[.determinism]") {
  ScratchDir dir;
  const std::string config = (dir.path() / "determinism.yaml").string();
  std::ofstream(config) << kExperiment;
  const fs::path a = run_with_threads(dir, config, "a", 2);
  const fs::path b = run_with_threads(dir, config, "b", 2);
  const fs::path c = run_with_threads(dir, config, "c", 1);
  for (const char* run : {"torus__poisson", "torus__dtsl"}) {
    std::vector<std::string> meshes;
    for (const auto& e : fs::directory_iterator(a / run))
      if (e.path().extension() == ".ply") meshes.push_back(e.path().filename().string());
    REQUIRE(!meshes.empty());
    const json reference = without_timings(json::parse(bytes_of(a / run / "metrics.json")));
    CHECK(reference.value("status", "") == "ok");
    for (const fs::path& other : {b, c}) {
      INFO(run << ": " << a.parent_path().filename() << " vs " << other.parent_path().filename());
      for (const std::string& m : meshes) {
        INFO(m);
        CHECK(bytes_of(a / run / m) == bytes_of(other / run / m));
      }
      const json record = without_timings(json::parse(bytes_of(other / run / "metrics.json")));
      // The difference, if any, names the fields that changed.
      // Run to run and across thread counts alike (reductions sum in point order).
      CHECK(json::diff(reference, record).dump() == "[]");
    }
  }
}
