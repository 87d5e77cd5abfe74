// Trimmed faces: the even-odd inside test, which rectangles of (u, v) meet the face, and the
// constructor's errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include "geometry/analytic_surfaces.hpp"
#include "geometry/trimmed_surface.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_trimmed_surface {

using namespace iga;

namespace {

// A square [-2, 2]^2 of the plane z = 0 with a round hole of radius 1 (a 256-gon).
TrimmedSurface square_with_hole() {
  TrimmedSurface::Loop outer{{-2, -2}, {2, -2}, {2, 2}, {-2, 2}};
  TrimmedSurface::Loop hole;
  for (int k = 0; k < 256; ++k) {
    const double t = 2 * std::numbers::pi * k / 256;
    hole.emplace_back(std::cos(t), std::sin(t));
  }
  return TrimmedSurface(Plane(), {outer, hole}, {}, 1e-4);
}

}  // namespace

TEST_CASE("TrimmedSurface: inside the loops by the even-odd rule", "[geometry][trimmed]") {
  const TrimmedSurface t = square_with_hole();
  CHECK(t.inside({1.5, 0.0}));
  CHECK(t.inside({-1.5, 1.5}));
  CHECK_FALSE(t.inside({0.0, 0.0}));  // in the hole
  CHECK_FALSE(t.inside({0.5, -0.5}));
  CHECK_FALSE(t.inside({2.5, 0.0}));  // beyond the outer loop
  CHECK(t.inside({2.0, 0.3}));        // on a loop: inside
  const Domain2 d = t.domain();
  CHECK(d.u.lo == -2.0);
  CHECK(d.v.hi == 2.0);
}

TEST_CASE("TrimmedSurface: a rectangle meets the face exactly when some point of it is on the face",
          "[geometry][trimmed]") {
  const TrimmedSurface t = square_with_hole();
  CHECK_FALSE(t.meets({{-0.3, 0.3}, {-0.3, 0.3}}));  // wholly in the hole
  CHECK(t.meets({{0.9, 1.1}, {-0.1, 0.1}}));         // across the hole's edge
  CHECK(t.meets({{1.2, 1.8}, {1.2, 1.8}}));          // wholly on the material, no loop crossed
  CHECK_FALSE(t.meets({{2.1, 3.0}, {-1.0, 1.0}}));   // beyond the outer loop
  CHECK(t.meets({{-5.0, 5.0}, {-5.0, 5.0}}));        // around everything
  CHECK(t.meets({{2.0, 3.0}, {0.0, 0.5}}));          // touching the outer side
  // Against sampling: a rectangle with a sample point on the face meets it; one that meets it
  // has a face point within its (slightly enlarged) rectangle.
  std::mt19937 g(7);
  std::uniform_real_distribution<double> U(-2.5, 2.5), W(0.01, 0.6);
  int met = 0, missed = 0;
  for (int k = 0; k < 2000; ++k) {
    const double u0 = U(g), v0 = U(g), w = W(g), h = W(g);
    const Domain2 r{{u0, u0 + w}, {v0, v0 + h}};
    bool sampled = false;
    const int n = 40;
    for (int j = 0; j <= n && !sampled; ++j)
      for (int i = 0; i <= n && !sampled; ++i) sampled = t.inside({u0 + w * i / n, v0 + h * j / n});
    INFO("rectangle [" << u0 << ", " << u0 + w << "] x [" << v0 << ", " << v0 + h << "]");
    if (sampled) CHECK(t.meets(r));
    if (t.meets(r) && !sampled) {
      // Only a sliver of the face inside r, thinner than the sample spacing: the rectangle
      // grown by one spacing has a sampled face point.
      bool near = false;
      for (int j = -1; j <= n + 1 && !near; ++j)
        for (int i = -1; i <= n + 1 && !near; ++i)
          near = t.inside({u0 + w * i / n, v0 + h * j / n});
      CHECK(near);
    }
    (t.meets(r) ? met : missed) += 1;
  }
  CHECK(met > 500);
  CHECK(missed > 100);
}

TEST_CASE("TrimmedSurface: bad loops are errors", "[geometry][trimmed]") {
  CHECK_THROWS_AS(TrimmedSurface(Plane(), {}, {}, 0.0), GeometryError);
  CHECK_THROWS_AS(TrimmedSurface(Plane(), {{{0, 0}, {1, 0}}}, {}, 0.0), GeometryError);
  CHECK_THROWS_AS(TrimmedSurface(Plane(), {{{0, 0}, {1, 0}, {2, 0}}}, {}, 0.0), GeometryError);
  CHECK_THROWS_AS(TrimmedSurface(Plane(), {{{0, 0}, {1, 0}, {1, 1}}}, {}, -1.0), GeometryError);
  const Plane bounded(Placement{}, {{0, 1}, {0, 1}});
  CHECK_THROWS_AS(TrimmedSurface(bounded, {{{0, 0}, {2, 0}, {2, 1}}}, {}, 0.0), GeometryError);
}

}  // namespace test_trimmed_surface
