// Tests of the tensor-product part of rational surface evaluation (geometry/tensor_derivs.hpp):
// the vector sums of degrees 2 and 3 (AVX2 with fused multiply-adds, or SSE2, whichever this
// process runs: a run under GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA tests the other) give
// the point and derivatives of the scalar loops of any degree to round-off, on random rational
// nets, orders 0 to 2, with a row stride wider than the element (a knot span's block of a
// NURBS net) and equal to it (a Bezier element).
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "geometry/bezier_surface.hpp"
#include "geometry/tensor_derivs.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_tensor_derivs {

using namespace iga;

TEST_CASE("tensor_derivs: the vector sums of degrees 2 and 3 are the scalar loops' to round-off",
          "[geometry][eval]") {
  std::mt19937 g(17);
  std::uniform_real_distribution<double> c(-2.0, 2.0), w(0.4, 2.5), t(0.0, 1.0);
  for (const int p : {2, 3})
    for (const int stride : {p + 1, p + 4}) {
      std::vector<Vector4d> net(static_cast<std::size_t>(stride * (p + 1)));
      for (Vector4d& q : net) {
        const double wq = w(g);
        q << wq * c(g), wq * c(g), wq * c(g), wq;
      }
      double worst = 0.0;
      for (int k = 0; k < 200; ++k) {
        BasisDerivs Bu, Bv;
        bernstein_derivs(p, t(g), 2, Bu);
        bernstein_derivs(p, t(g), 2, Bv);
        for (const int order : {0, 1, 2}) {
          const SurfaceDerivs a = detail::tensor_derivs(Bu, Bv, p, p, order, net.data(), stride);
          SurfaceDerivs b;
          if (order == 0) b = detail::eval_derivs<0, 0, 0>(Bu, Bv, p, p, net.data(), stride);
          if (order == 1) b = detail::eval_derivs<1, 0, 0>(Bu, Bv, p, p, net.data(), stride);
          if (order == 2) b = detail::eval_derivs<2, 0, 0>(Bu, Bv, p, p, net.data(), stride);
          REQUIRE(a.order == order);
          const Vector3d* da[6] = {&a.S, &a.Su, &a.Sv, &a.Suu, &a.Suv, &a.Svv};
          const Vector3d* db[6] = {&b.S, &b.Su, &b.Sv, &b.Suu, &b.Suv, &b.Svv};
          const int n = order == 0 ? 1 : order == 1 ? 3 : 6;
          for (int q = 0; q < n; ++q)
            worst = std::max(worst, (*da[q] - *db[q]).norm() / std::max(1.0, db[q]->norm()));
        }
      }
      INFO("degree " << p << ", stride " << stride << ": largest relative difference " << worst);
      CHECK(worst < 1e-13);
    }
}

}  // namespace test_tensor_derivs
