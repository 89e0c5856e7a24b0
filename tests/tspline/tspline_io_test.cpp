// Saving and loading the level set (identical values after a round trip, clear errors on malformed
// files), and the T-mesh as line geometry.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "algorithms/tspline/tspline_io.hpp"
#include "framework/core/error.hpp"
#include "tests/tspline/fixtures.hpp"

using namespace dtsl;

namespace {

/// A scratch folder for this test run, removed when the program exits.
struct ScratchDir {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("dtsl_tspline_test_" + std::to_string(::getpid()));
  ScratchDir() { std::filesystem::create_directories(path); }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

std::string temp_path(const std::string& name) {
  static const ScratchDir dir;
  return (dir.path / name).string();
}

std::string read_all(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_all(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

}  // namespace

TEST_CASE("save/load round trip gives identical values", "[tspline][io]") {
  for (const auto& [name, basis] : test::all_bases()) {
    SECTION(name) {
      const TSpline f(basis, test::random_coefficients(*basis, 31));
      const std::string path = temp_path("roundtrip.tspline");
      save_tspline(path, f);
      const TSpline g = load_tspline(path);
      REQUIRE(g.basis().size() == f.basis().size());
      CHECK(g.coefficients() == f.coefficients());
      CHECK(g.tmesh().leaf_count() == f.tmesh().leaf_count());
      for (const Vec3& x : test::random_points(f.domain(), 2000, 32)) {
        Vec3 gf, gg;
        Mat3 hf, hg;
        CHECK(f.evaluate(x, &gf, &hf) == g.evaluate(x, &gg, &hg));
        CHECK(gf == gg);
        CHECK(hf == hg);
      }
    }
  }
}

TEST_CASE("loading a malformed level-set file names the file and the problem", "[tspline][io]") {
  auto basis = test::adaptive_basis();
  const TSpline f(basis, test::random_coefficients(*basis, 33));
  const std::string good = temp_path("good.tspline");
  save_tspline(good, f);
  const std::string text = read_all(good);
  const std::string bad = temp_path("bad.tspline");

  auto expect_error = [&](const std::string& content, const std::string& problem) {
    write_all(bad, content);
    INFO("expected problem: " << problem);
    CHECK_THROWS_AS(load_tspline(bad), FileError);
    CHECK_THROWS_WITH(load_tspline(bad), Catch::Contains(bad) && Catch::Contains(problem));
  };
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const auto at = t.find(from);
    REQUIRE(at != std::string::npos);
    return t.replace(at, from.size(), to);
  };

  CHECK_THROWS_WITH(load_tspline(temp_path("missing.tspline")), Catch::Contains("missing.tspline") && Catch::Contains("cannot open"));
  expect_error("", "end of file");
  expect_error("ply\nformat ascii 1.0\n", "not a dtsl T-spline file");
  expect_error(replace("dtsl-tspline 1", "dtsl-tspline 7"), "unsupported version");
  expect_error(replace("max_depth 5", "max_depth 12"), "outside");
  expect_error(replace("max_depth 5", "max_depth five"), "not an integer");
  expect_error(text.substr(0, text.size() / 2), "end of file");
  expect_error(replace("coefficients " + std::to_string(basis->size()), "coefficients 12"), "control points");
  expect_error(replace("\nend\n", "\n"), "end of file");
  expect_error(replace("leaves " + std::to_string(basis->octree().leaf_count()), "leaves 1000000000"), "outside");
  expect_error(replace("leaves " + std::to_string(basis->octree().leaf_count()), "leaves 32768"), "leaf record");
  // A leaf dropped: the T-mesh has a gap.
  {
    std::string t = text;
    const auto leaves = t.find("leaves ");
    const auto first = t.find('\n', leaves) + 1;
    const auto second = t.find('\n', first) + 1;
    t.erase(first, second - first);
    t.replace(leaves, t.find('\n', leaves) - leaves, "leaves " + std::to_string(basis->octree().leaf_count() - 1));
    expect_error(t, "gap");
  }
  // A coefficient that is not a number, with its line number.
  {
    std::string t = text;
    const auto at = t.find("coefficients ");
    const auto line_start = t.find('\n', at) + 1;
    t.replace(line_start, t.find('\n', line_start) - line_start, "abc");
    const long line = std::count(t.begin(), t.begin() + line_start, '\n') + 1;
    write_all(bad, t);
    CHECK_THROWS_WITH(load_tspline(bad), Catch::Contains(bad + ":" + std::to_string(line)) && Catch::Contains("'abc'"));
  }
}

TEST_CASE("T-mesh line geometry: every leaf edge once, written as an .obj", "[tspline][io]") {
  // Uniform grid of n cells per axis: 3 n (n + 1)^2 distinct edges.
  for (int depth : {1, 3}) {
    const Octree t = uniform_octree(depth, 0.25);
    const int n = 1 << depth;
    CHECK(tmesh_edges(t).size() == std::size_t(3 * n * (n + 1) * (n + 1)));
  }
  const Octree& t = test::adaptive_basis()->octree();
  const auto edges = tmesh_edges(t);
  const double unit = t.unit();
  for (const auto& e : edges) {
    const Vec3 d = e[1] - e[0];
    CHECK((d.array().abs() > 0).count() == 1);  // axis-aligned
    CHECK(d.norm() >= unit * (1 - 1e-12));
  }
  const std::string path = temp_path("tmesh.obj");
  write_tmesh_obj(path, t);
  const std::string obj = read_all(path);
  CHECK(std::count(obj.begin(), obj.end(), 'l') >= long(edges.size()));
  std::istringstream in(obj);
  long v = 0, l = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) == 0) ++v;
    if (line.rfind("l ", 0) == 0) ++l;
  }
  CHECK(l == long(edges.size()));
  CHECK(v >= 2);
}
