// The round trip on a small case (issue 47): sixteen textured cards laid root to tip over a
// hemispherical scalp become reference hair, the hull is voxelised from them, the method runs on
// that hull at default hair keys (test-sized), and its strands are compared with the cards. The
// comparison's machinery is checked against exact answers; the method's figures are printed, not
// judged (bench/reference_hair.cpp measures them at full size on MakeHuman hair).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <filesystem>
#include <fstream>

#include "core/shapes.h"
#include "io/obj_mesh.h"
#include "pipeline/inputs.h"
#include "reference/reference_cards.h"
#include "reference/reference_hull.h"
#include "reference/round_trip_scene.h"
#include "tests/support/report_figure.h"
#include "tests/support/run_in_process.h"
#include "tests/support/scene_text.h"
#include "tests/support/scratch.h"

using namespace hairfit;

namespace {

constexpr double kScalpRadius = 9.0, kCardRadius = 10.0;  // cm: the cards lie 1 cm over the scalp
constexpr int kCards = 16, kQuads = 12;
const double kFrom = 10.0 * M_PI / 180.0, kTo = 115.0 * M_PI / 180.0;  // polar angles, root to tip

// The unit vector at polar angle theta (from +z) and azimuth phi.
Vec3 on_sphere(double theta, double phi) {
  return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// Card k runs down the meridian at azimuth 2πk/16, 2 cm wide, the root at the top of its texture.
TexturedMesh meridian_cards() {
  TexturedMesh m;
  for (int k = 0; k < kCards; ++k) {
    const double phi = 2.0 * M_PI * k / kCards;
    const Vec3 across(-std::sin(phi), std::cos(phi), 0.0);
    const int first = static_cast<int>(m.mesh.positions.size());
    for (int i = 0; i <= kQuads; ++i)
      for (int side = 0; side < 2; ++side) {
        const double s = static_cast<double>(i) / kQuads;
        m.mesh.positions.push_back(kCardRadius * on_sphere(kFrom + s * (kTo - kFrom), phi) + (side - 0.5) * 2.0 * across);
        m.texture_coordinates.push_back(Vec2(side, 1.0 - s));
      }
    for (int i = 0; i < kQuads; ++i) {
      const int a = first + 2 * i, b = a + 1, c = a + 3, d = a + 2;
      m.mesh.triangles.push_back(Vec3i(a, b, c)), m.triangle_texture.push_back(Vec3i(a, b, c));
      m.mesh.triangles.push_back(Vec3i(a, c, d)), m.triangle_texture.push_back(Vec3i(a, c, d));
    }
  }
  return m;
}

Mesh hemisphere_scalp() { return spherical_cap(80.0 * M_PI / 180.0, 10, 32, kScalpRadius); }

}  // namespace

TEST_CASE("round trip: cards over a hemisphere, their hull, the method at default keys, the match") {
  const TexturedMesh cards = meridian_cards();
  const Mesh scalp = hemisphere_scalp();
  const ReferenceHair reference = reference_from_cards(cards, scalp);

  // Every card is one island, read along v from its top, its root decided by the scalp, and its
  // hair running down its meridian: each direction is the chord of one of the cards' quads.
  REQUIRE(reference.islands.size() == kCards);
  for (const CardIsland& island : reference.islands) {
    CHECK(island.used);
    CHECK(island.along == 1);
    CHECK(island.root_at_high);
    CHECK(island.sense_from_scalp);
  }
  std::vector<Vec3> chords;
  for (int k = 0; k < kCards; ++k)
    for (int i = 0; i < kQuads; ++i) {
      const double phi = 2.0 * M_PI * k / kCards, step = (kTo - kFrom) / kQuads;
      chords.push_back((on_sphere(kFrom + (i + 1) * step, phi) - on_sphere(kFrom + i * step, phi)).normalized());
    }
  REQUIRE(reference.samples.points.size() > 1000);
  for (const Vec3& d : reference.samples.directions) {
    double nearest = INFINITY;
    for (const Vec3& c : chords) nearest = std::min(nearest, (d - c).norm());
    CHECK(nearest < 1e-12);
  }

  // The hull encloses the cards and the scalp.
  ReferenceHullOptions hull_options;
  hull_options.threads = 2;
  const ReferenceHull hull = reference_hull(cards.mesh, scalp, hull_options);
  CHECK(analyse_topology(hull.mesh).closed());
  for (std::size_t k = 0; k < reference.samples.points.size(); k += 37)
    CHECK(winding_number(hull.mesh, reference.samples.points[k]) > 0.99);
  for (const Vec3& p : scalp.positions) CHECK(winding_number(hull.mesh, p) > 0.99);

  // The comparison itself: the reference against itself, and copies shifted, reversed or turned.
  const OrientedPoints& r = reference.samples;
  MatchOptions lines, vectors;
  vectors.signed_directions = true;
  for (const MatchOptions& o : {lines, vectors}) {
    const MatchFigures self = match_reference(r, r, o);
    CHECK(self.precision == 1.0);
    CHECK(self.recall == 1.0);
    CHECK(self.reached == 1.0);
    CHECK(self.median_angle == 0.0);
  }
  OrientedPoints shifted = r, reversed = r, turned = r;
  for (Vec3& p : shifted.points) p.z() += 1.5;
  for (Vec3& d : reversed.directions) d = -d;
  for (std::size_t k = 0; k < r.points.size(); ++k) turned.directions[k] = r.directions[k].cross(r.points[k].normalized()).normalized();
  const MatchFigures s = match_reference(shifted, r, vectors);  // each point 1.5 cm from its original
  CHECK(s.precision == 1.0);
  CHECK(s.recall == 1.0);
  CHECK(match_reference(reversed, r, lines).f == 1.0);
  const MatchFigures back = match_reference(reversed, r, vectors);
  CHECK(back.f == 0.0);
  CHECK(back.reached == 1.0);
  CHECK(back.median_angle == 180.0);
  // Turned a right angle about the radius: the nearest point is the original, 90° off.
  CHECK(match_reference(turned, r, lines).median_angle == doctest::Approx(90.0).epsilon(1e-12));

  // The method on the hull, test-sized: its strands against the cards.
  const std::filesystem::path dir = hairfit::testing::fresh_scratch_folder("round-trip");
  write_obj_mesh(dir / "scalp.obj", scalp);
  write_obj_mesh(dir / "hull.obj", hull.mesh);
  RoundTripScene keys;
  keys.down = Vec3(0, 0, -1);
  keys.front = Vec3(0, 1, 0);
  keys.guides = 40;
  keys.density = 2.0;
  const std::string text = hairfit::testing::with_keys(
      round_trip_scene_text(keys),
      {{"fields", "voxel = 0.4"}, {"rod", "segments = 24"}, {"guides", "samples = 8"}, {"strands", "points = 12"}});
  std::ofstream(dir / "scene.toml") << text;
  const Scene scene = parse_scene(dir / "scene.toml");
  CHECK(scene.hair.from_shell);  // no length or tilt declared: the run derives them from the hull
  const PipelineResult run = hairfit::testing::run_in_process(scene, load_inputs(scene));
  const OrientedPoints generated = curve_points(run.values.strands->fibres, 0.5);
  REQUIRE(generated.points.size() > 100);
  for (const MatchOptions& o : {lines, vectors}) {
    const MatchFigures m = match_reference(generated, r, o);
    CHECK(m.generated == static_cast<int>(generated.points.size()));
    CHECK(m.f == doctest::Approx(2 * m.precision * m.recall / (m.precision + m.recall)));
    CHECK(m.reached >= m.recall);
    CHECK(m.median_angle <= (o.signed_directions ? 180.0 : 90.0));
    MESSAGE(std::string(o.signed_directions ? "signed" : "as lines") << ": precision " << m.precision << ", recall " << m.recall
                                                          << ", F " << m.f << ", reached " << m.reached
                                                          << ", median angle " << m.median_angle << "°, coverage "
                                                          << hairfit::testing::figure(run.report, "strands", "coverage"));
  }
}
