// Reference hair from textured cards: which texture axis runs along the hair, which end is the
// root, the direction in each triangle, and the OBJ reader that keeps the file's numbering.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>

#include "core/error.h"
#include "reference/reference_cards.h"
#include "tests/support/scratch.h"

using namespace hairfit;

namespace {

// A small scalp: one triangle around the origin in the plane z = 0.
Mesh scalp_triangle() {
  Mesh m;
  m.positions = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(0, 1, 0)};
  m.triangles = {Vec3i(0, 1, 2)};
  return m;
}

// A flat card from `root` along unit `along` for `length` cm, `width` wide along unit `across`,
// in `quads` quads along its length. Texture: the across coordinate runs 0 → 1 over the width,
// the along one 1 → 0 root to tip (the root at the texture's top), plus `shear` × the along share
// added to the across coordinate; `swap` exchanges u and v.
TexturedMesh card(const Vec3& root, const Vec3& along, const Vec3& across, double length, double width, int quads,
                  bool swap = false, double shear = 0.0) {
  TexturedMesh m;
  for (int i = 0; i <= quads; ++i)
    for (int side = 0; side < 2; ++side) {
      const double s = static_cast<double>(i) / quads;
      m.mesh.positions.push_back(root + s * length * along + (side - 0.5) * width * across);
      const Vec2 uv(side + shear * s, 1.0 - s);
      m.texture_coordinates.push_back(swap ? Vec2(uv.y(), uv.x()) : uv);
    }
  for (int i = 0; i < quads; ++i) {
    const int a = 2 * i, b = 2 * i + 1, c = 2 * i + 3, d = 2 * i + 2;
    m.mesh.triangles.push_back(Vec3i(a, b, c)), m.triangle_texture.push_back(Vec3i(a, b, c));
    m.mesh.triangles.push_back(Vec3i(a, c, d)), m.triangle_texture.push_back(Vec3i(a, c, d));
  }
  return m;
}

// Cards side by side in one mesh (their texture coordinates renumbered).
TexturedMesh joined(const TexturedMesh& a, const TexturedMesh& b) {
  TexturedMesh m = a;
  const int vp = static_cast<int>(a.mesh.positions.size()), vt = static_cast<int>(a.texture_coordinates.size());
  m.mesh.positions.insert(m.mesh.positions.end(), b.mesh.positions.begin(), b.mesh.positions.end());
  m.texture_coordinates.insert(m.texture_coordinates.end(), b.texture_coordinates.begin(), b.texture_coordinates.end());
  for (const Vec3i& t : b.mesh.triangles) m.mesh.triangles.push_back(t + Vec3i::Constant(vp));
  for (const Vec3i& t : b.triangle_texture) m.triangle_texture.push_back(t + Vec3i::Constant(vt));
  return m;
}

const Vec3 kDown(0, 0, 1);  // away from the scalp triangle: cards that stand off the head

}  // namespace

TEST_CASE("a card standing off the scalp: v runs along it, the root at its top, every direction root to tip") {
  const TexturedMesh c = card(Vec3(0, 0, 0.5), kDown, Vec3::UnitX(), 20.0, 2.0, 10);
  const ReferenceHair hair = reference_from_cards(c, scalp_triangle());
  REQUIRE(hair.islands.size() == 1);
  const CardIsland& island = hair.islands[0];
  CHECK(island.used);
  CHECK(island.along == 1);
  CHECK(island.root_at_high);
  CHECK(island.sense_from_scalp);
  CHECK(island.area == doctest::Approx(40.0).epsilon(1e-14));
  CHECK(island.end_separation == doctest::Approx(18.0).epsilon(1e-12));  // the first and last 2 cm, centre to centre
  CHECK(island.across_separation < 1.5);
  CHECK(island.root_scalp_distance < island.tip_scalp_distance);
  for (const Vec3& d : hair.triangle_directions) CHECK((d - kDown).norm() < 1e-14);
  CHECK(hair.samples.points.size() == 160);  // 4 per cm²
  for (const Vec3& d : hair.samples.directions) CHECK((d - kDown).norm() < 1e-14);
  CHECK(hair.used_area == doctest::Approx(40.0).epsilon(1e-14));
  CHECK(hair.sensed_area == hair.used_area);
}

TEST_CASE("the same card textured with u along and the root at u = 0, or turned the other way, gives the same hair") {
  TexturedMesh c = card(Vec3(0, 0, 0.5), kDown, Vec3::UnitX(), 20.0, 2.0, 10, true);
  for (Vec2& uv : c.texture_coordinates) uv.x() = 1.0 - uv.x();  // the root at u = 0
  const ReferenceHair hair = reference_from_cards(c, scalp_triangle());
  CHECK(hair.islands[0].along == 0);
  CHECK(!hair.islands[0].root_at_high);
  for (const Vec3& d : hair.triangle_directions) CHECK((d - kDown).norm() < 1e-14);
  // Tip at the scalp: the card turned over, texture unchanged; the scalp still says where the root is.
  const TexturedMesh upside = card(Vec3(0, 0, 20.5), -kDown, Vec3::UnitX(), 20.0, 2.0, 10);
  for (const Vec3& d : reference_from_cards(upside, scalp_triangle()).triangle_directions)
    CHECK((d - kDown).norm() < 1e-14);
}

TEST_CASE("a sheared texture: the hair follows the iso-lines of the across coordinate, not the along gradient") {
  // u = side + 0.5·s over a 2 cm × 20 cm card: the iso-lines of u lean by 0.5·2 cm per 20 cm.
  const TexturedMesh c = card(Vec3(0, 0, 0.5), kDown, Vec3::UnitX(), 20.0, 2.0, 4, false, 0.5);
  const Vec3 expected = Vec3(-1.0, 0.0, 20.0).normalized();
  for (const Vec3& d : reference_from_cards(c, scalp_triangle()).triangle_directions)
    CHECK((d - expected).norm() < 1e-14);
}

TEST_CASE("a card lying on the head: the scalp cannot tell the root, the texture's top is taken") {
  Mesh wide_scalp;
  wide_scalp.positions = {Vec3(-30, -30, 0), Vec3(30, -30, 0), Vec3(0, 30, 0)};
  wide_scalp.triangles = {Vec3i(0, 1, 2)};
  const TexturedMesh c = card(Vec3(-10, 0, 0.5), Vec3::UnitX(), Vec3::UnitY(), 20.0, 2.0, 10);
  const ReferenceHair hair = reference_from_cards(c, wide_scalp);
  CHECK(!hair.islands[0].sense_from_scalp);
  CHECK(hair.islands[0].root_at_high);
  CHECK(hair.sensed_area == 0.0);
  for (const Vec3& d : hair.triangle_directions) CHECK((d - Vec3::UnitX()).norm() < 1e-14);
}

TEST_CASE("a texture seam parts islands; islands too small to tell their axis carry no reference points") {
  const TexturedMesh long_card = card(Vec3(0, 0, 0.5), kDown, Vec3::UnitX(), 20.0, 2.0, 10);
  const TexturedMesh one_quad = card(Vec3(5, 0, 0.5), kDown, Vec3::UnitX(), 2.0, 2.0, 1);
  const ReferenceHair hair = reference_from_cards(joined(long_card, one_quad), scalp_triangle());
  REQUIRE(hair.islands.size() == 2);
  CHECK(hair.islands[0].used);
  CHECK(!hair.islands[1].used);
  CHECK(hair.islands[1].triangles == 2);
  CHECK(hair.total_area == doctest::Approx(44.0).epsilon(1e-14));
  CHECK(hair.used_area == doctest::Approx(40.0).epsilon(1e-14));
  CHECK(hair.triangle_directions.back() == Vec3::Zero());
  for (const Vec3& p : hair.samples.points) CHECK(p.x() < 1.0 + 1e-12);  // all on the long card
  // One mesh, two texture islands: the second half of the long card textured elsewhere in the atlas.
  TexturedMesh cut = long_card;
  const int n = static_cast<int>(cut.texture_coordinates.size());
  for (int k = 0; k < n; ++k) cut.texture_coordinates.push_back(cut.texture_coordinates[k] + Vec2(2, 0));
  for (std::size_t t = 10; t < cut.triangle_texture.size(); ++t) cut.triangle_texture[t] += Vec3i::Constant(n);
  CHECK(reference_from_cards(cut, scalp_triangle()).islands.size() == 2);
}

TEST_CASE("a tube's texture wraps around it: the axis along the tube is taken, not the one around its seam") {
  // A cylinder of radius 1 cm along +z from z = 0.5, u around (a seam at angle 0), v along.
  TexturedMesh tube;
  const int around = 12, rings = 10;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= around; ++j) {
      const double a = 2 * M_PI * j / around;
      tube.mesh.positions.push_back(Vec3(std::cos(a), std::sin(a), 0.5 + 2.0 * i));
      tube.texture_coordinates.push_back(Vec2(static_cast<double>(j) / around, 1.0 - static_cast<double>(i) / rings));
    }
  // Positions at j = around repeat j = 0 (as a seam in an OBJ repeats only the texture); weld them.
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < around; ++j) {
      const int row = i * (around + 1), next = (i + 1) * (around + 1);
      const int jp = (j + 1) % around;
      const Vec3i p(row + j, row + jp, next + jp), q(row + j, next + jp, next + j);
      tube.mesh.triangles.push_back(p), tube.triangle_texture.push_back(Vec3i(row + j, row + j + 1, next + j + 1));
      tube.mesh.triangles.push_back(q), tube.triangle_texture.push_back(Vec3i(row + j, next + j + 1, next + j));
    }
  const ReferenceHair hair = reference_from_cards(tube, scalp_triangle());
  REQUIRE(hair.islands.size() == 1);
  CHECK(hair.islands[0].along == 1);
  CHECK(hair.islands[0].root_at_high);
  CHECK(hair.islands[0].across_separation < 1.0);  // the seam's two sides meet
  for (const Vec3& d : hair.triangle_directions) CHECK((d - kDown).norm() < 1e-12);
}

TEST_CASE("load_obj_textured keeps the file's vertices and splits each polygon into a fan from its first corner") {
  const auto path = hairfit::testing::scratch_path("quad.obj");
  {
    std::ofstream out(path);
    out << "# two quads sharing an edge, a repeated vertex kept\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 0\n"
           "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\nf 5/1 4/4 3/3\n";
  }
  const TexturedMesh m = load_obj_textured(path, 10.0);
  REQUIRE(m.mesh.positions.size() == 5);
  CHECK(m.mesh.positions[2] == Vec3(10, 10, 0));
  CHECK(m.mesh.positions[4] == Vec3(0, 0, 0));
  REQUIRE(m.mesh.triangles.size() == 3);
  CHECK(m.mesh.triangles[0] == Vec3i(0, 1, 2));
  CHECK(m.mesh.triangles[1] == Vec3i(0, 2, 3));
  CHECK(m.mesh.triangles[2] == Vec3i(4, 3, 2));
  CHECK(m.triangle_texture[1] == Vec3i(0, 2, 3));
  CHECK(m.texture_coordinates[2] == Vec2(1, 1));
  CHECK_THROWS_AS(load_obj_textured(hairfit::testing::scratch_path("missing.obj")), InputError);
}
