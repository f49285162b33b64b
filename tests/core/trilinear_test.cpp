// Both forms of the trilinear interpolation (core/trilinear.h) against exact answers: a trilinear
// polynomial is reproduced with its exact gradient, and the two forms agree to rounding.
#include <doctest/doctest.h>

#include <cmath>

#include "core/random.h"
#include "core/trilinear.h"

using namespace hairfit;

namespace {

// p(x, y, z) = a + bx + cy + dz + exy + fyz + gzx + hxyz, which trilinear interpolation reproduces.
struct Polynomial {
  double k[8];
  double at(double x, double y, double z) const {
    return k[0] + k[1] * x + k[2] * y + k[3] * z + k[4] * x * y + k[5] * y * z + k[6] * z * x + k[7] * x * y * z;
  }
  Vec3 gradient(double x, double y, double z) const {
    return Vec3(k[1] + k[4] * y + k[6] * z + k[7] * y * z, k[2] + k[4] * x + k[5] * z + k[7] * x * z,
                k[3] + k[5] * y + k[6] * x + k[7] * x * y);
  }
};

}  // namespace

TEST_CASE("trilinear interpolation reproduces trilinear polynomials and their gradients in both forms") {
  Random random(17, RandomStage::roots, 0);
  for (int trial = 0; trial < 200; ++trial) {
    Polynomial p;
    for (double& k : p.k) k = 4.0 * random.uniform() - 2.0;
    double corners[8];
    for (int c = 0; c < 8; ++c) corners[c] = p.at(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    const double f[3] = {random.uniform(), random.uniform(), random.uniform()};
    const double exact = p.at(f[0], f[1], f[2]);
    const Vec3 exact_gradient = p.gradient(f[0], f[1], f[2]);

    double value = 0.0, value_only = 0.0;
    Vec3 gradient;
    trilinear<true>(corners, f, value, &gradient);
    trilinear<false>(corners, f, value_only, nullptr);
    CHECK(value == value_only);  // the same expression with or without the gradient
    CHECK(std::abs(value - exact) < 1e-14);
    CHECK((gradient - exact_gradient).norm() < 1e-13);

    const TrilinearWeights w = trilinear_weights(Vec3(f[0], f[1], f[2]));
    double sum = 0.0, weight_sum = 0.0;
    Vec3 weighted_gradient = Vec3::Zero(), weight_gradient_sum = Vec3::Zero();
    for (int c = 0; c < 8; ++c) {
      sum += w.w[c] * corners[c];
      weight_sum += w.w[c];
      weighted_gradient += w.dw[c] * corners[c];
      weight_gradient_sum += w.dw[c];
    }
    CHECK(std::abs(weight_sum - 1.0) < 1e-15);
    CHECK(weight_gradient_sum.norm() < 1e-15);
    CHECK(std::abs(sum - exact) < 1e-14);
    CHECK((weighted_gradient - exact_gradient).norm() < 1e-13);
  }
}

TEST_CASE("trilinear interpolation takes the corner values at the corners") {
  const double corners[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  for (int c = 0; c < 8; ++c) {
    const double f[3] = {double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)};
    double value = 0.0;
    trilinear<false>(corners, f, value, nullptr);
    CHECK(value == corners[c]);
    CHECK(trilinear_weights(Vec3(f[0], f[1], f[2])).w[c] == 1.0);
  }
}
