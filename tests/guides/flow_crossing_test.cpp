// flow_crossing against pairs counted by hand and by brute force.
#include <doctest/doctest.h>

#include <cmath>

#include "core/random.h"
#include "guides/flow_crossing.h"

using namespace hairfit;

namespace {

std::vector<Vec3> line(const Vec3& from, const Vec3& step, int points) {
  std::vector<Vec3> out;
  for (int i = 0; i < points; ++i) out.push_back(from + i * step);
  return out;
}

}  // namespace

TEST_CASE("parallel curves 1 cm apart never cross; their median angle is the first bin") {
  Curves c;
  c.add(line(Vec3(0, 0, 0), Vec3(0.1, 0, 0), 50));
  c.add(line(Vec3(0, 1, 0), Vec3(0.1, 0, 0), 50));
  const FlowCrossing f = flow_crossing(c);
  CHECK(f.pairs > 0);
  CHECK(f.crossing_share == 0.0);
  CHECK(f.median_degrees == doctest::Approx(0.025));
}

TEST_CASE("points of one curve are never paired, and pairs outside [near, far] are not counted") {
  Curves c;
  c.add(line(Vec3(0, 0, 0), Vec3(0.1, 0, 0), 50));
  CHECK(flow_crossing(c).pairs == 0);
  c.add(line(Vec3(0, 2, 0), Vec3(0.1, 0, 0), 50));  // 2 cm away: beyond far
  CHECK(flow_crossing(c).pairs == 0);
  c.add(line(Vec3(0, 0.1, 0), Vec3(0.1, 0, 0), 50));  // 0.1 cm: only pairs at ≥ 0.3 cm along
  const FlowCrossing f = flow_crossing(c);
  CHECK(f.pairs > 0);
  CHECK(f.crossing_share == 0.0);
}

TEST_CASE("random segments: count and share equal a brute-force count") {
  Curves c;
  for (int k = 0; k < 40; ++k) {
    Random r(1, RandomStage::test, k);
    const Vec3 start(r.uniform(0, 4), r.uniform(0, 4), r.uniform(0, 4));
    Vec3 dir(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1));
    dir.normalize();
    c.add(line(start, 0.25 * dir, 9), k);
  }
  FlowCrossingOptions o;
  o.threads = 3;
  const FlowCrossing f = flow_crossing(c, o);
  // Brute force: straight curves have one tangent each.
  long long pairs = 0, crossing = 0;
  for (std::size_t a = 0; a < c.count(); ++a)
    for (std::size_t b = a + 1; b < c.count(); ++b) {
      const Vec3 ta = (c.point(a, 1) - c.point(a, 0)).normalized(), tb = (c.point(b, 1) - c.point(b, 0)).normalized();
      for (std::size_t i = 0; i < c.size(a); ++i)
        for (std::size_t j = 0; j < c.size(b); ++j) {
          const double d = (c.point(a, i) - c.point(b, j)).norm();
          if (d < o.near || d > o.far) continue;
          ++pairs;
          crossing += ta.dot(tb) < std::cos(M_PI / 4);
        }
    }
  CHECK(f.pairs == pairs);
  CHECK(f.crossing_share == doctest::Approx(static_cast<double>(crossing) / pairs).epsilon(1e-12));
  o.threads = 1;
  const FlowCrossing serial = flow_crossing(c, o);
  CHECK(serial.pairs == f.pairs);
  CHECK(serial.median_degrees == f.median_degrees);
}

TEST_CASE("opposite curves differ by 180°") {
  Curves c;
  c.add(line(Vec3(0, 0, 0), Vec3(0.1, 0, 0), 20));
  c.add(line(Vec3(1.9, 0.5, 0), Vec3(-0.1, 0, 0), 20));
  const FlowCrossing f = flow_crossing(c);
  CHECK(f.crossing_share == 1.0);
  CHECK(f.median_degrees == doctest::Approx(179.975));
}

TEST_CASE("above max_points the figures are estimated from a sample, close to the exact count") {
  // 400 wavy curves in a 6 cm box, 30 points each (12 000 points), sampled at 2 000.
  Curves c;
  for (int k = 0; k < 400; ++k) {
    Random r(4, RandomStage::test, k);
    const Vec3 start(r.uniform(0, 6), r.uniform(0, 6), r.uniform(0, 6));
    const double phase = r.uniform(0, 2 * M_PI), tilt = r.uniform(-0.8, 0.8);
    std::vector<Vec3> points;
    for (int i = 0; i < 30; ++i) points.push_back(start + Vec3(0.2 * i, tilt * std::sin(0.4 * i + phase), 0.1 * i * tilt));
    c.add(points, k);
  }
  FlowCrossingOptions exact;
  exact.max_points = 0;
  exact.threads = 2;
  const FlowCrossing all = flow_crossing(c, exact);
  FlowCrossingOptions sample = exact;
  sample.max_points = 2000;
  const FlowCrossing some = flow_crossing(c, sample);
  CHECK(all.sampled_points == 0);
  CHECK(std::abs(some.sampled_points - 2000) < 200);  // one point in six, by a hash of its index
  MESSAGE("crossing share " << all.crossing_share << " exact, " << some.crossing_share << " sampled; median "
                            << all.median_degrees << "°, " << some.median_degrees << "°");
  CHECK(all.crossing_share > 0.05);  // the case has crossings to estimate
  CHECK(std::abs(some.crossing_share - all.crossing_share) < 0.02);
  CHECK(std::abs(some.median_degrees - all.median_degrees) < 2.0);
  CHECK(std::abs(static_cast<double>(some.pairs) / all.pairs - 1.0) < 0.05);
  sample.threads = 1;
  const FlowCrossing serial = flow_crossing(c, sample);
  CHECK(serial.crossing_share == some.crossing_share);
  CHECK(serial.median_degrees == some.median_degrees);
}
