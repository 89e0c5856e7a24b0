// The pictures of one run in the report: a run whose record names a line file (the T-mesh of dtsl runs)
// gets a "points + T-mesh" panel before its stage meshes; runs without one (baselines, results written
// before the T-mesh was kept, a file gone missing) render as before. Synthetic result directories.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "framework/core/error.hpp"
#include "framework/io/io.hpp"
#include "framework/pipeline/line_obj.hpp"
#include "framework/report/mesh_figures.hpp"

using namespace dtsl;
using namespace dtsl::report;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

TriangleMesh cube(double h) {
  TriangleMesh m;
  for (int c = 0; c < 8; ++c) m.vertices.push_back({(c & 1) ? h : -h, (c & 2) ? h : -h, (c & 4) ? h : -h});
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) m.faces.push_back({q[0], q[1], q[2]}), m.faces.push_back({q[0], q[2], q[3]});
  return m;
}

/// A result directory with dataset "ball" (points) and run "ball__dtsl" (MI, final mesh, T-mesh lines).
struct ResultDir {
  fs::path root = fs::temp_directory_path() / ("dtsl_run_renders_" + std::to_string(::getpid()));
  fs::path run = root / "runs" / "ball__dtsl";
  ResultDir() {
    fs::remove_all(root);
    fs::create_directories(root / "datasets" / "ball");
    fs::create_directories(run);
    PointCloud pts;
    for (int i = 0; i < 400; ++i) {  // points on the cube's surface
      const double a = -0.5 + (i % 20) / 19.0, b = -0.5 + (i / 20) / 19.0;
      pts.points.push_back(i % 2 ? Vec3(a, b, 0.5) : Vec3(0.5, a, b));
    }
    write_points((root / "datasets" / "ball" / "points.ply").string(), pts);
    write_mesh((run / "stage_MI.ply").string(), cube(0.5));
    write_mesh((run / "final.ply").string(), cube(0.5));
    std::vector<Segment> cells;  // a 4 x 4 grid of cell edges on the front face and through the cube
    for (int k = 0; k <= 4; ++k) {
      const double c = -0.5 + 0.25 * k;
      cells.push_back({Vec3(c, -0.5, 0.5), Vec3(c, 0.5, 0.5)});
      cells.push_back({Vec3(-0.5, c, 0.5), Vec3(0.5, c, 0.5)});
      cells.push_back({Vec3(c, 0.0, -0.75), Vec3(c, 0.0, 0.75)});
    }
    write_line_obj((run / "tmesh.obj").string(), cells, "test");
  }
  ~ResultDir() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
};

json record(bool with_lines, const std::string& lines_file = "tmesh.obj") {
  json tl = {{"name", "TL"}, {"seconds", 1.0}, {"summary", json::object()}};
  if (with_lines) tl["lines_file"] = lines_file, tl["lines_label"] = "T-mesh";
  json mt = {{"name", "MT"}, {"seconds", 0.1}, {"mesh_label", "MI"}, {"file", "stage_MI.ply"}, {"summary", json::object()}};
  return {{"run", "ball__dtsl"}, {"type", "dtsl"}, {"pipeline", "dtsl"}, {"status", "ok"}, {"stages", {tl, mt}}};
}

ReportOptions small() {
  ReportOptions o;
  o.panel_size = 96;
  o.views = 1;
  return o;
}

/// Pixels of panel `column` in the line colour's hue (warm: red well above blue).
int warm_pixels(const render::Image& img, int column, int panel) {
  int n = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = column * panel + 1; x < (column + 1) * panel; ++x) {
      const render::Rgb p = img.at(x, y);
      n += p.r > p.b + 60;
    }
  return n;
}

}  // namespace

TEST_CASE("a run with a T-mesh file gets a points + T-mesh panel before its stage meshes") {
  const ResultDir dir;
  const int panel = small().panel_size;
  const render::Image with = run_renders(dir.root, record(true), "ball", small());
  CHECK(with.width() == 3 * panel);  // points | points + T-mesh | MI
  CHECK(warm_pixels(with, 1, panel) > 20);
  CHECK(warm_pixels(with, 0, panel) == 0);
  CHECK(warm_pixels(with, 2, panel) == 0);
}

TEST_CASE("runs without a T-mesh render as before: no file named, a named file missing, a baseline") {
  const ResultDir dir;
  const int panel = small().panel_size;
  const render::Image old = run_renders(dir.root, record(false), "ball", small());
  CHECK(old.width() == 2 * panel);  // points | MI
  CHECK(warm_pixels(old, 0, panel) + warm_pixels(old, 1, panel) == 0);
  CHECK(run_renders(dir.root, record(true, "gone.obj"), "ball", small()).width() == 2 * panel);
  const json baseline = {{"run", "ball__dtsl"}, {"type", "pcl_poisson"}, {"pipeline", "poisson"}, {"status", "ok"}};
  CHECK(run_renders(dir.root, baseline, "ball", small()).width() == 2 * panel);  // points | final
}

TEST_CASE("a malformed T-mesh file is a FileError naming it") {
  const ResultDir dir;
  {
    std::ofstream out(dir.run / "tmesh.obj");
    out << "v 0 0 0\nv 1 0 0\nl 1 3\n";
  }
  CHECK_THROWS_WITH(run_renders(dir.root, record(true), "ball", small()), Catch::Contains("tmesh.obj"));
}

TEST_CASE("line files round-trip exactly and read polylines and relative indices") {
  const ResultDir dir;
  const std::vector<Segment> s = {{Vec3(0.1, 0.2, 0.3), Vec3(1.0 / 3.0, 0.2, 0.3)}, {Vec3(0.1, 0.2, 0.3), Vec3(-2, 5e-17, 7)}};
  const std::string p = (dir.root / "l.obj").string();
  write_line_obj(p, s);
  const std::vector<Segment> back = read_line_obj(p);
  REQUIRE(back.size() == 2);
  for (int i = 0; i < 2; ++i) CHECK((back[i][0] == s[i][0] && back[i][1] == s[i][1]));
  {
    std::ofstream out(p);
    out << "# comment\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nl 1 2 3\nl -1 -3\n";
  }
  const std::vector<Segment> poly = read_line_obj(p);
  REQUIRE(poly.size() == 3);
  CHECK(poly[1][1] == Vec3(1, 1, 0));
  CHECK(poly[2][0] == Vec3(1, 1, 0));
  CHECK(poly[2][1] == Vec3(0, 0, 0));
  for (const char* bad : {"v 0 0\n", "v 0 0 x\nl 1 1\n", "v 0 0 0\nl 1\n", "v 0 0 0\nl 0 1\n", "v 0 0 0\nl 1 2\n"}) {
    std::ofstream(p) << bad;
    CHECK_THROWS_AS(read_line_obj(p), FileError);
  }
  CHECK_THROWS_AS(write_line_obj(p, {{Vec3(0, 0, 0), Vec3(NAN, 0, 0)}}), FileError);
}
