// The initial level set (docs/design.md §1, clipped as initial_level_set.hpp explains) and the
// no-nucleation guard (sign_guard.hpp).
#include <catch2/catch.hpp>

#include "algorithms/evolution/initial_level_set.hpp"
#include "algorithms/evolution/sign_guard.hpp"
#include "framework/core/error.hpp"
#include "tests/evolution/fixtures.hpp"

using namespace dtsl;

TEST_CASE("initial level set: encloses every point, starts inside the domain, genus 0", "[evolution][initial]") {
  for (const auto* name : {"sphere", "torus", "cube surface, corners included"}) {
    DYNAMIC_SECTION(name) {
      std::vector<Vec3> points;
      if (std::string(name) == "sphere") points = test::sphere_data(500);
      else if (std::string(name) == "torus") points = test::torus_data();
      else  // the surface of [-1,1]^3 on a 21^2 grid per face: the sphere alone would leave the domain
        for (int a = 0; a < 3; ++a)
          for (int side = -1; side <= 1; side += 2)
            for (int i = 0; i <= 20; ++i)
              for (int j = 0; j <= 20; ++j) {
                Vec3 p;
                p[a] = side;
                p[(a + 1) % 3] = -1.0 + 0.1 * i;
                p[(a + 2) % 3] = -1.0 + 0.1 * j;
                points.push_back(p);
              }
      const EnclosingSurface sphere_only = enclosing_surface(points, 1.1, 0.0);
      const EnclosingSurface clipped = enclosing_surface(points, 1.1, 0.1);
      CHECK(!sphere_only.clipped);
      CHECK(clipped.clipped);
      double largest = 0.0;
      for (const Vec3& p : points) {
        largest = std::max(largest, (p - sphere_only.centre).norm());
        CHECK(sphere_only(p) < 0.0);
        // Inside both: by 0.1 x the radius for the sphere, by the rounding radius 0.1 at a box corner.
        CHECK(clipped(p) < -0.05);
      }
      CHECK(sphere_only.radius == Approx(1.1 * largest));
      // The clipped surface lies inside [-1.1, 1.1]^3, inside the T-mesh's domain [-1.25, 1.25]^3.
      CHECK(clipped(Vec3(1.1 + 1e-9, 0, 0)) > 0.0);
      CHECK(clipped(Vec3(1.1, 1.1, 1.1)) > 0.0);  // the rounded corner
      EvolutionOptions o = test::test_options("distance", "eigen_cg");
      auto basis = std::make_shared<TSplineBasis>(build_octree(points, o.tmesh));
      const TSpline f = initial_level_set(basis, points, 1.1, 0.1);
      for (const Vec3& p : points) CHECK(f.evaluate(p) < 0.0);
      const MeshStats s = mesh_stats(test::zero_set_mesh(f, points, 0.05, "domain"));
      CHECK(s.components == 1);
      // Data filling their box up to the corners on a T-mesh of 0.31 cells (this cube's octree stays at
      // level 3): the box 0.1 outside the data is blurred by half a cell and the zero set may touch the
      // domain's faces (as the unclipped docs/design.md sphere always does there). Otherwise it is closed.
      if (std::string(name) != "cube surface, corners included") {
        CHECK(s.watertight);
        CHECK(s.genus == 0.0);
      }
    }
  }
  CHECK_THROWS_AS(enclosing_surface({}, 1.1, 0.1), AlgorithmError);
  CHECK_THROWS_AS(enclosing_surface({Vec3::Zero(), Vec3::Ones()}, 0.9, 0.1), AlgorithmError);
}

TEST_CASE("initial level set: flat data still start inside a representable slab", "[evolution][initial]") {
  std::vector<Vec3> plane;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) plane.emplace_back(-0.9 + 1.8 * i / 19.0, -0.9 + 1.8 * j / 19.0, 0.0);
  auto basis = std::make_shared<TSplineBasis>(build_octree(plane, test::test_options("distance", "eigen_cg").tmesh));
  const TSpline f = initial_level_set(basis, plane, 1.1, 0.1);
  for (const Vec3& p : plane) CHECK(f.evaluate(p) < 0.0);
  CHECK(f.evaluate(Vec3(0, 0, 0.6)) > 0.0);
}

TEST_CASE("sign guard: controls away from the zero-set rows keep their sign", "[evolution][guard]") {
  const std::vector<Vec3> points = test::sphere_data(500);
  auto basis = std::make_shared<TSplineBasis>(build_octree(points, test::test_options("distance", "eigen_cg").tmesh));
  LeastSquaresBuilder rows(*basis);
  const std::vector<Vec3> surface = {Vec3(0.8, 0, 0)};
  rows.add_value_rows(surface, {0.0}, 1.0);
  rows.add_gradient_rows({Vec3(-0.8, 0, 0)}, {Vec3::UnitX()}, {0.0}, 1.0);
  const LeastSquaresSystem s = rows.finish(1e-3);
  const std::vector<double> floors = sign_floors(*basis, 0.25);
  std::vector<double> before(basis->size(), -0.5), after(basis->size(), 0.3);  // every unknown flips sign
  const int held = guard_signs(s, s.value_rows, floors, before, after);
  ActiveBasis active;
  basis->active(surface[0], active);
  std::vector<char> at_surface(basis->size(), 0);
  for (int i : active.index) at_surface[i] = 1;
  int band_only = 0;
  for (int k = 0; k < s.unknowns; ++k) {
    const int i = s.control[k];
    if (at_surface[i]) {
      CHECK(after[i] == 0.3);  // free to cross zero: the surface moves there
    } else {
      ++band_only;
      CHECK(after[i] == Approx(-std::min(floors[i], 0.5)));  // held on its side, away from zero
    }
  }
  CHECK(band_only > 0);
  CHECK(held == band_only);
  for (int i = 0; i < basis->size(); ++i)
    if (std::find(s.control.begin(), s.control.end(), i) == s.control.end()) CHECK(after[i] == 0.3);  // not unknowns
}

TEST_CASE("hold outside: flagged positive controls stay positive, touched by the front or not", "[evolution][guard]") {
  const std::vector<double> floors{0.1, 0.1, 0.1, 0.1, 0.1};
  const std::vector<char> held{1, 1, 1, 0, 1};
  const std::vector<double> before{0.5, 0.05, 0.3, 0.5, -0.2};
  std::vector<double> after{-0.4, -0.1, 0.2, -0.4, -0.6};
  CHECK(hold_outside(held, floors, before, after) == 2);
  CHECK(after[0] == 0.1);   // pulled through zero: held at the floor
  CHECK(after[1] == 0.05);  // below the floor before: held where it was
  CHECK(after[2] == 0.2);   // moved but still above the floor: free
  CHECK(after[3] == -0.4);  // not flagged: free
  CHECK(after[4] == -0.6);  // inside before: not held
}
