#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <numeric>

#include "io/obj_mesh.h"
#include "io/ply_points.h"
#include "scalp/roots.h"
#include "scalp/scalp_outputs.h"
#include "tests/scalp/scalp_meshes.h"
#include "../support/scratch.h"

using namespace hairfit;

namespace {

// The roots' inputs with these maps (copies: RootInputs shares them); null = not used.
RootInputs maps_of(const GreyMap* density, const GreyMap* tilt, const GreyMap* length) {
  RootInputs in;
  if (density) in.density = std::make_shared<const GreyMap>(*density);
  if (tilt) in.tilt = std::make_shared<const GreyMap>(*tilt);
  if (length) in.length = std::make_shared<const GreyMap>(*length);
  return in;
}

const Vec3 kFront(0, 0, 1), kDown(0, -1, 0);

GreyMap make_map(int w, int h, const std::function<float(int, int)>& value) {
  GreyMap m;
  m.width = w;
  m.height = h;
  m.values.resize(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) m.values[static_cast<std::size_t>(y) * w + x] = value(x, y);
  return m;
}

struct Stats {
  double min = 0, mean = 0, cv = 0;
};

Stats spacing_stats(const std::vector<Vec3>& points) {
  const std::vector<double> d = nearest_neighbour_distances(points, 2);
  Stats s;
  s.min = *std::min_element(d.begin(), d.end());
  s.mean = std::accumulate(d.begin(), d.end(), 0.0) / d.size();
  double var = 0.0;
  for (double x : d) var += (x - s.mean) * (x - s.mean);
  s.cv = std::sqrt(var / d.size()) / s.mean;
  return s;
}

// Brute-force nearest-neighbour distances, to check the grid search.
std::vector<double> brute_nearest(const std::vector<Vec3>& p) {
  std::vector<double> d(p.size(), INFINITY);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < p.size(); ++j)
      if (i != j) d[i] = std::min(d[i], (p[i] - p[j]).norm());
  return d;
}

}  // namespace

TEST_CASE("roots: uniform density on a head cap — count, blue-noise spacing, attributes") {
  const ScalpChart ch = make_scalp_chart(test::head_cap(40, 1.6, 0.03), kFront, kDown, "cap.obj");
  RootOptions o;
  o.density = 40.0;
  o.seed = 11;
  const Roots r = make_roots(ch, {}, o, Exec{2, {}});
  const double integral = o.density * surface_area(ch.mesh);  // independent: the mesh's area
  CHECK(r.expected_count == doctest::Approx(integral).epsilon(1e-12));
  CHECK(std::abs(r.pores.size() - integral) <= 0.5);
  CHECK(r.hair_area == doctest::Approx(ch.area));

  // Blue noise: no clumps (minimum spacing a large share of the mean), no holes (small spread).
  // A Poisson (white-noise) set of the same size has min/mean ≈ 0 and CV ≈ 0.52.
  const Stats s = spacing_stats(r.pores.positions);
  const double hex = std::sqrt(2.0 / (std::sqrt(3.0) * o.density));  // hexagonal-packing spacing
  MESSAGE("roots: n=" << r.pores.size() << " min/mean=" << s.min / s.mean << " cv=" << s.cv
                      << " mean/hex=" << s.mean / hex);
  CHECK(s.min > 0.55 * s.mean);
  CHECK(s.cv < 0.15);
  CHECK(s.mean > 0.65 * hex);  // blue noise: ≈ 0.75 of the hexagonal lattice spacing
  CHECK(s.mean < 0.9 * hex);

  // Attributes: unit normals facing out, straight growth (tilt 0), uniform length, heights.
  double worst = 0.0;
  for (int i = 0; i < r.pores.size(); ++i) {
    worst = std::max(worst, std::abs(r.pores.normals[i].norm() - 1.0));
    worst = std::max(worst, (r.pores.directions[i] - r.pores.normals[i]).norm());
    CHECK(r.pores.lengths[i] == o.length);
    CHECK(r.pores.heights[i] >= 0.0);
    CHECK(r.pores.heights[i] <= 1.0);
    CHECK(r.pores.normals[i].dot(r.pores.positions[i]) > 0);  // outward on a convex-ish cap
  }
  CHECK(worst < 1e-12);
  const double top = *std::max_element(r.pores.heights.begin(), r.pores.heights.end());
  CHECK(top > 0.99);
}

TEST_CASE("roots: nearest-neighbour search agrees with brute force") {
  const ScalpChart ch = make_scalp_chart(test::head_cap(12), kFront, kDown, "cap.obj");
  RootOptions o;
  o.density = 3.0;
  const Roots r = make_roots(ch, {}, o);
  REQUIRE(r.pores.size() > 500);
  const std::vector<double> fast = nearest_neighbour_distances(r.pores.positions, 3);
  const std::vector<double> slow = brute_nearest(r.pores.positions);
  for (std::size_t i = 0; i < fast.size(); ++i) CHECK(fast[i] == slow[i]);
}

TEST_CASE("roots: density maps — integral, adaptivity, and no root on black") {
  const double radius = 7.0;
  const ScalpChart ch = make_scalp_chart(test::flat_disk(40, radius, 0.3), kFront, kDown, "disk.obj");
  RootOptions o;
  o.density = 200.0;
  o.seed = 5;
  const Exec two{2, {}};
  const int sides = 6 * 40;  // the hairline is a regular 240-gon of circumradius R
  const double disk_area = 0.5 * sides * radius * radius * std::sin(2 * M_PI / sides);

  SUBCASE("linear ramp left → right") {
    const int w = 512;
    const GreyMap ramp = make_map(w, w, [&](int x, int) { return static_cast<float>(x) / (w - 1); });
    const Roots r = make_roots(ch, maps_of(&ramp, nullptr, nullptr), o, two);
    // The chart is (−x, z)/R, so the map value is (chart_x + 1)/2 and its mean over the disk ½.
    const double integral = o.density * disk_area * 0.5;
    CHECK(std::abs(r.pores.size() - integral) < 0.02 * integral);
    CHECK(std::abs(r.expected_count - integral) < 0.005 * integral);
    // Share of roots in the left half of the chart: ∫_{x<0}(x+1)/2 / ∫(x+1)/2 = (π/2 − 2/3)/π.
    int left = 0;
    for (const Vec2& c : r.pores.chart) left += c.x() < 0;
    const double expected_share = (M_PI / 2 - 2.0 / 3.0) / M_PI;
    MESSAGE("ramp: roots=" << r.pores.size() << " left share=" << static_cast<double>(left) / r.pores.size()
                           << " expected " << expected_share);
    CHECK(static_cast<double>(left) / r.pores.size() == doctest::Approx(expected_share).epsilon(0.03));
    // Local spacing follows the local density: min spacing ≥ c × local mean spacing 1/√ρ.
    const std::vector<double> d = nearest_neighbour_distances(r.pores.positions, 2);
    double worst = INFINITY;
    for (int i = 0; i < r.pores.size(); ++i) {
      const double value = std::max(ramp.sample(chart_to_image(r.pores.chart[i])), 1.0 / 16);
      const double local_hex = std::sqrt(2.0 / (std::sqrt(3.0) * o.density * value));
      worst = std::min(worst, d[i] / local_hex);
    }
    MESSAGE("ramp: min spacing / local hexagonal spacing = " << worst);
    CHECK(worst > 0.45);
  }

  SUBCASE("left half black: density 0 means not a single root") {
    const int w = 256;
    const GreyMap half = make_map(w, w, [&](int x, int) { return x < w / 2 ? 0.0f : 1.0f; });
    const Roots r = make_roots(ch, maps_of(&half, nullptr, nullptr), o, two);
    const double integral = o.density * disk_area * 0.5;
    CHECK(std::abs(r.pores.size() - integral) < 0.02 * integral);
    for (const Vec2& c : r.pores.chart) CHECK(half.sample(chart_to_image(c)) > 0.0);
    const Stats s = spacing_stats(r.pores.positions);
    CHECK(s.min > 0.5 * s.mean);
    const PreguideRoots pre = make_preguide_roots(ch, maps_of(&half, nullptr, nullptr), o, two);
    for (const Vec2& c : pre.roots.chart) CHECK(half.sample(chart_to_image(c)) > 0.0);
  }

  SUBCASE("all black or zero density: no roots, no clusters") {
    const GreyMap black = make_map(8, 8, [](int, int) { return 0.0f; });
    const Roots r = make_roots(ch, maps_of(&black, nullptr, nullptr), o, two);
    CHECK(r.pores.size() == 0);
    CHECK(make_clusters(ch, r, o, two).size() == 0);
    CHECK(make_preguide_roots(ch, maps_of(&black, nullptr, nullptr), o, two).roots.size() == 0);
    RootOptions none = o;
    none.density = 0.0;
    CHECK(make_roots(ch, {}, none, two).pores.size() == 0);
  }
}

TEST_CASE("roots: deterministic for a seed and any thread count; the seed changes them") {
  const ScalpChart ch = make_scalp_chart(test::head_cap(24, 1.6, 0.04), kFront, kDown, "cap.obj");
  const GreyMap map = make_map(64, 64, [](int x, int y) { return static_cast<float>(0.2 + 0.8 * ((x + y) % 17) / 16.0); });
  RootOptions o;
  o.density = 30.0;
  o.guides = 200;
  o.seed = 99;
  std::string first_roots, first_clusters, first_pre;
  for (int threads : {1, 2, 4}) {
    const Exec exec{threads, {}};
    const Roots r = make_roots(ch, maps_of(&map, &map, &map), o, exec);
    const Clusters c = make_clusters(ch, r, o, exec);
    const PreguideRoots p = make_preguide_roots(ch, maps_of(&map, &map, &map), o, exec);
    if (threads == 1) {
      first_roots = digest(r).hex();
      first_clusters = digest(c).hex();
      first_pre = digest(p).hex();
    } else {
      CHECK(digest(r).hex() == first_roots);
      CHECK(digest(c).hex() == first_clusters);
      CHECK(digest(p).hex() == first_pre);
    }
  }
  o.seed = 100;
  CHECK(digest(make_roots(ch, maps_of(&map, nullptr, nullptr), o)).hex() != first_roots);
}

TEST_CASE("roots: make_scalp_roots equals make_roots, make_clusters and make_preguide_roots") {
  const ScalpChart ch = make_scalp_chart(test::head_cap(40, 1.6, 0.03), kFront, kDown, "cap.obj");
  const GreyMap map = make_map(64, 64, [](int x, int y) { return x + y < 20 ? 0.0f : static_cast<float>(x) / 63.0f; });
  RootOptions o;
  o.density = 30.0;
  o.guides = 40;
  o.preguide_spacing = 0.4;
  o.seed = 5;
  const Exec two{2, {}};
  const RootInputs maps = maps_of(&map, &map, nullptr);
  const ScalpRoots together = make_scalp_roots(ch, maps, o, two);
  const Roots roots = make_roots(ch, maps, o, two);
  CHECK(together.roots.pores.size() > 100);
  CHECK(digest(together.roots).hex() == digest(roots).hex());
  CHECK(digest(together.clusters).hex() == digest(make_clusters(ch, roots, o, two)).hex());
  CHECK(digest(together.preguides).hex() == digest(make_preguide_roots(ch, maps, o, two)).hex());
  CHECK_THROWS_AS(make_scalp_roots(ch, maps, o, Exec{0, {}}), std::invalid_argument);
  o.preguide_spacing = 0.0;
  CHECK_THROWS_AS(make_scalp_roots(ch, maps, o, two), std::invalid_argument);
}

TEST_CASE("roots: growth direction tilts toward down and never yields NaN") {
  const Vec3 down(0, -1, 0), front(0, 0, 1);
  const Vec3 side = Vec3(1, 0.2, 0).normalized();
  for (double tilt : {0.0, 30.0, 90.0}) {
    const Vec3 d = growth_direction(side, down, front, tilt);
    CHECK(d.norm() == doctest::Approx(1.0));
    CHECK(std::acos(std::clamp(d.dot(side), -1.0, 1.0)) * 180 / M_PI == doctest::Approx(tilt).epsilon(1e-9));
    const Vec3 tangent = (down - down.dot(side) * side).normalized();
    if (tilt > 0) CHECK((d - std::cos(tilt * M_PI / 180) * side).normalized().dot(tangent) == doctest::Approx(1.0));
  }
  // At the crown (normal = up) the tilt goes toward the back (−front), in the tangent plane.
  const Vec3 crown = growth_direction(Vec3(0, 1, 0), down, front, 90.0);
  CHECK(crown.isApprox(Vec3(0, 0, -1), 1e-12));
  // Even front parallel to the normal: some unit tangent.
  const Vec3 odd = growth_direction(Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(0, 0, 1), 45.0);
  CHECK(std::isfinite(odd.norm()));
  CHECK(odd.norm() == doctest::Approx(1.0));
  CHECK(odd.z() == doctest::Approx(std::cos(M_PI / 4)));

  // Maps: tilt and length from their ranges (black → first, white → second).
  const ScalpChart ch = make_scalp_chart(test::head_cap(16), kFront, kDown, "cap.obj");
  const GreyMap grey = make_map(4, 4, [](int, int) { return 0.25f; });
  RootOptions o;
  o.density = 5.0;
  o.tilt_range = {10.0, 50.0};
  o.length_range = {20.0, 40.0};
  const Roots r = make_roots(ch, maps_of(nullptr, &grey, &grey), o);
  REQUIRE(r.pores.size() > 100);
  for (int i = 0; i < r.pores.size(); ++i) {
    CHECK(r.pores.lengths[i] == doctest::Approx(25.0));
    const double angle = std::acos(std::clamp(r.pores.directions[i].dot(r.pores.normals[i]), -1.0, 1.0)) * 180 / M_PI;
    CHECK(angle == doctest::Approx(20.0).epsilon(1e-9));
  }
}

TEST_CASE("clusters: a partition of all pores by randomly chosen overlapping circles") {
  const ScalpChart ch = make_scalp_chart(test::head_cap(30, 1.6, 0.03), kFront, kDown, "cap.obj");
  RootOptions o;
  o.density = 30.0;
  o.guides = 300;
  o.seed = 3;
  const Roots r = make_roots(ch, {}, o, Exec{2, {}});
  const Clusters c = make_clusters(ch, r, o, Exec{2, {}});
  REQUIRE(c.size() == 300);
  // Partition: every pore in exactly one member list, consistent with pore_cluster.
  std::vector<int> seen(r.pores.size(), 0);
  for (int k = 0; k < c.size(); ++k)
    for (int i : c.members[k]) {
      ++seen[i];
      CHECK(c.pore_cluster[i] == k);
    }
  CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
  // Each pore lies in the circle of its cluster; the guide base is the centre pore.
  int multi = 0, elsewhere = 0;
  for (int i = 0; i < r.pores.size(); ++i) {
    const int k = c.pore_cluster[i];
    CHECK((r.pores.chart[i] - c.bases.chart[k]).norm() <= c.radius[k] * (1 + 1e-12));
    // Brute-force nearest centre.
    int nearest = 0;
    for (int j = 1; j < c.size(); ++j)
      if ((r.pores.chart[i] - c.bases.chart[j]).norm() < (r.pores.chart[i] - c.bases.chart[nearest]).norm()) nearest = j;
    if (c.candidate_clusters[i] > 1) {
      ++multi;
      elsewhere += k != nearest;
    } else {
      CHECK(k == nearest);
    }
  }
  for (int k = 0; k < c.size(); ++k) CHECK(c.bases.positions[k] == r.pores.positions[c.centre_pore[k]]);
  MESSAGE("clusters: pores in several circles " << multi << " of " << r.pores.size() << ", not in the nearest "
                                                << elsewhere);
  CHECK(multi > r.pores.size() / 5);      // overlap 1.3: borders are blurred
  CHECK(elsewhere > multi / 5);           // a random choice, not always the nearest circle
  // Guides cover the scalp evenly: blue-noise centres on the surface.
  const Stats s = spacing_stats(c.bases.positions);
  CHECK(s.min > 0.5 * s.mean);

  // The assignment varies with the seed only.
  RootOptions other = o;
  CHECK(digest(make_clusters(ch, r, other, Exec{1, {}})).hex() == digest(c).hex());
  other.seed = 4;
  const Clusters c2 = make_clusters(ch, r, other);
  CHECK(c2.pore_cluster != c.pore_cluster);

  // Overlap 1: circles are the exact covering, every pore still belongs to exactly one cluster.
  RootOptions tight = o;
  tight.cluster_overlap = 1.0;
  const Clusters c3 = make_clusters(ch, r, tight);
  int total = 0;
  for (const auto& m : c3.members) total += static_cast<int>(m.size());
  CHECK(total == r.pores.size());

  // More guides than pores: one cluster per pore.
  RootOptions many = o;
  many.guides = r.pores.size() + 10;
  CHECK(make_clusters(ch, r, many).size() == r.pores.size());
}

TEST_CASE("pre-guide roots: about one per spacing², blue noise") {
  const ScalpChart ch = make_scalp_chart(test::head_cap(30, 1.6), kFront, kDown, "cap.obj");
  RootOptions o;
  o.preguide_spacing = 1.0;
  const PreguideRoots p = make_preguide_roots(ch, {}, o);
  const double expected = ch.area * 2.0 / std::sqrt(3.0);
  CHECK(std::abs(p.roots.size() - expected) <= 0.5);
  const Stats s = spacing_stats(p.roots.positions);
  MESSAGE("pre-guides: n=" << p.roots.size() << " mean spacing " << s.mean << " min " << s.min);
  // Spacing is the hexagonal lattice's; a blue-noise set's nearest neighbours sit at ≈ 0.75 of it.
  CHECK(s.mean > 0.65);
  CHECK(s.mean < 0.9);
  CHECK(s.min > 0.5);
  for (double h : p.roots.heights) CHECK((h >= 0 && h <= 1));
}

TEST_CASE("roots.ply and chart.obj round trip") {
  const ScalpChart ch = make_scalp_chart(test::head_cap(10), kFront, kDown, "cap.obj");
  RootOptions o;
  o.density = 4.0;
  o.guides = 20;
  const Roots r = make_roots(ch, {}, o);
  const Clusters c = make_clusters(ch, r, o);
  const std::filesystem::path dir = hairfit::testing::fresh_scratch_folder("scalp");
  write_roots_ply(dir / "roots.ply", r, c);
  const PlyPoints back = read_ply_points(dir / "roots.ply");
  REQUIRE(static_cast<int>(back.positions.size()) == r.pores.size());
  for (int i = 0; i < r.pores.size(); ++i) {
    CHECK((back.positions[i] - r.pores.positions[i]).norm() < 1e-5);
    CHECK(back.column("cluster")->values[i] == c.pore_cluster[i]);
    CHECK(back.column("length")->values[i] == doctest::Approx(r.pores.lengths[i]));
    CHECK(back.column("dz")->values[i] == doctest::Approx(r.pores.directions[i].z()).epsilon(1e-6));
  }
  CHECK(back.column("cluster")->is_int);
  // ASCII too.
  PlyPoints ascii;
  ascii.positions = {Vec3(1, 2, 3), Vec3(-4, 5.5, 6)};
  ascii.columns = {{"id", true, {7, -8}}, {"w", false, {0.5, 0.25}}};
  write_ply_points(dir / "ascii.ply", ascii, false);
  const PlyPoints a = read_ply_points(dir / "ascii.ply");
  CHECK(a.positions[1] == Vec3(-4, 5.5, 6));
  CHECK(a.column("id")->values[1] == -8);
  CHECK(a.column("w")->values[0] == 0.5);
  CHECK_THROWS(write_ply_points(dir / "bad.ply", PlyPoints{{Vec3::Zero()}, {{"bad name", false, {1}}}}));
  CHECK(!std::filesystem::exists(dir / "bad.ply"));

  write_chart_obj(dir / "chart.obj", ch);
  const LoadedMesh loaded = load_obj_mesh(dir / "chart.obj");
  CHECK(loaded.mesh.triangles.size() == ch.mesh.triangles.size());
  std::filesystem::remove_all(dir);
}

TEST_CASE("roots: stubble from the hull is at most half of its straight run in the layer, a hair's width at least") {
  CHECK(fitted_stubble(0.2, 1.0) == 0.2);                  // the layer holds it: its own length
  CHECK(fitted_stubble(0.2, 0.3) == 0.5 * 0.3);            // half the run
  CHECK(fitted_stubble(0.2, 0.0) == kShortestStubble);     // a root at the layer's very edge
  CHECK(fitted_stubble(0.2, 0.015) == kShortestStubble);   // half the run is thinner than a hair

  const ScalpChart ch = make_scalp_chart(test::head_cap(24, 1.6, 0.03), kFront, kDown, "cap.obj");
  RootOptions o;
  o.density = 20.0;
  o.seed = 3;
  for (const double length : {0.2, 0.3}) {
    RootInputs in;
    in.vertex_lengths.assign(ch.mesh.positions.size(), length);
    in.vertex_hang_weights.assign(ch.mesh.positions.size(), 0.0);
    in.stubble_length = 0.25;
    // The run grows across the cap with x, so that some roots keep their length and some do not.
    const auto run_at = [](const Vec3& p) { return std::max(0.0, 0.4 * (p.x() + 1.0)); };
    std::atomic<int> calls{0};
    std::atomic<bool> reach_ok{true};
    in.layer_run = [&](const Vec3& root, const Vec3& direction, double reach) {
      ++calls;
      if (!(std::abs(reach - length / kStubbleShare) < 1e-12) || !(std::abs(direction.norm() - 1.0) < 1e-12)) reach_ok = false;
      return std::min(reach, run_at(root));
    };
    const Roots r = make_roots(ch, in, o, Exec{2, {}});
    REQUIRE(r.pores.size() > 50);
    INFO("hair from the hull " << length << " cm long, stubble under 0.25 cm");
    if (length >= in.stubble_length) {
      CHECK(calls == 0);
      for (double l : r.pores.lengths) CHECK(l == doctest::Approx(length).epsilon(1e-12));
      continue;
    }
    CHECK(calls == r.pores.size());
    CHECK(reach_ok);
    int shortened = 0;
    for (int i = 0; i < r.pores.size(); ++i) {
      const double run = std::min(length / kStubbleShare, run_at(r.pores.positions[i]));
      CHECK(r.pores.lengths[i] == doctest::Approx(std::max(kShortestStubble, std::min(length, kStubbleShare * run))).epsilon(1e-12));
      shortened += r.pores.lengths[i] < length - 1e-12;
    }
    CHECK(shortened > 0);
    CHECK(shortened < r.pores.size());
  }
}
