// The figure code's properties: the rasteriser draws what is in front, upright and shaded; PNGs are
// written atomically and read back with the right size; charts put their data where the axes say.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <unistd.h>

#include "framework/core/error.hpp"
#include "framework/render/chart.hpp"
#include "framework/render/font.hpp"
#include "framework/render/png.hpp"
#include "framework/render/rasterizer.hpp"
#include "framework/render/scene_figure.hpp"

using namespace dtsl;
using namespace dtsl::render;
namespace fs = std::filesystem;

namespace {

/// An axis-aligned box as a closed triangle mesh (outward normals).
TriangleMesh box_mesh(const Vec3& lo, const Vec3& hi) {
  TriangleMesh m;
  for (int c = 0; c < 8; ++c)
    m.vertices.push_back({(c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z()});
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.faces.push_back({q[0], q[1], q[2]});
    m.faces.push_back({q[0], q[2], q[3]});
  }
  return m;
}

bool is_background(const Image& img, int x, int y) {
  const Rgb p = img.at(x, y);
  return p.r == 255 && p.g == 255 && p.b == 255;
}

int brightness(Rgb p) { return p.r + p.g + p.b; }

}  // namespace

TEST_CASE("a box is drawn in the middle, the background stays white") {
  const TriangleMesh m = box_mesh({-1, -1, -1}, {1, 1, 1});
  Canvas c(100, 100);
  const Camera cam(bounding_box(m.vertices), 100, 100, ViewOptions{});
  c.draw_mesh(m, cam);
  CHECK(!is_background(c.image(), 50, 50));
  CHECK(is_background(c.image(), 0, 0));
  CHECK(is_background(c.image(), 99, 99));
}

TEST_CASE("renders are upright: what is higher along the up axis is higher in the picture") {
  for (char up : {'x', 'y', 'z'}) {
    // A small box at the top end of the up axis, a big one below.
    Vec3 axis = up == 'x' ? Vec3::UnitX() : up == 'y' ? Vec3::UnitY() : Vec3::UnitZ();
    TriangleMesh top = box_mesh(Vec3::Constant(-0.1) + 0.9 * axis, Vec3::Constant(0.1) + 0.9 * axis);
    BoundingBox box;
    box.extend(Vec3::Constant(-1)), box.extend(Vec3::Constant(1));
    ViewOptions v;
    v.up = up;
    Canvas c(200, 200);
    c.draw_mesh(top, Camera(box, 200, 200, v));
    int ysum = 0, n = 0;
    for (int y = 0; y < 200; ++y)
      for (int x = 0; x < 200; ++x)
        if (!is_background(c.image(), x, y)) ysum += y, ++n;
    INFO("up " << up);
    REQUIRE(n > 0);
    CHECK(ysum / n < 70);  // in the upper third
  }
}

TEST_CASE("faces towards the light are brighter, and nearer geometry hides farther geometry") {
  // Looking from +z (azimuth 0, elevation 0, up y): the light is from the upper left.
  ViewOptions v;
  v.azimuth_deg = 0, v.elevation_deg = 0;
  BoundingBox box;
  box.extend(Vec3::Constant(-1)), box.extend(Vec3::Constant(1));
  const Camera cam(box, 100, 100, v);
  TriangleMesh facing = box_mesh({-0.8, -0.8, 0.4}, {0.8, 0.8, 0.5});
  TriangleMesh behind = box_mesh({-0.9, -0.9, -0.5}, {0.9, 0.9, -0.4});
  Canvas c(100, 100);
  c.draw_mesh(facing, cam);
  const Rgb front = c.image().at(50, 50);
  c.draw_mesh(behind, cam);  // drawn later but farther: must not overwrite
  CHECK(brightness(c.image().at(50, 50)) == brightness(front));
  // A plane tilted away from the light is darker than one facing it.
  TriangleMesh lit, dark;
  lit.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  lit.faces = {{0, 1, 2}};
  dark = lit;
  for (Vec3& p : dark.vertices) p.z() = -p.x();  // normal (1, 0, 1): turned to +x, the light comes from -x
  Canvas a(100, 100), b(100, 100);
  a.draw_mesh(lit, cam);
  b.draw_mesh(dark, cam);
  CHECK(brightness(a.image().at(60, 40)) > brightness(b.image().at(60, 40)));
}

TEST_CASE("points are drawn as splats") {
  std::vector<Vec3> pts = {{0, 0, 0}, {0.5, 0.5, 0}, {-0.5, -0.5, 0}};
  BoundingBox box;
  box.extend(Vec3::Constant(-1)), box.extend(Vec3::Constant(1));
  ViewOptions v;
  v.azimuth_deg = 0, v.elevation_deg = 0;
  Canvas c(101, 101);
  c.draw_points(pts, Camera(box, 101, 101, v));
  int drawn = 0;
  for (const Rgb& p : c.image().pixels()) drawn += !(p.r == 255 && p.g == 255 && p.b == 255);
  CHECK(drawn >= 3);
  CHECK(drawn < 3 * 30);
}

TEST_CASE("a scene has one column per item and one row per view, with labels") {
  const TriangleMesh m = box_mesh({-1, -1, -1}, {1, 1, 1});
  std::vector<Vec3> pts = m.vertices;
  SceneOptions o;
  o.panel_size = 64;
  const Image img = render_scene({{"mesh", &m, nullptr}, {"points", nullptr, &pts}}, o);
  CHECK(img.width() == 2 * 64);
  CHECK(img.height() > 2 * 64);
  o.panel_size = 8;
  CHECK_THROWS_AS(render_scene({{"mesh", &m, nullptr}}, o), ConfigError);
}

TEST_CASE("PNG files are written atomically and read back with their size") {
  const fs::path p = fs::temp_directory_path() / ("dtsl_render_" + std::to_string(::getpid()) + ".png");
  Image img(37, 21, {10, 20, 30});
  draw_text(img, 1, 1, "Hi", {255, 255, 255});
  write_png(p.string(), img);
  CHECK(png_size(p.string()) == std::make_pair(37, 21));
  fs::remove(p);
  CHECK_THROWS_AS(write_png(p.string(), Image()), FileError);
  CHECK(!fs::exists(p));
  CHECK_THROWS_AS(write_png("/nonexistent-dir/x.png", img), FileError);
  CHECK_THROWS_AS(png_size("/nonexistent-dir/x.png"), FileError);
}

TEST_CASE("text is drawn inside its advertised box") {
  Image img(200, 40);
  draw_text(img, 10, 10, "Ag_9~", {0, 0, 0}, 2);
  int minx = 1000, maxx = -1, miny = 1000, maxy = -1;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      if (!is_background(img, x, y)) minx = std::min(minx, x), maxx = std::max(maxx, x), miny = std::min(miny, y), maxy = std::max(maxy, y);
  CHECK(minx >= 10);
  CHECK(maxx < 10 + text_width("Ag_9~", 2));
  CHECK(miny >= 10);
  CHECK(maxy < 10 + char_height(2));
}

TEST_CASE("nice ticks are round, ordered and cover the range") {
  for (auto [lo, hi] : {std::pair{0.0, 1.0}, {0.0013, 0.0071}, {-3.0, 250.0}, {5.0, 5.5}}) {
    const std::vector<double> t = nice_ticks(lo, hi, 6);
    INFO(lo << " " << hi);
    REQUIRE(t.size() >= 2);
    CHECK(t.size() <= 12);
    for (std::size_t i = 1; i < t.size(); ++i) CHECK(t[i] > t[i - 1]);
    CHECK(t.front() >= lo - 1e-12);
    CHECK(t.back() <= hi + 1e-12);
    const double step = t[1] - t[0];
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    CHECK((std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 || std::abs(mantissa - 5) < 1e-6));
  }
}

TEST_CASE("a line chart draws its series inside the plot, rising data from lower left to upper right") {
  LineChart c;
  c.title = "t";
  c.series.push_back({"s", {0, 1, 2, 3}, {0, 1, 2, 3}, false});
  const Image img = c.draw();
  // Find pixels of the first palette colour.
  const Rgb col = palette(0);
  int n = 0;
  double sx = 0, sy = 0, sxy = 0, sxx = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const Rgb p = img.at(x, y);
      if (p.r == col.r && p.g == col.g && p.b == col.b) ++n, sx += x, sy += y, sxy += double(x) * y, sxx += double(x) * x;
    }
  REQUIRE(n > 50);
  const double slope = (sxy - sx * sy / n) / (sxx - sx * sx / n);
  CHECK(slope < 0);  // image y grows downwards: rising data has a negative slope in pixels
  LineChart empty;
  CHECK(empty.draw().width() == empty.width);  // "no data", not a crash
  LineChart logc;
  logc.log_y = true;
  logc.series.push_back({"neg", {0, 1}, {-1, 0}, true});  // nothing drawable on a log axis
  CHECK(logc.draw().height() == logc.height);
}

TEST_CASE("a bar chart grows with its rows and draws longer bars for larger values") {
  BarChart b;
  b.rows = {"small", "large"};
  b.segments = {"s"};
  b.values = {{1.0}, {4.0}};
  const Image img = b.draw();
  BarChart more = b;
  more.rows.push_back("third");
  more.values.push_back({2.0});
  CHECK(more.draw().height() > img.height());
  auto bar_length = [&](int row) {
    const int y = 16 + char_height(2) + 12 + row * b.row_height + b.row_height / 2;
    int len = 0;
    const Rgb col = palette(0);
    for (int x = 0; x < img.width(); ++x) {
      const Rgb p = img.at(x, y);
      len += p.r == col.r && p.g == col.g && p.b == col.b;
    }
    return len;
  };
  CHECK(bar_length(1) > 3 * bar_length(0));
  CHECK(bar_length(0) > 0);
}
