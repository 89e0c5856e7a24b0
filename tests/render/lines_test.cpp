// Line drawing of the rasteriser (the T-mesh over the points, the paper's Fig. 1a): a line covers the
// pixels between its ends without gaps, each once; the depth test hides what is behind a surface, or
// fades it; lines never hide points; an occluder hides what lies behind it but not what lies on it.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <set>

#include "framework/core/error.hpp"
#include "framework/render/rasterizer.hpp"
#include "framework/render/scene_figure.hpp"

using namespace dtsl;
using namespace dtsl::render;

namespace {

using Segment = std::array<Vec3, 2>;

BoundingBox unit_box() {
  BoundingBox box;
  box.extend(Vec3::Constant(-1)), box.extend(Vec3::Constant(1));
  return box;
}

/// Looking along -z (azimuth 0, elevation 0, up y): screen x grows with model x, screen y with -y, and
/// depth with z (nearer the viewer).
ViewOptions front_view() {
  ViewOptions v;
  v.azimuth_deg = 0, v.elevation_deg = 0;
  return v;
}

/// The model point at depth z that the camera maps to screen position (px, py): the front view is a
/// scaled translation, recovered from the images of the origin and the unit vectors.
Vec3 model_at(const Camera& cam, double px, double py, double z) {
  const Eigen::Vector3d o = cam.project(Vec3::Zero());
  return {(px - o.x()) / cam.scale(), -(py - o.y()) / cam.scale(), z};
}

/// A square in the plane z, facing the viewer, over [-h, h]^2.
TriangleMesh square(double h, double z) {
  TriangleMesh m;
  m.vertices = {{-h, -h, z}, {h, -h, z}, {h, h, z}, {-h, h, z}};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

bool is_white(Rgb p) { return p.r == 255 && p.g == 255 && p.b == 255; }
bool same(Rgb a, Rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

}  // namespace

TEST_CASE("a line from one pixel to another covers exactly the pixels between them") {
  const Camera cam(unit_box(), 120, 120, front_view());
  LineStyle black;
  black.colour = {0, 0, 0};
  // Pixel centres (10, 20) -> (40, 20): the 31 pixels of row 20 from column 10 to 40, nothing else.
  Canvas c(120, 120);
  c.draw_lines({{model_at(cam, 10.5, 20.5, 0), model_at(cam, 40.5, 20.5, 0)}}, cam, black);
  int drawn = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 120; ++x)
      if (!is_white(c.image().at(x, y))) {
        ++drawn;
        CHECK(y == 20);
        CHECK((x >= 10 && x <= 40));
      }
  CHECK(drawn == 31);
  // A diagonal (5, 5) -> (25, 25): the pixels (k, k).
  Canvas d(120, 120);
  d.draw_lines({{model_at(cam, 5.5, 5.5, 0), model_at(cam, 25.5, 25.5, 0)}}, cam, black);
  for (int k = 5; k <= 25; ++k) CHECK(!is_white(d.image().at(k, k)));
  CHECK(is_white(d.image().at(4, 4)));
  CHECK(is_white(d.image().at(26, 26)));
}

TEST_CASE("random lines between pixels: one pixel per step of the longer axis, on the line, both ends included") {
  const int n = 160;
  const Camera cam(unit_box(), n, n, front_view());
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> u(2, n - 3);  // pixels; the line joins their centres
  LineStyle black;
  black.colour = {0, 0, 0};
  for (int trial = 0; trial < 200; ++trial) {
    const double ax = u(rng) + 0.5, ay = u(rng) + 0.5, bx = u(rng) + 0.5, by = u(rng) + 0.5;
    if (ax == bx && ay == by) continue;
    Canvas c(n, n);
    c.draw_lines({{model_at(cam, ax, ay, 0.1), model_at(cam, bx, by, -0.3)}}, cam, black);
    std::set<std::pair<int, int>> covered;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        if (!is_white(c.image().at(x, y))) covered.insert({x, y});
    INFO("trial " << trial << ": (" << ax << ", " << ay << ") -> (" << bx << ", " << by << ")");
    CHECK(covered.count({int(std::floor(ax)), int(std::floor(ay))}));
    CHECK(covered.count({int(std::floor(bx)), int(std::floor(by))}));
    const bool steep = std::abs(by - ay) > std::abs(bx - ax);
    const double a_major = steep ? ay : ax, b_major = steep ? by : bx;
    const int m0 = int(std::floor(std::min(a_major, b_major))), m1 = int(std::floor(std::max(a_major, b_major)));
    CHECK(int(covered.size()) == m1 - m0 + 1);  // no gaps, no pixel twice, nothing beyond the ends
    for (const auto& [x, y] : covered) {
      const int major = steep ? y : x;
      CHECK((major >= m0 && major <= m1));
      // The pixel centre's distance from the line: at most half a pixel (within its row or column) plus rounding.
      const double dist = std::abs((bx - ax) * (ay - (y + 0.5)) - (ax - (x + 0.5)) * (by - ay)) / std::hypot(bx - ax, by - ay);
      CHECK(dist <= 0.5 + 1e-9);
    }
  }
}

TEST_CASE("the depth test hides a line behind a triangle, draws one in front, fades a hidden one if asked") {
  const int n = 100;
  const Camera cam(unit_box(), n, n, front_view());
  const TriangleMesh wall = square(0.5, 0.0);
  LineStyle red;
  red.colour = {255, 0, 0};
  auto across = [&](double z) {  // a horizontal line through the middle, at depth z, wider than the wall
    return std::vector<Segment>{{Vec3(-0.9, 0.0, z), Vec3(0.9, 0.0, z)}};
  };
  const Eigen::Vector3d centre = cam.project(Vec3::Zero()), outside = cam.project(Vec3(-0.8, 0.0, 0.0));
  const int cx = int(centre.x()), cy = int(centre.y()), ox = int(outside.x()), oy = int(outside.y());

  Canvas behind(n, n);
  behind.draw_mesh(wall, cam);
  const Rgb wall_colour = behind.image().at(cx, cy);
  behind.draw_lines(across(-0.5), cam, red);
  CHECK(same(behind.image().at(cx, cy), wall_colour));      // hidden by the wall
  CHECK(same(behind.image().at(ox, oy), red.colour));       // beside the wall: nothing in front of it

  Canvas front(n, n);
  front.draw_mesh(wall, cam);
  front.draw_lines(across(0.5), cam, red);
  CHECK(same(front.image().at(cx, cy), red.colour));

  Canvas faded(n, n);
  faded.draw_mesh(wall, cam);
  LineStyle faint = red;
  faint.hidden_alpha = 0.3;
  faded.draw_lines(across(-0.5), cam, faint);
  const Rgb f = faded.image().at(cx, cy);
  CHECK(!same(f, wall_colour));
  CHECK(!same(f, red.colour));
  CHECK(f.r > wall_colour.r);  // tinted towards the line's colour

  // A line lying on the surface is drawn (a bias towards the viewer keeps it so under rounding).
  Canvas on(n, n);
  on.draw_mesh(wall, cam);
  LineStyle biased = red;
  biased.depth_bias = 1e-6;
  on.draw_lines(across(0.0), cam, biased);
  CHECK(same(on.image().at(cx, cy), red.colour));
}

TEST_CASE("lines hide no points; an occluder hides what is behind it and nothing else") {
  const int n = 100;
  const Camera cam(unit_box(), n, n, front_view());
  // Lines write no depth: a point drawn later, even behind the line, shows.
  Canvas c(n, n);
  LineStyle red;
  red.colour = {255, 0, 0};
  c.draw_lines({{Vec3(-0.9, 0.0, 0.5), Vec3(0.9, 0.0, 0.5)}}, cam, red);
  c.draw_points({Vec3(0.0, 0.0, -0.5)}, cam);
  const Eigen::Vector3d p = cam.project(Vec3::Zero());
  CHECK(!same(c.image().at(int(p.x()), int(p.y())), red.colour));
  CHECK(!is_white(c.image().at(int(p.x()), int(p.y()))));

  // The occluder: invisible itself; a point on it shows (the offset), one behind it does not.
  Canvas o(n, n);
  o.draw_depth(square(0.8, 0.0), cam, 0.05);
  for (const Rgb& px : o.image().pixels()) REQUIRE(is_white(px));
  const Vec3 on(-0.4, 0.4, 0.0), behind(0.4, -0.4, -0.3), beside(0.9, 0.9, -0.3);
  o.draw_points({on, behind, beside}, cam);
  auto at = [&](const Vec3& q) {
    const Eigen::Vector3d s = cam.project(q);
    return o.image().at(int(s.x()), int(s.y()));
  };
  CHECK(!is_white(at(on)));
  CHECK(is_white(at(behind)));
  CHECK(!is_white(at(beside)));
  LineStyle style;
  o.draw_lines({{Vec3(-0.2, 0.2, -0.3), Vec3(0.2, 0.2, -0.3)}}, cam, style);  // behind: hidden
  CHECK(is_white(at(Vec3(0.0, 0.2, -0.3))));
}

TEST_CASE("a scene item with lines and an occluder: lines drawn, the frame set by points and meshes only") {
  const std::vector<Vec3> pts = {{-1, -1, -1}, {1, 1, 1}};
  const std::vector<Segment> far = {{Vec3(-5, 0, 0), Vec3(5, 0, 0)}};  // beyond the points
  const TriangleMesh wall = square(0.5, 0.0);
  SceneItem item{"points + T-mesh", nullptr, &pts, &far, &wall};
  const BoundingBox box = scene_box({item});
  CHECK(box.min.isApprox(Vec3::Constant(-1)));
  CHECK(box.max.isApprox(Vec3::Constant(1)));
  SceneOptions o;
  o.panel_size = 64;
  o.views = {front_view()};
  const Image img = render_view(item, box, o.views[0], o);
  int warm = 0;
  for (const Rgb& px : img.pixels()) warm += px.r > px.b + 40;
  CHECK(warm > 0);  // the line, clipped to the panel
  o.lines.width = 0;
  CHECK_THROWS_AS(o.check(), ConfigError);
}
