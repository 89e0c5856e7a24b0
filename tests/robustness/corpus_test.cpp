// The robustness corpus (corpus/, written by make_corpus.py; expectations in corpus/expectations.txt)
// through the command line: every point file through `dtsl reconstruct` with the baseline and with the
// method, every config through `dtsl run`. Each must end in a clear error naming the problem (exit 1,
// the expected substring) with nothing written, or, for degenerate but valid inputs, in a valid mesh;
// never a crash, a hang or a partial output.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "framework/core/error.hpp"
#include "framework/io/io.hpp"
#include "tests/robustness/process.hpp"

namespace fs = std::filesystem;
using namespace dtsl::test;

namespace {

const std::string kCorpus = std::string(DTSL_SOURCE_DIR) + "/tests/robustness/corpus";

std::vector<CorpusEntry> entries_under(const std::string& folder) {
  std::vector<CorpusEntry> out;
  for (const CorpusEntry& e : read_expectations(kCorpus + "/expectations.txt"))
    if (e.file.rfind(folder + "/", 0) == 0) out.push_back(e);
  return out;
}

// A clean failure: exit code 1, "dtsl: error:" and the expected words.
void check_clean_error(const Outcome& o, const std::string& expected) {
  CHECK(o.exit_code == 1);
  CHECK(contains(o.output, "dtsl: error:"));
  CHECK(contains(o.output, expected));
}

// A written mesh must read back: triangles, finite coordinates, indices in range (read_mesh checks).
void check_valid_mesh(const std::string& path) {
  try {
    const dtsl::TriangleMesh m = dtsl::read_mesh(path);
    CHECK(!m.faces.empty());
  } catch (const dtsl::Error& e) {
    FAIL_CHECK("the output does not read back as a mesh: " << e.what());
  }
}

}  // namespace

TEST_CASE("the corpus has at least 40 bad inputs, each file present") {
  const auto all = read_expectations(kCorpus + "/expectations.txt");
  std::size_t bad = 0;
  for (const CorpusEntry& e : all) {
    INFO(e.file);
    CHECK(fs::exists(kCorpus + "/" + e.file));
    if (e.must_fail) {
      ++bad;
      CHECK(!e.expected.empty());
    }
  }
  CHECK(bad >= 40);
}

namespace {

void check_point_files(const std::string& pipeline) {
  const double timeout = command_timeout(120);
  for (const CorpusEntry& e : entries_under("points")) {
    ScratchDir dir;
    const std::string out = (dir.path() / "out.ply").string();
    const Outcome o = run_process({DTSL_EXECUTABLE, "reconstruct", kCorpus + "/" + e.file, out, "--pipeline", pipeline},
                                  timeout);
    INFO(e.file << " with --pipeline " << pipeline << ": " << o.describe() << "\n" << o.output);
    REQUIRE_FALSE(o.timed_out);
    REQUIRE_FALSE(o.crashed());
    if (e.must_fail || o.exit_code != 0) {
      check_clean_error(o, e.expected);
      CHECK(dir.files().empty());  // no output, no temporary file
    } else {
      check_valid_mesh(out);
      CHECK(dir.files() == std::vector<std::string>{"out.ply"});
    }
  }
}

}  // namespace

TEST_CASE("dtsl reconstruct --pipeline pcl_poisson: every corpus point file rejected by name or meshed cleanly",
          "[.corpus_baseline]") {
  check_point_files("pcl_poisson");
}

TEST_CASE("dtsl reconstruct --pipeline dtsl: every corpus point file rejected by name or meshed cleanly",
          "[.corpus_method]") {
  check_point_files("dtsl");
}

TEST_CASE("dtsl run: every corpus config is rejected by key before anything is written", "[.corpus_baseline]") {
  const double timeout = command_timeout(120);
  for (const CorpusEntry& e : entries_under("configs")) {
    ScratchDir dir;
    const Outcome o = run_process(
        {DTSL_EXECUTABLE, "run", kCorpus + "/" + e.file, "--results", (dir.path() / "results").string(), "--quiet"},
        timeout);
    INFO(e.file << ": " << o.describe() << "\n" << o.output);
    REQUIRE_FALSE(o.timed_out);
    REQUIRE_FALSE(o.crashed());
    check_clean_error(o, e.expected);
    CHECK(!fs::exists(dir.path() / "results"));
  }
}
