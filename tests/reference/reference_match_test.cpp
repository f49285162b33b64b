// The point-by-point match against reference hair: hand-made cases with exact answers, the grid
// search against brute force, and the arc-length resampling of curves.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "reference/reference_match.h"

using namespace hairfit;

namespace {

Vec3 in_plane(double degrees) { return Vec3(std::cos(degrees * M_PI / 180.0), std::sin(degrees * M_PI / 180.0), 0.0); }

// Ten reference points on the x axis, x = 0 … 9, running along +x.
OrientedPoints reference_line() {
  OrientedPoints r;
  for (int i = 0; i < 10; ++i) r.points.push_back(Vec3(i, 0, 0)), r.directions.push_back(Vec3::UnitX());
  return r;
}

// Five generated points: beside the line (A), over it turned by 30° (B) and by 60° (C), far beyond
// its end (D), and on it running backward (E).
OrientedPoints generated_five() {
  OrientedPoints g;
  g.points = {Vec3(0, 1.5, 0), Vec3(5, 0, 1), Vec3(5, 0, 0), Vec3(20, 0, 0), Vec3(2, 0, 0)};
  g.directions = {Vec3::UnitX(), in_plane(30), in_plane(60), Vec3::UnitX(), -Vec3::UnitX()};
  return g;
}

// The figures by their definitions, every pair of points compared.
MatchFigures brute_force(const OrientedPoints& g, const OrientedPoints& r, const MatchOptions& o) {
  MatchFigures f;
  f.generated = static_cast<int>(g.points.size());
  f.reference = static_cast<int>(r.points.size());
  auto near = [&](const Vec3& a, const Vec3& b) { return (a - b).squaredNorm() <= o.radius * o.radius; };
  auto turns_little = [&](const Vec3& a, const Vec3& b) { return direction_angle(a, b, o.signed_directions) <= o.max_angle; };
  int precise = 0, recalled = 0, reached = 0, near_any = 0;
  std::vector<double> angles;
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    bool match = false, any = false;
    std::size_t nearest = 0;
    for (std::size_t j = 0; j < r.points.size(); ++j) {
      any |= near(g.points[i], r.points[j]);
      match |= near(g.points[i], r.points[j]) && turns_little(g.directions[i], r.directions[j]);
      if ((g.points[i] - r.points[j]).squaredNorm() < (g.points[i] - r.points[nearest]).squaredNorm()) nearest = j;
    }
    precise += match;
    near_any += any;
    angles.push_back(direction_angle(g.directions[i], r.directions[nearest], o.signed_directions));
  }
  for (std::size_t j = 0; j < r.points.size(); ++j) {
    bool match = false, any = false;
    for (std::size_t i = 0; i < g.points.size(); ++i) {
      any |= near(g.points[i], r.points[j]);
      match |= near(g.points[i], r.points[j]) && turns_little(g.directions[i], r.directions[j]);
    }
    recalled += match;
    reached += any;
  }
  f.precision = static_cast<double>(precise) / f.generated;
  f.recall = static_cast<double>(recalled) / f.reference;
  f.f = f.precision + f.recall > 0 ? 2 * f.precision * f.recall / (f.precision + f.recall) : 0.0;
  f.reached = static_cast<double>(reached) / f.reference;
  f.near = static_cast<double>(near_any) / f.generated;
  std::sort(angles.begin(), angles.end());
  const std::size_t n = angles.size();
  f.median_angle = n % 2 ? angles[n / 2] : 0.5 * (angles[n / 2 - 1] + angles[n / 2]);
  return f;
}

void check_same(const MatchFigures& a, const MatchFigures& b) {
  CHECK(a.generated == b.generated);
  CHECK(a.reference == b.reference);
  CHECK(a.precision == b.precision);
  CHECK(a.recall == b.recall);
  CHECK(a.f == b.f);
  CHECK(a.reached == b.reached);
  CHECK(a.near == b.near);
  CHECK(a.median_angle == b.median_angle);
}

// Every share (precision, recall, F, reached, near) is `share`, and the median angle is `angle`.
void check_every_share(const MatchFigures& m, double share, double angle) {
  CHECK(m.precision == share);
  CHECK(m.recall == share);
  CHECK(m.f == share);
  CHECK(m.reached == share);
  CHECK(m.near == share);
  CHECK(m.median_angle == angle);
}

}  // namespace

TEST_CASE("direction angles: as lines in [0°, 90°], as vectors in [0°, 180°]") {
  CHECK(direction_angle(Vec3::UnitX(), Vec3::UnitY(), false) == doctest::Approx(90.0).epsilon(1e-15));
  CHECK(direction_angle(Vec3::UnitX(), -Vec3::UnitX(), false) == 0.0);
  CHECK(direction_angle(Vec3::UnitX(), -Vec3::UnitX(), true) == doctest::Approx(180.0).epsilon(1e-15));
  CHECK(direction_angle(Vec3::UnitX(), in_plane(60), false) == doctest::Approx(60.0).epsilon(1e-14));
  CHECK(direction_angle(Vec3::UnitX(), -in_plane(60), false) == doctest::Approx(60.0).epsilon(1e-14));
  CHECK(direction_angle(Vec3::UnitX(), -in_plane(60), true) == doctest::Approx(120.0).epsilon(1e-14));
}

TEST_CASE("five points against a line: exact precision, recall, reach and median angle, both senses") {
  MatchOptions o;  // 2 cm, 45°, as lines
  const MatchFigures lines = match_reference(generated_five(), reference_line(), o);
  // A, B and E match (E runs backward, which lines do not see); C turns 60°, D is 11 cm away.
  CHECK(lines.precision == doctest::Approx(3.0 / 5).epsilon(1e-15));
  // x = 0, 1 near A; 4, 5, 6 near B (1 cm above 5); 0 … 4 near E.
  CHECK(lines.recall == doctest::Approx(7.0 / 10).epsilon(1e-15));
  CHECK(lines.f == doctest::Approx(2 * 0.6 * 0.7 / 1.3).epsilon(1e-15));
  CHECK(lines.reached == doctest::Approx(8.0 / 10).epsilon(1e-15));  // C reaches 3 … 7 too
  CHECK(lines.near == doctest::Approx(4.0 / 5).epsilon(1e-15));     // all but D
  CHECK(lines.median_angle == 0.0);                                   // of 0, 30, 60, 0, 0
  o.signed_directions = true;
  const MatchFigures vectors = match_reference(generated_five(), reference_line(), o);
  CHECK(vectors.precision == doctest::Approx(2.0 / 5).epsilon(1e-15));
  CHECK(vectors.recall == doctest::Approx(5.0 / 10).epsilon(1e-15));
  CHECK(vectors.reached == lines.reached);
  CHECK(vectors.median_angle == doctest::Approx(30.0).epsilon(1e-14));  // of 0, 30, 60, 0, 180
  check_same(lines, brute_force(generated_five(), reference_line(), MatchOptions{}));
  CHECK(matched_points(generated_five(), reference_line()) == std::vector<unsigned char>{1, 1, 0, 0, 1});
  check_same(vectors, brute_force(generated_five(), reference_line(), o));
}

TEST_CASE("hair against itself matches everywhere; shifted, turned or reversed copies give known figures") {
  const OrientedPoints r = reference_line();
  check_every_share(match_reference(r, r), 1.0, 0.0);
  OrientedPoints far = r;
  for (Vec3& p : far.points) p.z() += 2.5;
  check_every_share(match_reference(far, r), 0.0, 0.0);
  OrientedPoints turned = r;
  for (Vec3& d : turned.directions) d = in_plane(50);
  const MatchFigures t = match_reference(turned, r);
  CHECK(t.precision == 0.0);
  CHECK(t.reached == 1.0);
  CHECK(t.median_angle == doctest::Approx(50.0).epsilon(1e-14));
  OrientedPoints reversed = r;
  for (Vec3& d : reversed.directions) d = -d;
  MatchOptions o;
  CHECK(match_reference(reversed, r, o).f == 1.0);
  o.signed_directions = true;
  CHECK(match_reference(reversed, r, o).f == 0.0);
  CHECK(match_reference(reversed, r, o).median_angle == doctest::Approx(180.0).epsilon(1e-15));
}

TEST_CASE("the grid search gives the brute-force figures on random points, for any thread count") {
  std::mt19937_64 random(47);
  std::uniform_real_distribution<double> box(0.0, 12.0), unit(-1.0, 1.0);
  auto cloud = [&](int n) {
    OrientedPoints p;
    for (int i = 0; i < n; ++i) {
      p.points.push_back(Vec3(box(random), box(random), 0.3 * box(random)));
      Vec3 d(unit(random), unit(random), unit(random));
      p.directions.push_back(d.normalized());
    }
    return p;
  };
  const OrientedPoints g = cloud(400), r = cloud(301);
  for (const bool sense : {false, true})
    for (const double radius : {0.7, 2.0, 5.0}) {
      MatchOptions o;
      o.radius = radius;
      o.signed_directions = sense;
      const MatchFigures one = match_reference(g, r, o);
      check_same(one, brute_force(g, r, o));
      o.threads = 3;
      check_same(one, match_reference(g, r, o));
    }
}

TEST_CASE("no points on one side gives zero figures; bad options are refused") {
  const MatchFigures none = match_reference(OrientedPoints{}, reference_line());
  CHECK(none.generated == 0);
  CHECK(none.reference == 10);
  CHECK(none.recall == 0.0);
  CHECK(none.reached == 0.0);
  MatchOptions o;
  o.radius = 0.0;
  CHECK_THROWS_AS(match_reference(generated_five(), reference_line(), o), std::invalid_argument);
  OrientedPoints unpaired = reference_line();
  unpaired.directions.pop_back();
  CHECK_THROWS_AS(match_reference(unpaired, reference_line()), std::invalid_argument);
}

TEST_CASE("curve points: every `spacing` cm of arc length, the segment's direction, the tip when on the spacing") {
  Curves curves;
  curves.add({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)});  // an L with a repeated corner
  curves.add({Vec3(0, 0, 5), Vec3(0, 0, 6.2)});
  const OrientedPoints p = curve_points(curves, 0.5);
  const std::vector<Vec3> points = {Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(1, 0, 0), Vec3(1, 0.5, 0), Vec3(1, 1, 0),
                                    Vec3(0, 0, 5), Vec3(0, 0, 5.5), Vec3(0, 0, 6)};
  const std::vector<Vec3> directions = {Vec3::UnitX(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitY(), Vec3::UnitY(),
                                        Vec3::UnitZ(), Vec3::UnitZ(), Vec3::UnitZ()};
  REQUIRE(p.points.size() == points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    CHECK((p.points[k] - points[k]).norm() < 1e-15);
    CHECK(p.directions[k] == directions[k]);
  }
  CHECK_THROWS_AS(curve_points(curves, 0.0), std::invalid_argument);
}
