// Distance fields against brute-force exact distances, winding numbers and finite differences.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/random.h"
#include "core/triangle_closest.h"
#include "field/distance_field.h"
#include "field/field_nrrd.h"
#include "test_meshes.h"

using namespace hairfit;
using hairfit::test::spec_for;

namespace {

struct BandCheck {
  double max_error = 0;     // cm, |sample| vs brute force over band voxels
  int band_voxels = 0;
  int missing = 0;          // voxels within r by brute force but not in the band
  int spurious = 0;         // voxels in the band but farther than r
};

// Every `stride`-th voxel (and all band voxels among them) against the brute-force distance.
BandCheck check_band(const Mesh& mesh, const DistanceField& f, int stride) {
  BandCheck c;
  const double r = f.band_width();
  for (int k = 0; k < f.dims().z(); k += stride)
    for (int j = 0; j < f.dims().y(); j += stride)
      for (int i = 0; i < f.dims().x(); i += stride) {
        const Vec3 p = f.origin() + f.voxel() * Vec3(i, j, k);
        const double exact = test::brute_distance(mesh, p);
        if (f.in_band(i, j, k)) {
          ++c.band_voxels;
          c.max_error = std::max(c.max_error, std::abs(std::abs(f.sample(i, j, k)) - exact));
          if (exact > r * (1 + 1e-9)) ++c.spurious;
        } else if (exact < r * (1 - 1e-9)) {
          ++c.missing;
        }
      }
  return c;
}

// Signs of samples more than half a voxel from a closed mesh against its winding number.
int wrong_signs(const Mesh& mesh, const DistanceField& f, int stride, bool band_only) {
  int wrong = 0;
  for (int k = 0; k < f.dims().z(); k += stride)
    for (int j = 0; j < f.dims().y(); j += stride)
      for (int i = 0; i < f.dims().x(); i += stride) {
        if (band_only && !f.in_band(i, j, k)) continue;
        const Vec3 p = f.origin() + f.voxel() * Vec3(i, j, k);
        if (test::brute_distance(mesh, p) <= 0.5 * f.voxel()) continue;
        const bool inside = winding_number(mesh, p) > 0.5;
        if (inside != (f.sample(i, j, k) < 0)) ++wrong;
      }
  return wrong;
}

}  // namespace

TEST_CASE("test meshes are oriented outward") {
  CHECK(winding_number(test::icosphere(2, 1.0), Vec3::Zero()) == doctest::Approx(1.0));
  CHECK(winding_number(test::cube(1.0), Vec3(0.1, 0.2, 0.3)) == doctest::Approx(1.0));
}

TEST_CASE("sphere: exact in the band, every band voxel found, signs right") {
  const Mesh mesh = test::icosphere(2, 1.0);
  const DistanceField f = make_distance_field(mesh, spec_for(0.07, 3, 0.4), 2);
  const BandCheck c = check_band(mesh, f, 1);
  CHECK(c.band_voxels > 1000);
  CHECK(c.band_voxels == f.band_voxels());
  CHECK(c.max_error <= 1e-6 * f.voxel());
  CHECK(c.missing == 0);
  CHECK(c.spurious == 0);
  CHECK(wrong_signs(mesh, f, 1, true) == 0);
  CHECK(wrong_signs(mesh, f, 3, false) == 0);  // beyond the band too
}

TEST_CASE("cube: exact at edges and corners, signs right at convex corners") {
  const Mesh mesh = test::cube(0.5);
  const DistanceField f = make_distance_field(mesh, spec_for(0.05, 4, 0.3), 2);
  const BandCheck c = check_band(mesh, f, 1);
  CHECK(c.max_error <= 1e-6 * f.voxel());
  CHECK(c.missing == 0);
  CHECK(c.spurious == 0);
  CHECK(wrong_signs(mesh, f, 1, false) == 0);
  // Outside a corner the distance is to the vertex.
  const Vec3 corner(0.5, 0.5, 0.5);
  const Vec3 p = corner + Vec3(0.1, 0.1, 0.1);
  CHECK(f.value(p) == doctest::Approx((p - corner).norm()).epsilon(0.02));
}

TEST_CASE("concave corners: a box with a notch keeps the signs right") {
  // The cube turned inside out: every edge and corner is concave as seen from the front side.
  Mesh mesh = test::cube(0.5);
  for (Vec3i& t : mesh.triangles) std::swap(t[1], t[2]);  // inward: every corner is concave
  const DistanceField f = make_distance_field(mesh, spec_for(0.05, 4, 0.3), 1);
  int wrong = 0;
  for (int k = 0; k < f.dims().z(); ++k)
    for (int j = 0; j < f.dims().y(); ++j)
      for (int i = 0; i < f.dims().x(); ++i) {
        if (!f.in_band(i, j, k)) continue;
        const Vec3 p = f.origin() + f.voxel() * Vec3(i, j, k);
        if (test::brute_distance(mesh, p) <= 0.5 * f.voxel()) continue;
        const bool inside_cube = p.cwiseAbs().maxCoeff() < 0.5;
        if (inside_cube != (f.sample(i, j, k) > 0)) ++wrong;  // inside the cube is now "in front"
      }
  CHECK(wrong == 0);
}

TEST_CASE("open cap: exact distances, sign by the side of the sheet") {
  const Mesh mesh = test::open_cap(2, 1.0, 0.4);
  const DistanceField f = make_distance_field(mesh, spec_for(0.06, 3, 0.3), 2);
  const BandCheck c = check_band(mesh, f, 1);
  CHECK(c.band_voxels > 500);
  CHECK(c.max_error <= 1e-6 * f.voxel());
  CHECK(c.missing == 0);
  CHECK(c.spurious == 0);
  // Straight above and below the middle of the cap the side is unambiguous.
  CHECK(f.value(Vec3(0, 0, 1.1)) > 0);
  CHECK(f.value(Vec3(0, 0, 0.9)) < 0);
}

TEST_CASE("raw mesh with a hole, duplicates, zero-area triangles and a flipped patch: exact distances") {
  const Mesh mesh = test::messy_sphere(2, 1.0);
  const DistanceField f = make_distance_field(mesh, spec_for(0.07, 3, 0.4), 2);
  const BandCheck c = check_band(mesh, f, 1);
  CHECK(c.band_voxels > 1000);
  CHECK(c.max_error <= 1e-6 * f.voxel());
  CHECK(c.missing == 0);
  CHECK(c.spurious == 0);
  // Away from the hole (x > 0.8) and the flipped patch (y > 0.75) the sign is still right,
  // including on the patch whose vertices were duplicated (welded before the pseudo-normals).
  int wrong = 0, checked = 0;
  for (int k = 0; k < f.dims().z(); ++k)
    for (int j = 0; j < f.dims().y(); ++j)
      for (int i = 0; i < f.dims().x(); ++i) {
        if (!f.in_band(i, j, k)) continue;
        const Vec3 p = f.origin() + f.voxel() * Vec3(i, j, k);
        const Vec3 dir = p.normalized();
        if (dir.x() > 0.5 || dir.y() > 0.4 || std::abs(p.norm() - 1) < 0.1) continue;
        ++checked;
        if ((p.norm() < 1) != (f.sample(i, j, k) < 0)) ++wrong;
      }
  CHECK(checked > 500);
  CHECK(wrong == 0);
}

TEST_CASE("wide bands around tilted sheets, flat and nearly flat edges and slivers: no band sample missed") {
  // The band scan visits only the rows of each face's and edge's region that its needle bounds
  // allow. Here faces are much smaller than the band is wide and tilted against the grid, edges
  // are exactly flat, flat to within 1e-9 cm, and folded sharply, and slivers have angles down to
  // 1e-7 rad: every sample within the band must still be found, with its exact distance.
  Random random(7, RandomStage::roots, 0);
  Mesh sheet;
  const Vec3 u = Vec3(1, 0.3, -0.2).normalized(), v = u.cross(Vec3(0.2, 1, 0.5)).normalized(), n = u.cross(v);
  const int cells = 9;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      const double lift = i > cells / 2 ? 1e-9 * random.uniform(-1, 1) : 0.0;  // half flat, half nearly flat
      const double fold = j == cells ? 0.3 : 0.0;                            // one sharply folded row
      sheet.positions.push_back(0.06 * (i * u + j * v) + (lift + fold) * n);
    }
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const int a = j * (cells + 1) + i, b = a + 1, c = a + cells + 1, d = c + 1;
      sheet.triangles.push_back({a, b, d});
      sheet.triangles.push_back({a, d, c});
    }
  // Slivers: a fan of needles from one point, the last ones with angles of 1e-4 … 1e-7 rad.
  const int apex = static_cast<int>(sheet.positions.size());
  sheet.positions.push_back(Vec3(0.1, -0.2, 0.3));
  for (double angle : {0.3, 1e-4, 1e-7}) {
    const int first = static_cast<int>(sheet.positions.size());
    sheet.positions.push_back(sheet.positions[apex] + 0.5 * Vec3(0.3, 1, 0.4).normalized());
    sheet.positions.push_back(sheet.positions[apex] + 0.5 * (Vec3(0.3, 1, 0.4).normalized() + angle * Vec3(0.7, 0, -0.1)));
    sheet.triangles.push_back({apex, first, first + 1});
  }
  for (double band : {3.0, 9.0}) {
    CAPTURE(band);
    const DistanceField f = make_distance_field(sheet, spec_for(0.05, band, 0.3), 2);
    const BandCheck c = check_band(sheet, f, 1);
    CHECK(c.band_voxels > 1000);
    CHECK(c.max_error <= 1e-6 * f.voxel());
    CHECK(c.missing == 0);
    CHECK(c.spurious == 0);
  }
}

TEST_CASE("carried values: a vertex value read at each band sample's closest point, as brute force reads it") {
  // A linear function of the position is reproduced exactly by the interpolation over any face or
  // edge, so the carried value at a sample is that function at its closest point. The brute force
  // finds the closest point over every triangle and reads the function there; where two triangles
  // are nearly as close with different closest points (a medial surface), either answer is right.
  const Mesh mesh = test::messy_sphere(2, 1.0);
  const Vec3 slope(0.3, -1.7, 0.9);
  std::vector<double> values;
  for (const Vec3& p : mesh.positions) values.push_back(slope.dot(p) + 2.0);
  const CarriedField c = make_distance_field_carrying(mesh, values, spec_for(0.07, 3, 0.4), 2);
  CHECK(c.carried.size() == static_cast<std::size_t>(c.field.dims().prod()));
  int checked = 0, wrong = 0, ties = 0, beyond = 0;
  for (int k = 0; k < c.field.dims().z(); ++k)
    for (int j = 0; j < c.field.dims().y(); ++j)
      for (int i = 0; i < c.field.dims().x(); ++i) {
        const double carried = c.carried[i + c.field.dims().x() * (j + c.field.dims().y() * std::int64_t(k))];
        if (!c.field.in_band(i, j, k)) {
          beyond += !std::isnan(carried);
          continue;
        }
        const Vec3 p = c.field.origin() + c.field.voxel() * Vec3(i, j, k);
        double best = INFINITY, second = INFINITY;
        Vec3 best_point = Vec3::Zero();
        for (const Vec3i& f : mesh.triangles) {
          const Vec3 &a = mesh.positions[f[0]], &b = mesh.positions[f[1]], &q = mesh.positions[f[2]];
          const Vec3 w = closest_barycentric(p, a, b, q);
          const Vec3 x = w[0] * a + w[1] * b + w[2] * q;
          const double d = (x - p).norm();
          if (d < best) {
            if ((x - best_point).norm() > 1e-9) second = best;
            best = d, best_point = x;
          } else if (d < second && (x - best_point).norm() > 1e-9) {
            second = d;
          }
        }
        if (second - best < 1e-9) {
          ++ties;
          continue;
        }
        ++checked;
        wrong += !(std::abs(carried - (slope.dot(best_point) + 2.0)) <= 1e-9);
      }
  CHECK(checked > 1000);
  CHECK(wrong == 0);
  CHECK(beyond == 0);  // NaN beyond the band
  CHECK(ties < checked / 20);
  // The field itself is make_distance_field's, bit for bit.
  const DistanceField plain = make_distance_field(mesh, spec_for(0.07, 3, 0.4), 2);
  int differ = 0;
  for (int k = 0; k < plain.dims().z(); ++k)
    for (int j = 0; j < plain.dims().y(); ++j)
      for (int i = 0; i < plain.dims().x(); ++i) differ += plain.sample(i, j, k) != c.field.sample(i, j, k);
  CHECK(differ == 0);
  CHECK_THROWS_AS(make_distance_field_carrying(mesh, std::vector<double>(3, 0.0), spec_for(0.07, 3, 0.4), 2),
                  std::invalid_argument);
}

TEST_CASE("gradient equals central differences of the interpolant") {
  const Mesh mesh = test::icosphere(2, 1.0);
  const DistanceField f = make_distance_field(mesh, spec_for(0.1, 2, 0.5), 1);
  const double h = f.voxel();
  uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) / double(1ULL << 53);
  };
  int checked = 0;
  for (int n = 0; n < 400; ++n) {
    // A point well inside a cell, so ±1e-5·h stays in it (the interpolant is smooth there).
    Vec3 cell(std::floor(next() * (f.dims().x() - 1)), std::floor(next() * (f.dims().y() - 1)),
              std::floor(next() * (f.dims().z() - 1)));
    const Vec3 frac(0.1 + 0.8 * next(), 0.1 + 0.8 * next(), 0.1 + 0.8 * next());
    const Vec3 p = f.origin() + h * (cell + frac);
    const FieldValueGradient vg = f.value_and_gradient(p);
    CHECK(vg.value == f.value(p));
    const double step = 1e-5 * h;
    for (int d = 0; d < 3; ++d) {
      const Vec3 e = step * Vec3::Unit(d);
      const double fd = (f.value(p + e) - f.value(p - e)) / (2 * step);
      CHECK(vg.gradient[d] == doctest::Approx(fd).epsilon(1e-6).scale(1.0));
    }
    ++checked;
  }
  CHECK(checked == 400);
}

// Trilinear interpolation of 8 corner values (x fastest) at fractions t, and its gradient (per voxel).
FieldValueGradient trilinear_reference(const double c[8], const double t[3], double voxel) {
  const double x0 = 1 - t[0], y0 = 1 - t[1], z0 = 1 - t[2];
  const double c00 = c[0] * x0 + c[1] * t[0], c10 = c[2] * x0 + c[3] * t[0];
  const double c01 = c[4] * x0 + c[5] * t[0], c11 = c[6] * x0 + c[7] * t[0];
  const double c0 = c00 * y0 + c10 * t[1], c1 = c01 * y0 + c11 * t[1];
  FieldValueGradient out;
  out.value = c0 * z0 + c1 * t[2];
  out.gradient.z() = c1 - c0;
  out.gradient.y() = (c10 - c00) * z0 + (c11 - c01) * t[2];
  out.gradient.x() = ((c[1] - c[0]) * y0 + (c[3] - c[2]) * t[1]) * z0 + ((c[5] - c[4]) * y0 + (c[7] - c[6]) * t[1]) * t[2];
  out.gradient /= voxel;
  return out;
}

// Whether the corners differ in sign although no surface can pass between any two of opposite
// sign (|d_a| + |d_b| > |a − b|): a seam of the inside, not a surface.
bool seam_reference(const double c[8], double voxel) {
  bool positive = false, negative = false, surface_between = false;
  for (int a = 0; a < 8; ++a) {
    positive = positive || c[a] > 0;
    negative = negative || c[a] < 0;
    for (int b = 0; b < 8; ++b) {
      if (!(c[a] > 0 && c[b] < 0)) continue;
      const Vec3 offset((a & 1) - (b & 1), ((a >> 1) & 1) - ((b >> 1) & 1), (a >> 2) - (b >> 2));
      if (c[a] - c[b] <= voxel * offset.norm() * (1 + 1e-9)) surface_between = true;
    }
  }
  return positive && negative && !surface_between;
}

// What a lookup must return, written from the public samples alone: the trilinear interpolant of
// the 8 corner samples of the point's cell (x fastest), gradient by the chain rule; in a seam cell
// the interpolated magnitudes with the interpolant's sign; beyond the grid the value at the
// clamped point plus the distance to the box.
FieldValueGradient reference_lookup(const DistanceField& f, const Vec3& p) {
  const Vec3 upper = f.origin() + f.voxel() * (f.dims() - Vec3i::Ones()).cast<double>();
  const Vec3 q = p.cwiseMax(f.origin()).cwiseMin(upper);
  int cell[3];
  double t[3];
  for (int d = 0; d < 3; ++d) {
    const double u = std::clamp((q[d] - f.origin()[d]) / f.voxel(), 0.0, double(f.dims()[d] - 1));
    cell[d] = std::min(int(u), f.dims()[d] - 2);
    t[d] = u - cell[d];
  }
  double c[8], magnitudes[8];
  for (int n = 0; n < 8; ++n) c[n] = f.sample(cell[0] + (n & 1), cell[1] + ((n >> 1) & 1), cell[2] + (n >> 2));
  for (int n = 0; n < 8; ++n) magnitudes[n] = std::abs(c[n]);
  FieldValueGradient out = trilinear_reference(c, t, f.voxel());
  if (seam_reference(c, f.voxel())) {
    const double sign = out.value < 0 ? -1.0 : 1.0;
    out = trilinear_reference(magnitudes, t, f.voxel());
    out.value *= sign;
    out.gradient *= sign;
  }
  const Vec3 outside = p - q;
  const double distance = outside.norm();
  if (distance > 0) {
    const double sign = out.value < 0 ? -1.0 : 1.0;
    out.value += sign * distance;
    for (int d = 0; d < 3; ++d)
      if (outside[d] != 0) out.gradient[d] = sign * outside[d] / distance;
  }
  return out;
}

TEST_CASE("lookups: value() is value_and_gradient()'s value bit for bit, both the interpolant of the samples; side() its sign") {
  const Mesh mesh = test::messy_sphere(2, 1.0);
  const DistanceField f = make_distance_field(mesh, spec_for(0.05, 2, 1.5), 2);
  const Vec3 upper = f.origin() + f.voxel() * (f.dims() - Vec3i::Ones()).cast<double>();
  uint64_t state = 987654321;
  auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) / double(1ULL << 53);
  };
  int exact = 0, all_far = 0, decided = 0;
  for (int n = 0; n < 20000; ++n) {
    // Points near the sphere, over the grid and up to a quarter of its size beyond it; every 10th
    // on a grid node or face (fractions 0 and the clamps' upper edge), every 10th just below one
    // (where u / coarse factor may round up to the next coarse cell).
    Vec3 p;
    for (int d = 0; d < 3; ++d) {
      const double span = upper[d] - f.origin()[d];
      p[d] = n % 2 ? f.origin()[d] - 0.25 * span + 1.5 * span * next() : 2.4 * next() - 1.2;  // half near the sphere
      if (n % 10 == 0) p[d] = f.origin()[d] + f.voxel() * std::floor(next() * f.dims()[d]);
      if (n % 10 == 5) p[d] = f.origin()[d] + f.voxel() * (std::floor(next() * f.dims()[d]) - 1e-13);  // just below
    }
    const FieldValueGradient fast = f.value_and_gradient(p);
    const double value = f.value(p);
    REQUIRE(std::memcmp(&value, &fast.value, sizeof value) == 0);
    const int side = f.side(p);
    if (side != 0) {
      CHECK(side * value > 0.0);  // strictly on that side
      ++decided;
    }
    const FieldValueGradient ref = reference_lookup(f, p);
    CHECK(std::memcmp(&ref.value, &fast.value, sizeof value) == 0);
    CHECK(ref.gradient == fast.gradient);
    const Vec3 q = p.cwiseMax(f.origin()).cwiseMin(upper);
    Vec3i cell;
    for (int d = 0; d < 3; ++d)
      cell[d] = std::min(int(std::clamp((q[d] - f.origin()[d]) / f.voxel(), 0.0, double(f.dims()[d] - 1))), f.dims()[d] - 2);
    bool any_in_band = false;
    for (int c = 0; c < 8; ++c) any_in_band = any_in_band || f.in_band(cell[0] + (c & 1), cell[1] + ((c >> 1) & 1), cell[2] + (c >> 2));
    ++(any_in_band ? exact : all_far);
  }
  CHECK(exact > 1000);
  CHECK(all_far > 1000);
  CHECK(decided > 15000);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(std::isnan(f.value(Vec3(nan, 0, 0))));
  CHECK(std::isnan(f.value_and_gradient(Vec3(0, std::numeric_limits<double>::infinity(), 0)).value));
}

TEST_CASE("sides_on_lattice: side() at every point of a lattice") {
  const Mesh mesh = test::icosphere(2, 1.0);
  const DistanceField f = make_distance_field(mesh, spec_for(0.05, 2, 0.5), 2);
  uint64_t state = 4242;
  auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) / double(1ULL << 53);
  };
  std::vector<double> axes[3];
  for (int d = 0; d < 3; ++d) {
    for (int n = 0; n < 23 + d; ++n) axes[d].push_back(-2.5 + 5.0 * next());  // inside and beyond the grid
    axes[d].push_back(f.origin()[d] + f.voxel() * 7);                         // on a node
  }
  axes[1].push_back(std::numeric_limits<double>::quiet_NaN());
  for (int threads : {1, 3}) {
    const std::vector<std::int8_t> sides = f.sides_on_lattice(axes[0], axes[1], axes[2], threads);
    REQUIRE(sides.size() == axes[0].size() * axes[1].size() * axes[2].size());
    int decided = 0, differ = 0;
    for (std::size_t k = 0; k < axes[2].size(); ++k)
      for (std::size_t j = 0; j < axes[1].size(); ++j)
        for (std::size_t i = 0; i < axes[0].size(); ++i) {
          const int expected = f.side(Vec3(axes[0][i], axes[1][j], axes[2][k]));
          differ += sides[i + axes[0].size() * (j + axes[1].size() * k)] != expected;
          decided += expected != 0;
        }
    CHECK(differ == 0);
    CHECK(decided > 10000);
  }
}

TEST_CASE("beyond the band: close to the true distance, continuous at the band's edge, pulls back") {
  const double R = 1.0;
  const Mesh mesh = test::icosphere(3, R);
  const DistanceField f = make_distance_field(mesh, spec_for(0.05, 2, 1.5), 2);
  const double h = f.voxel();
  // Neighbouring samples differ by little more than h (the distance is 1-Lipschitz; beyond the
  // band the coarse interpolation adds O(H²·curvature)), also where one is in the band and the
  // other not.
  double worst_step = 0;
  int edge_pairs = 0;
  for (int k = 0; k + 1 < f.dims().z(); ++k)
    for (int j = 0; j < f.dims().y(); ++j)
      for (int i = 0; i < f.dims().x(); ++i) {
        const double a = f.sample(i, j, k), b = f.sample(i, j, k + 1);
        worst_step = std::max(worst_step, std::abs(a - b));
        if (f.in_band(i, j, k) != f.in_band(i, j, k + 1)) ++edge_pairs;
      }
  CHECK(edge_pairs > 100);
  CHECK(worst_step <= 1.5 * h);
  // Beyond the band: close to the exact distance near the surface (the coarse nodes there are
  // exact), within a coarse cell's diagonal everywhere (near the medial axis the distance has a
  // kink the coarse grid smooths), and at coarse nodes never below the exact distance.
  const double H = 4 * h;  // coarse spacing floor(2·band) voxels
  double worst_near = 0, worst_far = 0, below = 0;
  for (int k = 0; k < f.dims().z(); k += 2)
    for (int j = 0; j < f.dims().y(); j += 2)
      for (int i = 0; i < f.dims().x(); i += 2) {
        if (f.in_band(i, j, k)) continue;
        const Vec3 p = f.origin() + h * Vec3(i, j, k);
        const double unsigned_exact = test::brute_distance(mesh, p);
        const double exact = unsigned_exact * (winding_number(mesh, p) > 0.5 ? -1 : 1);
        const double error = std::abs(f.sample(i, j, k) - exact);
        (unsigned_exact < 3 * f.band_width() ? worst_near : worst_far) =
            std::max(unsigned_exact < 3 * f.band_width() ? worst_near : worst_far, error);
        if (i % 4 == 0 && j % 4 == 0 && k % 4 == 0)
          below = std::max(below, unsigned_exact - std::abs(f.sample(i, j, k)));
      }
  CHECK(worst_near <= 0.5 * h);  // about 3H²/(8R): trilinear error on a curved field
  CHECK(worst_far <= std::sqrt(3.0) * H);
  CHECK(below <= 1e-9);
  // Along a ray from the centre the value increases through the band's edge and beyond.
  const Vec3 dir = Vec3(0.3, -0.5, 0.8).normalized();
  double previous = f.value(R * dir);
  for (double t = R + 0.01; t < R + 1.4; t += 0.01) {
    const double v = f.value(t * dir);
    CHECK(v > previous);
    CHECK(f.gradient(t * dir).dot(dir) > 0.5);
    previous = v;
  }
  // 30 cm away (far outside the grid) the field is positive and its gradient points away from
  // the surface, so descending |d| leads back.
  const Vec3 far = 30 * Vec3(1, 2, 2).normalized();
  const FieldValueGradient vg = f.value_and_gradient(far);
  CHECK(vg.value == doctest::Approx(30 - R).epsilon(0.02));
  CHECK(vg.gradient.normalized().dot(far.normalized()) > 0.9);
  // Inside, beyond the band, values are negative and deepen toward the centre.
  CHECK(f.value(Vec3(0, 0, 0)) < -(R - std::sqrt(3.0) * H));
}

TEST_CASE("the result does not depend on the number of threads") {
  const Mesh mesh = test::messy_sphere(2, 1.0);
  const DistanceField a = make_distance_field(mesh, spec_for(0.05, 3, 0.3), 1);
  const DistanceField b = make_distance_field(mesh, spec_for(0.05, 3, 0.3), 3);
  REQUIRE(a.dims() == b.dims());
  int differ = 0;
  for (int k = 0; k < a.dims().z(); ++k)
    for (int j = 0; j < a.dims().y(); ++j)
      for (int i = 0; i < a.dims().x(); ++i) differ += a.sample(i, j, k) != b.sample(i, j, k);
  CHECK(differ == 0);
}

TEST_CASE("bad meshes and specs are refused with InputError") {
  const FieldSpec spec = spec_for(0.1, 3, 0.2);
  CHECK_THROWS_AS(make_distance_field(Mesh{}, spec), InputError);
  Mesh nan = test::icosphere(1, 1.0);
  nan.positions[3].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(make_distance_field(nan, spec), InputError);
  Mesh inf = test::icosphere(1, 1.0);
  inf.positions[0].x() = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(make_distance_field(inf, spec), InputError);
  Mesh bad_index = test::icosphere(1, 1.0);
  bad_index.triangles[2][1] = 9999;
  CHECK_THROWS_AS(make_distance_field(bad_index, spec), InputError);
  Mesh flat;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.triangles = {{0, 1, 2}};
  CHECK_THROWS_AS(make_distance_field(flat, spec), InputError);
  CHECK_THROWS_AS(make_distance_field(test::cube(1), spec_for(0, 3, 0.2)), InputError);
  CHECK_THROWS_AS(make_distance_field(test::cube(1), spec_for(0.1, 0.5, 0.2)), InputError);
  CHECK_THROWS_AS(make_distance_field(test::cube(1), spec_for(0.1, 3, -1)), InputError);
}

TEST_CASE("the memory limit names the grid and a voxel size that fits") {
  FieldSpec spec = spec_for(0.001, 3, 0.1);
  spec.max_memory_gib = 0.5;
  spec.name = "volume.obj";
  std::string message;
  try {
    make_distance_field(test::cube(1.0), spec);
  } catch (const InputError& e) {
    message = e.what();
  }
  CHECK(message.find("volume.obj") != std::string::npos);
  CHECK(message.find("voxels") != std::string::npos);
  CHECK(message.find("use a voxel of at least") != std::string::npos);
  // The suggested voxel fits and a 1% smaller one does not.
  const size_t at = message.find("at least ") + 9;
  const double suggested = std::stod(message.substr(at));
  spec.voxel = suggested;
  CHECK(plan_field_grid(test::cube(1.0), spec).bytes <= 0.5 * 1073741824.0);
  spec.voxel = suggested * 0.97;
  CHECK(plan_field_grid(test::cube(1.0), spec).bytes > 0.5 * 1073741824.0);
}

TEST_CASE("field_to_nrrd: every sample in x-fastest order, the same for any thread count") {
  const DistanceField f = make_distance_field(test::icosphere(2, 1.0), spec_for(0.1, 2, 0.3), 1);
  const NrrdVolume one = field_to_nrrd(f, 1);
  REQUIRE(one.data.size() == static_cast<std::size_t>(f.dims().x()) * f.dims().y() * f.dims().z());
  const int i = f.dims().x() / 3, j = f.dims().y() / 2, k = f.dims().z() - 2;
  CHECK(one.data[i + static_cast<std::size_t>(f.dims().x()) * (j + static_cast<std::size_t>(f.dims().y()) * k)] ==
        static_cast<float>(f.sample(i, j, k)));
  for (int threads : {2, 3}) CHECK(field_to_nrrd(f, threads).data == one.data);
}

TEST_CASE("distance_lower_bound never exceeds the exact distance, and is within a voxel of it near the mesh") {
  // A sphere and a cube (edges and corners), at random points inside the grid, beyond it and far
  // beyond the band, against brute-force distances.
  for (const Mesh& mesh : {test::icosphere(2, 1.0), test::cube(0.5)}) {
    const DistanceField f = make_distance_field(mesh, spec_for(0.07, 3, 0.4), 2);
    Random r(11, RandomStage::test, 0);
    int near = 0;
    for (int k = 0; k < 4000; ++k) {
      const double reach = k % 2 ? 1.2 : 2.5;  // every other point near the mesh
      const Vec3 p(r.uniform(-reach, reach), r.uniform(-reach, reach), r.uniform(-reach, reach));
      const double exact = test::brute_distance(mesh, p), lower = f.distance_lower_bound(p);
      CHECK(lower <= exact + 1e-12);
      if (exact < f.band_width() - f.voxel()) {
        ++near;
        // The nearest node is at most √3/2 voxels away, and its sample is exact: the bound loses
        // at most twice that.
        CHECK(lower >= exact - std::sqrt(3.0) * f.voxel() - 1e-12);
      }
    }
    CHECK(near > 100);
  }
  CHECK(make_distance_field(test::icosphere(1, 1.0), spec_for(0.1, 3, 0.4), 1)
            .distance_lower_bound(Vec3(std::nan(""), 0, 0)) == -std::numeric_limits<double>::infinity());
}

TEST_CASE("from_parts rebuilds a field from its parts, the same at every point, and refuses parts that are no field") {
  const Mesh mesh = test::icosphere(2, 1.0);
  const DistanceField f = make_distance_field(mesh, spec_for(0.1, 3, 0.4), 1);
  auto parts_of = [&f] {
    DistanceFieldParts p;
    p.origin = f.origin();
    p.voxel = f.voxel();
    p.dims = f.dims();
    p.band_width = f.band_width();
    p.band_voxels = f.band_voxels();
    p.samples = f.samples();
    p.flags = f.flags();
    return p;
  };
  const DistanceField g = DistanceField::from_parts(parts_of());
  CHECK(g.dims() == f.dims());
  CHECK(g.band_voxels() == f.band_voxels());
  Random r(3, RandomStage::test, 1);
  for (int n = 0; n < 200; ++n) {
    const Vec3 p(r.uniform(-1.8, 1.8), r.uniform(-1.8, 1.8), r.uniform(-1.8, 1.8));
    CHECK(g.value(p) == f.value(p));
    CHECK(g.gradient(p) == f.gradient(p));
    CHECK(g.side(p) == f.side(p));
  }
  DistanceFieldParts short_samples = parts_of();
  short_samples.samples.pop_back();
  CHECK_THROWS_AS(DistanceField::from_parts(short_samples), std::invalid_argument);
  DistanceFieldParts short_flags = parts_of();
  short_flags.flags.pop_back();
  CHECK_THROWS_AS(DistanceField::from_parts(short_flags), std::invalid_argument);
  DistanceFieldParts no_voxel = parts_of();
  no_voxel.voxel = 0.0;
  CHECK_THROWS_AS(DistanceField::from_parts(no_voxel), std::invalid_argument);
  DistanceFieldParts negative = parts_of();
  negative.dims.x() = -1;
  CHECK_THROWS_AS(DistanceField::from_parts(negative), std::invalid_argument);
}
