// Fields signed by the robust inside (generalized winding numbers) on raw meshes: the right sign at
// every node more than half a voxel from the surface, and no phantom surface anywhere — checked
// against brute-force distances and direct winding-number sums, not against the field's own
// machinery.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "core/fast_winding.h"
#include "core/random.h"
#include "core/shapes.h"
#include "field/distance_field.h"
#include "field/hair_region.h"
#include "test_meshes.h"

using namespace hairfit;
using hairfit::test::spec_for;

namespace {

struct SignCheck {
  int nodes = 0;           // nodes more than half a voxel from the surface that were checked
  int wrong_sign = 0;      // whose sign differs from the direct winding number's
  int band_error = 0;      // in the band, |sample| differing from the exact distance by > 1e-9 voxel
  int below_band = 0;      // beyond the band, |sample| below the band's width
  int cells = 0;           // cell centres farther than a cell's diagonal from the surface
  int phantom = 0;         // whose interpolated |value| is below min(distance, band) − one voxel
};

// Every `stride`-th node and cell centre of the field against brute force: the inside is
// direct winding number > ½ (of `inside_mesh`), the distance that to `mesh`.
SignCheck check(const Mesh& mesh, const Mesh& inside_mesh, const DistanceField& f, int stride) {
  SignCheck c;
  const FastWindingNumber winding(inside_mesh);
  const double h = f.voxel(), r = f.band_width();
  for (int k = 0; k + 1 < f.dims().z(); k += stride)
    for (int j = 0; j + 1 < f.dims().y(); j += stride)
      for (int i = 0; i + 1 < f.dims().x(); i += stride) {
        const Vec3 p = f.origin() + h * Vec3(i, j, k);
        const double distance = test::brute_distance(mesh, p);
        const double sample = f.sample(i, j, k);
        if (distance > 0.5 * h) {
          ++c.nodes;
          if ((winding.direct(p) > 0.5) != (sample < 0)) ++c.wrong_sign;
        }
        if (f.in_band(i, j, k) && std::abs(std::abs(sample) - distance) > 1e-9 * h) ++c.band_error;
        if (!f.in_band(i, j, k) && std::abs(sample) < r) ++c.below_band;
        const Vec3 centre = p + Vec3::Constant(0.5 * h);
        const double centre_distance = test::brute_distance(mesh, centre);
        if (centre_distance > std::sqrt(3.0) * h) {
          ++c.cells;
          if (std::abs(f.value(centre)) < std::min(centre_distance, r) - h) ++c.phantom;
        }
      }
  return c;
}

// The mesh's own inside, decided as the direct sum decides it wherever an estimate does not
// (estimates of boxes of nodes included).
RobustInside exact_inside(const Mesh& mesh, const FastWindingNumber& winding) { return {{winding_soup(mesh, winding)}}; }

SignCheck check_robust(const Mesh& mesh, double voxel, double band, int stride) {
  const FastWindingNumber winding(mesh);
  const RobustInside inside = exact_inside(mesh, winding);
  const DistanceField f = make_distance_field(mesh, spec_for(voxel, band, 0.6), 2, inside);
  return check(mesh, mesh, f, stride);
}

void require_clean(const SignCheck& c, int min_nodes) {
  CHECK(c.nodes >= min_nodes);
  CHECK(c.wrong_sign == 0);
  CHECK(c.band_error == 0);
  CHECK(c.below_band == 0);
  CHECK(c.cells >= min_nodes / 2);
  CHECK(c.phantom == 0);
}

// Two parallel open squares `gap` apart, facing +z, each of n×n quads.
Mesh two_sheets(double half, double gap, int n) {
  Mesh m;
  for (int sheet = 0; sheet < 2; ++sheet) {
    const int base = static_cast<int>(m.positions.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        m.positions.push_back(Vec3(-half + 2 * half * i / n, -half + 2 * half * j / n, sheet * gap));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = base + i + (n + 1) * j, b = a + 1, c = a + n + 1, d = c + 1;
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({a, d, c});
      }
  }
  return m;
}


// `m` with the vertices of the triangles below the plane normal·x = cut duplicated where triangles
// above it use them: a closed shell whose seam is not welded (its w is still 0 or 1 off the seam).
Mesh unwelded(Mesh m, const Vec3& normal, double cut) {
  const int nv = int(m.positions.size());
  std::vector<char> upper(m.triangles.size()), used_above(nv, 0);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Vec3i f = m.triangles[t];
    upper[t] = (m.positions[f[0]] + m.positions[f[1]] + m.positions[f[2]]).dot(normal) / 3 > cut;
    if (upper[t])
      for (int k = 0; k < 3; ++k) used_above[f[k]] = 1;
  }
  std::vector<int> copy(nv, -1);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    if (upper[t]) continue;
    for (int k = 0; k < 3; ++k) {
      int& v = m.triangles[t][k];
      if (!used_above[v]) continue;
      if (copy[v] < 0) copy[v] = int(m.positions.size()), m.positions.push_back(m.positions[v]);
      v = copy[v];
    }
  }
  return m;
}

// The parts as one soup, not merged.
Mesh join(const std::vector<Mesh>& parts) {
  Mesh m;
  for (const Mesh& p : parts) {
    const int base = int(m.positions.size());
    m.positions.insert(m.positions.end(), p.positions.begin(), p.positions.end());
    for (Vec3i t : p.triangles) m.triangles.push_back(t + Vec3i::Constant(base));
  }
  return m;
}

struct ExactCheck {
  int band = 0, band_wrong = 0;  // band voxels off the surface, and those whose sign is not w > ½'s
  int far = 0, far_wrong = 0;    // the same beyond the band
};

// Every node of the field of `mesh` signed as the pipeline signs it (winding_soup over a tree at
// β = HairRegion::kFirstBeta) against the direct winding number, except nodes within 1e-9 voxel of
// the surface, where w is undefined (a node exactly on a face reads ±0).
ExactCheck exact_check(const Mesh& mesh, double voxel, double band) {
  const FastWindingNumber winding(mesh, HairRegion::kFirstBeta), exact(mesh);
  const DistanceField f = make_distance_field(mesh, spec_for(voxel, band, 2 * voxel), 2, RobustInside{{winding_soup(mesh, winding)}});
  ExactCheck c;
  for (int k = 0; k < f.dims().z(); ++k)
    for (int j = 0; j < f.dims().y(); ++j)
      for (int i = 0; i < f.dims().x(); ++i) {
        const double s = f.sample(i, j, k);
        if (std::abs(s) < 1e-9 * voxel) continue;
        const bool wrong = (exact.direct(f.origin() + voxel * Vec3(i, j, k)) > 0.5) != (s < 0);
        if (f.in_band(i, j, k)) ++c.band, c.band_wrong += wrong;
        else ++c.far, c.far_wrong += wrong;
      }
  return c;
}

// A crumpled soup of kind 0 (a sphere with an unwelded seam), 1 (three overlapping spheres) or 2 (a
// cube with an unwelded seam), rotated, every vertex then moved by up to 1 along each axis: closed
// but self-intersecting, so w is any integer off the surface.
Mesh crumpled(int kind, int level, Random& rng) {
  auto around = [&] { return Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)); };
  Mesh m;
  if (kind == 0) m = unwelded(test::icosphere(level, 1.0), around(), rng.uniform(-0.5, 0.5));
  if (kind == 1) m = join({test::icosphere(level, 1.0), test::icosphere(level, rng.uniform(0.4, 0.9), around()),
                            test::icosphere(2, rng.uniform(0.4, 0.9), around())});
  if (kind == 2) m = unwelded(test::cube(0.7), around(), rng.uniform(-0.2, 0.2));
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(rng.uniform(0, 3), around().normalized()).toRotationMatrix();
  for (Vec3& p : m.positions) p = rotation * p + around();
  return m;
}

}  // namespace

TEST_CASE("robust sign: an open cap has its winding number's inside and no phantom surface") {
  const Mesh cap = test::open_cap(3, 1.0, 0.3);
  require_clean(check_robust(cap, 0.05, 2, 2), 5000);
}

TEST_CASE("robust sign: a sphere with holes, duplicates and a flipped patch") {
  const Mesh mesh = test::messy_sphere(3, 1.0);
  require_clean(check_robust(mesh, 0.05, 2, 2), 5000);
}

TEST_CASE("robust sign: two sheets closer together than the coarse spacing") {
  // Coarse spacing floor(2·band) = 4 voxels = 0.2; the sheets are 0.12 apart, so coarse cells
  // straddle both and their interpolation once crossed zero between and beyond them.
  const Mesh sheets = two_sheets(1.0, 0.12, 16);
  require_clean(check_robust(sheets, 0.05, 2, 2), 5000);
}

TEST_CASE("robust sign: a thin closed part, thinner than the band, beside a thick one") {
  // A sphere and a flat box 0.06 thick (1.2 voxels) beside it: the box's inside is all band.
  Mesh mesh = test::icosphere(3, 0.6);
  Mesh slab = test::cube(1.0);
  for (Vec3& p : slab.positions) p = Vec3(0.5 * p.x() + 1.2, 0.5 * p.y(), 0.03 * p.z());
  const int base = static_cast<int>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), slab.positions.begin(), slab.positions.end());
  for (Vec3i t : slab.triangles) mesh.triangles.push_back(t + Vec3i::Constant(base));
  require_clean(check_robust(mesh, 0.05, 2, 2), 5000);
}

TEST_CASE("robust sign: closed meshes read as the pseudo-normals read them") {
  const Mesh sphere = test::icosphere(3, 1.0);
  const FastWindingNumber winding(sphere);
  const RobustInside inside = exact_inside(sphere, winding);
  const DistanceField robust = make_distance_field(sphere, spec_for(0.05, 2, 0.6), 2, inside);
  const DistanceField plain = make_distance_field(sphere, spec_for(0.05, 2, 0.6), 2);
  int differ = 0, far = 0;
  for (int k = 0; k < robust.dims().z(); ++k)
    for (int j = 0; j < robust.dims().y(); ++j)
      for (int i = 0; i < robust.dims().x(); ++i) {
        if (std::abs(plain.sample(i, j, k)) <= 0.5 * robust.voxel()) continue;
        far += !robust.in_band(i, j, k);
        differ += (robust.sample(i, j, k) < 0) != (plain.sample(i, j, k) < 0);
      }
  CHECK(far > 10000);
  CHECK(differ == 0);
}

TEST_CASE("robust sign: the same field for any thread count") {
  const Mesh cap = test::open_cap(3, 1.0, 0.3);
  const FastWindingNumber winding(cap);
  const RobustInside inside = exact_inside(cap, winding);
  const DistanceField one = make_distance_field(cap, spec_for(0.05, 2, 0.6), 1, inside);
  const DistanceField three = make_distance_field(cap, spec_for(0.05, 2, 0.6), 3, inside);
  int differ = 0;
  for (int k = 0; k < one.dims().z(); ++k)
    for (int j = 0; j < one.dims().y(); ++j)
      for (int i = 0; i < one.dims().x(); ++i) differ += one.sample(i, j, k) != three.sample(i, j, k);
  CHECK(differ == 0);
}

// The cases, signed as the pipeline signs them: 100 % agreement with w > ½.
TEST_CASE("robust sign: a sphere whose seam is not welded, every node as the direct winding number says") {
  const Mesh sphere = unwelded(test::icosphere(3, 1.0), Vec3(0.3, 0, 1), 0.1);
  REQUIRE(analyse_topology(sphere).boundary_loops.size() == 2);  // the seam, once per side
  for (double band : {1.0, 2.0}) {
    const ExactCheck c = exact_check(sphere, 0.083, band);
    CHECK(c.band > 2000);
    CHECK(c.band_wrong == 0);
    CHECK(c.far_wrong == 0);
  }
}

TEST_CASE("robust sign: three overlapping spheres, not merged, every node as the direct winding number says") {
  const Mesh three = join({test::icosphere(3, 1.0), test::icosphere(3, 0.8, Vec3(0.9, 0.2, 0.1)),
                           test::icosphere(3, 0.7, Vec3(0.3, -0.8, 0.4))});
  const ExactCheck c = exact_check(three, 0.083, 2);
  CHECK(c.band > 5000);
  CHECK(c.band_wrong == 0);
  CHECK(c.far_wrong == 0);
}

TEST_CASE("robust sign: two cubes sharing an edge, every node as the direct winding number says") {
  // Unit cubes meeting along one edge (not merged), turned off the grid's axes.
  Mesh a = test::cube(0.5), b = test::cube(0.5);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (Vec3& p : a.positions) p = rotation * (p + Vec3(0.013, 0.021, 0.017));
  for (Vec3& p : b.positions) p = rotation * (p + Vec3(1.013, 1.021, 0.017));
  const ExactCheck c = exact_check(join({a, b}), 0.061, 2);
  CHECK(c.band > 5000);
  CHECK(c.band_wrong == 0);
  CHECK(c.far_wrong == 0);
}

TEST_CASE("robust sign: closed parts without rims (a cavity, a doubled part), every node as the direct winding number says") {
  // No rims: far samples take w from one estimate and the jumps, row by row. w is 0 in the
  // cavity (a sphere turned inward), 1 in the shell, 2 inside the doubled sphere.
  Mesh cavity = test::icosphere(3, 0.45, Vec3(0.05, 0.02, -0.03));
  for (Vec3i& t : cavity.triangles) std::swap(t[1], t[2]);
  const Mesh doubled = test::icosphere(2, 0.35, Vec3(1.3, 0.1, 0.2));
  const Mesh m = join({test::icosphere(3, 1.0), cavity, doubled, doubled});
  const ExactCheck c = exact_check(m, 0.071, 2);
  CHECK(c.far > 5000);
  CHECK(c.band_wrong == 0);
  CHECK(c.far_wrong == 0);
}

TEST_CASE("robust sign: a crumpled soup's nodes right next to its surface (within the lattice's snapping)") {
  // Trial 34 of the sweep below: three crumpled spheres at voxel 0.0905 and band 3, where a node
  // 1e-6 voxel from the surface took the sign its reference and the snapped soup's jumps gave it.
  Random rng(50, RandomStage::test, 34);
  const Mesh m = crumpled(1, 2, rng);
  const double voxel = rng.uniform(0.06, 0.2);
  const ExactCheck c = exact_check(m, voxel, 3);
  CHECK(c.band > 40000);
  CHECK(c.band_wrong == 0);
}

TEST_CASE("robust sign: crumpled cubes' samples beyond the band") {
  // Trials 53 and 86 of the sweep below (voxel 0.094, band 3; voxel 0.081, band 2), where the
  // coarse cells' agreement and the flood from the band gave 41 and 17 far samples the wrong sign.
  for (int trial : {53, 86}) {
    Random rng(50, RandomStage::test, trial);
    const Mesh m = crumpled(2, 1, rng);
    const double voxel = rng.uniform(0.06, 0.2), band = 1 + trial / 3 % 3;
    const ExactCheck c = exact_check(m, voxel, band);
    CHECK(c.far > 50000);
    CHECK(c.band_wrong == 0);
    CHECK(c.far_wrong == 0);
  }
}

TEST_CASE("robust sign: an open hull's region with the reversed scalp inside it, beyond the band too") {
  // The soup holds the scalp, which is not the field's mesh: far samples lie on both sides of it,
  // and H jumps between them. (A search that took no jumps between far samples passes this case
  // too; the grooved fixture's relief test, tests/pipeline, is what showed it wrong.)
  const Mesh hull = test::open_cap(3, 1.0, 0.3), scalp = spherical_cap(0.7, 6, 16, 0.6);
  const HairRegion region(hull, scalp, false, 2);
  const FastWindingNumber hull_direct(hull), scalp_direct(scalp);
  const double voxel = 0.07;
  const DistanceField f = make_distance_field(hull, spec_for(voxel, 1, 0.3), 2, RobustInside{{region.soup(hull, scalp)}});
  int far = 0, wrong = 0;
  for (int k = 0; k < f.dims().z(); ++k)
    for (int j = 0; j < f.dims().y(); ++j)
      for (int i = 0; i < f.dims().x(); ++i) {
        const double s = f.sample(i, j, k);
        if (std::abs(s) < 1e-9 * voxel) continue;
        const Vec3 p = f.origin() + voxel * Vec3(i, j, k);
        far += !f.in_band(i, j, k);
        wrong += (hull_direct.direct(p) - scalp_direct.direct(p) > 0.5) != (s < 0);
      }
  CHECK(far > 10000);
  CHECK(wrong == 0);
}

// The sweep the fixed cases come from (skipped: some minutes).
TEST_CASE("robust sign: crumpled soups sweep" * doctest::skip(true)) {
  for (int trial = 0; trial < 90; ++trial) {
    Random rng(50, RandomStage::test, trial);
    const int kind = trial % 3;
    const Mesh m = crumpled(kind, 1 + trial % 3, rng);
    const double voxel = rng.uniform(0.06, 0.2), band = 1 + trial / 3 % 3;
    const ExactCheck c = exact_check(m, voxel, band);
    MESSAGE("trial " << trial << " kind " << kind << " voxel " << voxel << " band " << band << " tris " << m.triangles.size() << ": band " << c.band_wrong << "/" << c.band << " far " << c.far_wrong << "/" << c.far);
  }
}
