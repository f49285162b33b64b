#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/random.h"
#include "core/segment_triangle.h"
#include "core/triangle_grid.h"
#include "strands/cutting.h"
#include "hair/guide_track.h"
#include "strands/strands.h"

using namespace hairfit;

namespace {

double polyline_length(const std::vector<Vec3>& p) {
  double l = 0;
  for (std::size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  return l;
}

// Outside where z > 0: the volume is the half-space below the plane z = 0.
double below_plane(const Vec3& p) { return p.z(); }

// A guide that rises along +y and then bends toward +x over a quarter circle of radius 5.
std::vector<Vec3> bent_guide(int n = 41) {
  std::vector<Vec3> g;
  for (int i = 0; i < n; ++i) {
    const double a = 0.5 * M_PI * i / (n - 1);
    g.emplace_back(5.0 - 5.0 * std::cos(a), 5.0 * std::sin(a), 0.0);
  }
  return g;
}

// The scalp y = 0 with the head below it, its exit the exact projection onto it.
HeadExit plane_scalp_exit() {
  return [](const Vec3& p, double& scalp) {
    scalp = p.y();
    return p.y() < 0.0 ? Vec3(p.x(), 0.0, p.z()) : p;
  };
}

// A guide along x that rises from the scalp y = 0 to `height` within its first centimetre.
std::vector<Vec3> rising_guide(double height) {
  std::vector<Vec3> guide;
  for (int i = 0; i <= 40; ++i) guide.emplace_back(0.25 * i, height * std::min(1.0, 0.25 * i), 0.0);
  return guide;
}

// Forty fibres from pores in the guide's root disk (|z| ≤ 0.3, on the scalp), of random lengths
// in [shortest, longest]: visit(pore, length).
template <class Visit>
void forty_fibres(std::uint64_t seed, double shortest, double longest, Visit visit) {
  Random r(seed, RandomStage::test, 0);
  for (int k = 0; k < 40; ++k) {
    const Vec3 pore(0.0, 0.0, r.uniform(-0.3, 0.3));
    visit(pore, r.uniform(shortest, longest));
  }
}

}  // namespace

TEST_CASE("cutting: an excursion under the threshold is kept, one over it is cut where it left") {
  // In at z = −1, out to z = +1 over x ∈ [1, 3], back in: the crossings are at x = 1.5 and 2.5,
  // so exactly 1 cm runs outside (a polyline of chords between the listed points, each of which
  // crosses at its midpoint, and a horizontal stretch z = 1 in between).
  const std::vector<Vec3> dip{{0, 0, -1}, {1, 0, -1}, {2, 0, 1}, {2, 0, 1}, {3, 0, -1}, {4, 0, -1}};
  const double outside = std::hypot(0.5, 1.0) * 2;  // two half-chords outside
  const CutResult kept = cut_at_exit(dip, below_plane, outside + 1e-9);
  CHECK_FALSE(kept.cut);
  CHECK(kept.points == dip);
  const CutResult cut = cut_at_exit(dip, below_plane, outside - 1e-9);
  CHECK(cut.cut);
  CHECK(cut.outside_length > outside - 1e-9);
  REQUIRE(cut.points.size() == 3);
  CHECK((cut.points.back() - Vec3(1.5, 0, 0)).norm() < 1e-15);  // the exit crossing
  // The distances handed back are the function's at the kept points, the crossing's included.
  for (const CutResult* r : {&kept, &cut}) {
    REQUIRE(r->distances.size() == r->points.size());
    for (std::size_t i = 0; i < r->points.size(); ++i) CHECK(r->distances[i] == below_plane(r->points[i]));
  }
}

TEST_CASE("cutting: an excursion running to the tip counts to the tip; one from the root is never cut") {
  const std::vector<Vec3> up{{0, 0, -1}, {0, 0, 0.5}, {0, 0, 3}};
  const CutResult c = cut_at_exit(up, below_plane, 2.0);
  CHECK(c.cut);
  CHECK(c.points.back().isApprox(Vec3(0, 0, 0), 1e-15));
  CHECK_FALSE(cut_at_exit(up, below_plane, 3.5).cut);
  const std::vector<Vec3> from_root{{0, 0, 1}, {0, 0, 5}, {0, 0, 9}};
  CHECK_FALSE(cut_at_exit(from_root, below_plane, 0.1).cut);
  // Several short excursions each under the threshold are not added up.
  const std::vector<Vec3> wavy{{0, 0, -1}, {1, 0, 1}, {2, 0, -1}, {3, 0, 1}, {4, 0, -1}};
  // Each excursion runs half of two chords of length √5 outside: √5 ≈ 2.236 cm, twice.
  CHECK_FALSE(cut_at_exit(wavy, below_plane, 2.3).cut);
  CHECK(cut_at_exit(wavy, below_plane, 2.2).cut);
}

TEST_CASE("cutting tips: a fibre ending outside is cut where it last left, however short the stretch") {
  // Out at z = 0 between the second and third points (3 cm outside to the tip), under a threshold
  // of 3.5: kept without cut_tips, cut at the crossing with it.
  const std::vector<Vec3> up{{0, 0, -1}, {0, 0, 0.5}, {0, 0, 3}};
  CHECK_FALSE(cut_at_exit(up, below_plane, 3.5).cut);
  const CutResult c = cut_at_exit(up, below_plane, 3.5, nullptr, true);
  CHECK(c.cut);
  CHECK(c.outside_length == doctest::Approx(3.0).epsilon(1e-15));
  CHECK(c.points.back().isApprox(Vec3(0, 0, 0), 1e-15));
  // The last of several excursions is the one cut; the earlier, under the threshold, stay.
  const std::vector<Vec3> wavy{{0, 0, -1}, {1, 0, 1}, {2, 0, -1}, {3, 0, 1}};
  const CutResult w = cut_at_exit(wavy, below_plane, 10.0, nullptr, true);
  CHECK(w.cut);
  REQUIRE(w.points.size() == 4);
  CHECK((w.points.back() - Vec3(2.5, 0, 0)).norm() < 1e-15);
  // A fibre that ends inside, or lies outside from its root on, is not cut.
  const std::vector<Vec3> back_in{{0, 0, -1}, {1, 0, 1}, {2, 0, -1}};
  CHECK_FALSE(cut_at_exit(back_in, below_plane, 10.0, nullptr, true).cut);
  const std::vector<Vec3> from_root{{0, 0, 1}, {0, 0, 5}, {0, 0, 9}};
  CHECK_FALSE(cut_at_exit(from_root, below_plane, 0.1, nullptr, true).cut);
}

TEST_CASE("cutting with a quick side test: the same cut, exact distances at the crossings") {
  // quick says ±infinity beyond 0.5 cm of the plane; random wiggly polylines about it.
  const DistanceFunction quick = [](const Vec3& p) {
    return std::fabs(p.z()) > 0.5 ? std::copysign(std::numeric_limits<double>::infinity(), p.z()) : p.z();
  };
  Random r(3, RandomStage::test, 2);
  int cuts = 0;
  for (int n = 0; n < 500; ++n) {
    std::vector<Vec3> line;
    for (int i = 0; i < 16; ++i) line.emplace_back(0.3 * i, 0.0, r.uniform(-2.0, 1.0) * (i > 0) - 0.1 * (i == 0));
    const double threshold = r.uniform(0.0, 3.0);
    const CutResult exact = cut_at_exit(line, below_plane, threshold);
    const CutResult fast = cut_at_exit(line, below_plane, threshold, quick);
    CHECK(fast.points == exact.points);
    CHECK(fast.cut == exact.cut);
    CHECK(fast.outside_length == exact.outside_length);
    REQUIRE(fast.distances.size() == exact.distances.size());
    for (std::size_t i = 0; i < fast.distances.size(); ++i) {
      CHECK((fast.distances[i] > 0.0) == (exact.distances[i] > 0.0));
      if (!std::isinf(fast.distances[i])) CHECK(fast.distances[i] == exact.distances[i]);
    }
    if (exact.cut) CHECK(fast.distances.back() == below_plane(fast.points.back()));  // the crossing, exactly
    cuts += exact.cut;
  }
  CHECK(cuts > 50);
  CHECK(cuts < 450);
}

TEST_CASE("the guide track's frame is orthonormal and does not twist along a planar guide") {
  const GuideTrack track(bent_guide());
  CHECK(track.length() == doctest::Approx(2.5 * M_PI).epsilon(1e-3));
  for (double s = 0; s <= track.length() + 2; s += 0.37) {
    Vec3 p, t, d1, d2;
    track.at(s, p, t, d1, d2);
    CHECK(std::fabs(t.norm() - 1) < 1e-12);
    CHECK(std::fabs(d1.dot(t)) < 1e-12);
    CHECK(std::fabs(d2.dot(t)) < 1e-12);
    CHECK(std::fabs(d1.norm() - 1) < 1e-12);
    // A rotation-minimising frame on a plane curve keeps one normal perpendicular to the plane.
    CHECK(std::min(std::fabs(std::fabs(d1.z()) - 1), std::fabs(std::fabs(d2.z()) - 1)) < 1e-9);
  }
}

TEST_CASE("a fibre starts exactly at its pore and has exactly its own length") {
  StrandOptions o;
  o.wisp.points = 16;
  Random r(3, RandomStage::test, 0);
  for (int k = 0; k < 200; ++k) {
    const Vec3 pore(r.uniform(-0.4, 0.4), r.uniform(-0.1, 0.1), r.uniform(-0.4, 0.4));
    const double length = r.uniform(0.5, 20.0);  // shorter and longer than the guide (7.85 cm)
    o.wisp.turns = r.uniform(-2, 2);
    const std::vector<Vec3> f = make_fibre(bent_guide(), pore, length, 0.6, o);
    REQUIRE(f.size() == 16);
    CHECK((f[0] - pore).norm() <= 1e-9);
    CHECK(std::fabs(polyline_length(f) - length) <= 1e-11 * length);  // the length solve stops at 1e-12
    for (const Vec3& p : f) CHECK(p.allFinite());
  }
  // Hair shorter than its own wisp offsets (the polyline at zero reach is already longer): a
  // straight fibre of exactly its length along the root tangent.
  for (double length : {1e-3, 0.01, 0.05}) {
    const Vec3 pore(0.4, 0.0, 0.3);
    o.wisp.turns = 1.0;
    const std::vector<Vec3> f = make_fibre(bent_guide(), pore, length, 0.5, o);
    CHECK((f[0] - pore).norm() <= 1e-12);
    CHECK(std::fabs(polyline_length(f) - length) <= 1e-12 * length);
    CHECK((f.back() - f.front()).norm() == doctest::Approx(length).epsilon(1e-12));  // straight
  }
}

TEST_CASE("fibres stay inside the generalised cylinder and wind by the declared turns") {
  // A straight guide along +z: the wisp radius profile and the winding angle are easy to read off.
  std::vector<Vec3> guide;
  for (int i = 0; i <= 10; ++i) guide.emplace_back(0, 0, i);
  StrandOptions o;
  o.wisp.points = 41;
  o.wisp.root_radius = 0.3;
  o.wisp.tip_radius = 0.9;
  o.wisp.turns = 1.5;
  const Vec3 pore(0.3, 0.0, 0.0);  // on the rim of a wisp of extent 0.3
  const std::vector<Vec3> f = make_fibre(guide, pore, 10.0, 0.3, o);
  double previous_angle = 0.0, turned = 0.0;
  for (int i = 0; i < 41; ++i) {
    const double t = i / 40.0;
    const double radius = std::hypot(f[i].x(), f[i].y());
    CHECK(radius <= o.wisp.root_radius + (o.wisp.tip_radius - o.wisp.root_radius) * t + 1e-9);
    const double angle = std::atan2(f[i].y(), f[i].x());
    if (i > 0) turned += std::remainder(angle - previous_angle, 2 * M_PI);
    previous_angle = angle;
  }
  CHECK(turned / (2 * M_PI) == doctest::Approx(1.5).epsilon(1e-9));
  // A fibre on the rim of the wisp reaches the tip radius exactly (it has no other offset).
  CHECK(std::hypot(f.back().x(), f.back().y()) == doctest::Approx(0.9).epsilon(1e-9));
}

TEST_CASE("a fibre longer than its guide continues along the guide's last tangent") {
  StrandOptions o;
  o.wisp.points = 31;
  o.wisp.root_radius = o.wisp.tip_radius = 0.0;
  const std::vector<Vec3> f = make_fibre(bent_guide(), Vec3::Zero(), 12.0, 0.0, o);
  // With zero radius the fibre is the guide itself, then a straight run along its last chord.
  const std::vector<Vec3> g = bent_guide();
  const Vec3 last = (g[40] - g[39]).normalized();
  const Vec3 run = f.back() - g[40];
  CHECK(run.cross(last).norm() < 1e-9);
  CHECK(run.dot(last) > 0.0);
  CHECK(std::fabs(f.back().z()) < 1e-12);
}

TEST_CASE("make_strands: one fibre per pore, cutting counted, identical for any thread count") {
  Curves guides;
  guides.add(bent_guide(), 0);
  std::vector<Vec3> second = bent_guide();
  for (Vec3& p : second) p = Vec3(-p.x(), p.y(), p.z() + 1.0);
  guides.add(second, 1);
  Pores pores;
  Random r(11, RandomStage::test, 1);
  for (int i = 0; i < 300; ++i) {
    const int g = i % 2;
    pores.positions.push_back(Vec3(r.uniform(-0.3, 0.3), 0.0, g + r.uniform(-0.3, 0.3)));
    pores.lengths.push_back(r.uniform(4, 12));
    pores.guide.push_back(g);
  }
  StrandOptions o;
  o.cutting = true;
  o.cut_threshold = 0.5;
  o.wisp.turns = 0.5;
  // The volume: the slab y < 4.5 (fibres rise along +y and leave it for good).
  const DistanceFunction slab = [](const Vec3& p) { return p.y() - 4.5; };
  Strands reference;
  for (int threads : {1, 2, 4}) {
    const Exec exec{threads, {}};
    StrandSurroundings around;
    around.volume = slab;
    const GrownStrands plain = make_strands(guides, pores, o, around, exec);
    const Strands& s = plain.strands;
    const FibrePointSides& sides = plain.sides;
    REQUIRE(sides.outside_volume.size() == s.fibres.points.size());
    for (std::size_t k = 0; k < sides.outside_volume.size(); ++k)
      CHECK(sides.outside_volume[k] == (slab(s.fibres.points[k]) > 0.0));
    CHECK(sides.in_head.empty());
    // The same with `quick` telling the side far from the boundary (±infinity beyond 1 cm).
    const DistanceFunction quick = [&slab](const Vec3& p) {
      const double d = slab(p);
      return std::fabs(d) > 1.0 ? std::copysign(std::numeric_limits<double>::infinity(), d) : d;
    };
    StrandSurroundings quick_around = around;
    quick_around.volume_quick = quick;
    const GrownStrands quickly = make_strands(guides, pores, o, quick_around, exec);
    const Strands& q = quickly.strands;
    CHECK(q.fibres.points == s.fibres.points);
    CHECK(q.fibres.offsets == s.fibres.offsets);
    CHECK(quickly.sides.outside_volume == sides.outside_volume);
    // With a head (below y = −1, beyond every fibre): the reported sides at every point but the
    // roots, and the same fibres.
    const HeadExit below = [](const Vec3& p, double& scalp) {
      scalp = p.y() + 1.0;
      return p.y() < -1.0 ? Vec3(p.x(), -1.0, p.z()) : p;
    };
    StrandSurroundings head_around = around;
    head_around.out_of_head = below;
    const GrownStrands headed = make_strands(guides, pores, o, head_around, exec);
    const Strands& h = headed.strands;
    const FibrePointSides& head_sides = headed.sides;
    CHECK(h.fibres.points == s.fibres.points);
    REQUIRE(head_sides.in_head.size() == h.fibres.points.size());
    for (std::size_t c = 0; c < h.fibres.count(); ++c)
      for (std::size_t k = h.fibres.offsets[c]; k < h.fibres.offsets[c + 1]; ++k) {
        const int expected = h.fibres.points[k].y() + 1.0 < 0.0;
        if (k == h.fibres.offsets[c]) CHECK(head_sides.in_head[k] == -1);  // the root is not asked about
        else if (h.cut[c] && k + 1 == h.fibres.offsets[c + 1]) CHECK((head_sides.in_head[k] == -1 || head_sides.in_head[k] == expected));
        else CHECK(head_sides.in_head[k] == expected);
      }
    CHECK(s.fibres.count() == 300);
    CHECK(s.cut_count > 0);
    for (std::size_t c = 0; c < s.fibres.count(); ++c) {
      CHECK(s.fibres.guide[c] == pores.guide[c]);
      CHECK((s.fibres.point(c, 0) - pores.positions[c]).norm() <= 1e-9);
      if (s.cut[c]) CHECK(std::fabs(s.fibres.point(c, s.fibres.size(c) - 1).y() - 4.5) < 1e-9);
      else CHECK(std::fabs(polyline_length(std::vector<Vec3>(s.fibres.points.begin() + s.fibres.offsets[c],
                                                             s.fibres.points.begin() + s.fibres.offsets[c + 1])) -
                           pores.lengths[c]) <= 1e-6 * pores.lengths[c]);
    }
    if (threads == 1) reference = s;
    else {
      CHECK(s.fibres.points == reference.fibres.points);
      CHECK(s.fibres.offsets == reference.fibres.offsets);
    }
  }
}

TEST_CASE("a fibre that would pass behind the scalp is moved out of the head, keeping its root and length") {
  // The scalp is the plane y = 0 with the head below it, and the exit is the exact projection
  // onto it. The guide hugs the scalp, so a wisp winding about it sends its fibres below.
  std::vector<Vec3> guide;
  for (int i = 0; i <= 40; ++i) guide.emplace_back(0.25 * i, 0.05 * std::sin(M_PI * i / 40.0), 0.0);
  const HeadExit project = plane_scalp_exit();
  StrandOptions o;
  o.wisp.points = 24;
  o.wisp.root_radius = 0.5;
  o.wisp.tip_radius = 1.0;
  o.wisp.turns = 0.75;
  Random r(5, RandomStage::test, 0);
  int moved = 0;
  for (int k = 0; k < 50; ++k) {
    const Vec3 pore(0.0, 0.0, r.uniform(-0.5, 0.5));  // in the wisp's root disk, on the scalp
    const double length = r.uniform(4.0, 14.0);    // shorter and longer than the guide (10 cm)
    const std::vector<Vec3> loose = make_fibre(guide, pore, length, 0.5, o);
    const std::vector<Vec3> kept = make_fibre(guide, pore, length, 0.5, o, project);
    bool dips = false;
    for (const Vec3& p : loose) dips = dips || p.y() < 0.0;
    moved += dips;
    REQUIRE(kept.size() == loose.size());
    CHECK(kept[0] == pore);  // the root stays exactly at its pore
    for (const Vec3& p : kept) CHECK(p.y() >= 0.0);
    CHECK(std::fabs(polyline_length(kept) - length) <= 1e-6 * length);
    if (!dips) CHECK(kept == loose);  // nothing to move: the same fibre, bit for bit
  }
  CHECK(moved > 10);  // the case exercises the exit, not only the fast path
}

TEST_CASE("make_strands takes over fibres grown beforehand (grow_fibre): the same strands, bit for bit") {
  // Two guides hugging the scalp y = 0 (the head below it), so that winding wisps send some fibres
  // behind the scalp (grown again with the exit) and the cut at y = 0.3 shortens others.
  Curves guides;
  for (int g = 0; g < 2; ++g) {
    std::vector<Vec3> guide;
    for (int i = 0; i <= 40; ++i) guide.emplace_back(0.25 * i, 0.05 * std::sin(M_PI * i / 40.0), 2.0 * g);
    guides.add(guide, g);
  }
  const HeadExit project = plane_scalp_exit();
  const DistanceFunction slab = [](const Vec3& p) { return p.y() - 0.3; };
  Pores pores;
  Random r(7, RandomStage::test, 2);
  for (int i = 0; i < 120; ++i) {
    const int g = i % 2;
    pores.positions.emplace_back(0.0, 0.0, 2.0 * g + r.uniform(-0.5, 0.5));
    pores.lengths.push_back(r.uniform(4.0, 14.0));
    pores.guide.push_back(g);
  }
  StrandOptions o;
  o.wisp.points = 24;
  o.wisp.root_radius = 0.5;
  o.wisp.tip_radius = 1.0;
  o.wisp.turns = 0.75;
  o.cutting = true;
  o.cut_threshold = 0.2;
  // The wisp extents as make_strands measures them.
  std::vector<GuideTrack> tracks;
  std::vector<std::vector<int>> pores_of(2);
  for (std::size_t i = 0; i < pores.positions.size(); ++i) pores_of[pores.guide[i]].push_back(static_cast<int>(i));
  std::vector<double> extent;
  for (int g = 0; g < 2; ++g) {
    tracks.emplace_back(std::vector<Vec3>(guides.points.begin() + guides.offsets[g], guides.points.begin() + guides.offsets[g + 1]));
    extent.push_back(wisp_extent(tracks[g], pores.positions, pores_of[g]));
  }
  const std::size_t n = fibre_point_count(o.wisp);
  REQUIRE(n == 24);
  StrandSurroundings around;
  around.volume = slab;
  around.out_of_head = project;
  for (int threads : {1, 3}) {
    const Exec exec{threads, {}};
    std::vector<Vec3> grown(n * pores.positions.size());
    for (std::size_t i = 0; i < pores.positions.size(); ++i)
      grow_fibre(tracks[pores.guide[i]], pores.positions[i], pores.lengths[i], extent[pores.guide[i]], o.wisp, &grown[n * i]);
    const GrownStrands grown_fresh = make_strands(guides, pores, o, around, exec);
    const GrownStrands grown_taken = make_strands(guides, pores, o, around, exec, std::move(grown));
    const Strands &fresh = grown_fresh.strands, &taken = grown_taken.strands;
    const FibrePointSides &sides = grown_fresh.sides, &sides_grown = grown_taken.sides;
    CHECK(taken.fibres.points == fresh.fibres.points);
    CHECK(taken.fibres.offsets == fresh.fibres.offsets);
    CHECK(taken.cut == fresh.cut);
    CHECK(sides_grown.in_head == sides.in_head);
    CHECK(sides_grown.outside_volume == sides.outside_volume);
    // The case exercises both paths: fibres moved out of the head, and fibres cut.
    int moved = 0;
    for (std::size_t c = 0; c < fresh.fibres.count(); ++c)
      moved += sides.in_head[fresh.fibres.offsets[c] + 1] == -1;
    CHECK(moved > 5);
    CHECK(fresh.cut_count > 5);
  }
  std::vector<Vec3> wrong(5);
  CHECK_THROWS_AS(make_strands(guides, pores, o, around, {}, wrong), std::invalid_argument);
}

TEST_CASE("a chord through a narrow ridge the exit does not see is lifted off it, keeping root and length") {
  // The scalp is y = h(x) with a ridge h = 0.4·exp(−(x − 5)²/0.2) across it, the head below; the
  // exit sees only the plane y = 0 (as an interpolated field rounds a feature narrower than a
  // voxel). The guide rises from the scalp to y = 0.15 within 1 cm and runs along x through the
  // ridge, so fibre points land on both sides of it and chords pass through it. The exact chord test is the triangle grid's.
  Mesh scalp;
  const int nx = 240, nz = 40;
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= nx; ++i) {
      const double x = -1.0 + 12.0 * i / nx, z = -2.0 + 4.0 * k / nz;
      scalp.positions.emplace_back(x, 0.4 * std::exp(-(x - 5.0) * (x - 5.0) / 0.2), z);
    }
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int v = k * (nx + 1) + i;
      scalp.triangles.emplace_back(v, v + nx + 1, v + 1);  // normals toward +y, out of the head
      scalp.triangles.emplace_back(v + 1, v + nx + 1, v + nx + 2);
    }
  REQUIRE(triangle_normal(scalp, 0).y() > 0);
  const TriangleGrid grid(scalp);
  HeadExit exit = plane_scalp_exit();
  const HeadExit blind = exit;
  exit.chord_crossing = [&](const Vec3& a, const Vec3& b, bool, ChordCrossing& first) {
    const SegmentHit hit = grid.first_crossing(a, b);
    if (!hit.found()) return false;
    first = {hit.t, a + hit.t * (b - a), triangle_normal(scalp, hit.triangle)};
    return true;
  };
  auto crossings = [&](const std::vector<Vec3>& fibre) {  // every triangle, no grid
    int n = 0;
    for (std::size_t i = 1; i < fibre.size(); ++i)
      for (const Vec3i& f : scalp.triangles)
        if (!std::isnan(segment_triangle_parameter(fibre[i - 1], fibre[i], scalp.positions[f[0]], scalp.positions[f[1]],
                                                   scalp.positions[f[2]]))) {
          ++n;
          break;
        }
    return n;
  };
  const std::vector<Vec3> guide = rising_guide(0.15);
  StrandOptions o;
  o.wisp.points = 20;
  int crossed_before = 0;
  forty_fibres(8, 7.0, 12.0, [&](const Vec3& pore, double length) {
    const std::vector<Vec3> loose = make_fibre(guide, pore, length, 0.3, o, blind);
    const std::vector<Vec3> kept = make_fibre(guide, pore, length, 0.3, o, exit);
    crossed_before += crossings(loose) > 0;
    CHECK(kept[0] == pore);
    CHECK(crossings(kept) == 0);
    CHECK(std::fabs(polyline_length(kept) - length) <= 1e-6 * length);
    if (crossings(loose) == 0) CHECK(kept == loose);
  });
  CHECK(crossed_before > 20);  // the case exercises the lift
}

TEST_CASE("fibres held in a thin layer: points that skim out of the volume move back in, keeping root and length") {
  // The layer 0 ≤ y ≤ 0.4 over the scalp y = 0 (the head below): a guide along its middle and
  // wisps 0.3–0.6 cm wide, winding, so fibres leave it on both sides. The volume's exit moves a
  // point above the layer by less than 1 cm to 0.02 cm inside it; the head's exit comes after.
  const std::vector<Vec3> guide = rising_guide(0.2);
  HeadExit exit = plane_scalp_exit();
  const HeadExit head_only = exit;
  exit.into_volume = [](const Vec3& p) { return p.y() > 0.4 && p.y() < 1.4 ? Vec3(p.x(), 0.38, p.z()) : p; };
  StrandOptions o;
  o.wisp.points = 24;
  o.wisp.turns = 0.75;
  int left_before = 0;
  forty_fibres(9, 6.0, 12.0, [&](const Vec3& pore, double length) {
    const std::vector<Vec3> loose = make_fibre(guide, pore, length, 0.3, o, head_only);
    const std::vector<Vec3> held = make_fibre(guide, pore, length, 0.3, o, exit);
    bool left = false;
    for (const Vec3& p : loose) left = left || p.y() > 0.4;
    left_before += left;
    CHECK(held[0] == pore);
    for (const Vec3& p : held) {
      CHECK(p.y() >= 0.0);
      CHECK(p.y() <= 0.4);
    }
    CHECK(std::fabs(polyline_length(held) - length) <= 1e-6 * length);
  });
  CHECK(left_before > 20);  // the case exercises the containment
}

TEST_CASE("a fibre whose chord the keep-out pass cannot lift off the scalp ends before that chord") {
  // A scalp sheet at y = 2 that the head exit does not see (both sides read clear of the head, as
  // at a real scalp's rim) and whose crossings cannot be lifted: the crossed plane's normal runs
  // along x, so lifting moves a chord's end sideways and it still crosses. Fibres rising along
  // the bent guide through y = 2 are cut before their first crossing chord; no segment crossing
  // the sheet is left, and the count says how many were cut there.
  Curves guides;
  guides.add(bent_guide(), 0);
  Pores pores;
  Random r(12, RandomStage::test, 1);
  for (int i = 0; i < 60; ++i) {
    pores.positions.push_back(Vec3(r.uniform(-0.3, 0.3), 0.0, r.uniform(-0.3, 0.3)));
    pores.lengths.push_back(i % 3 == 0 ? r.uniform(0.8, 1.5) : r.uniform(4, 8));  // a third stay below the sheet
    pores.guide.push_back(0);
  }
  HeadExit exit = [](const Vec3& p, double& scalp) {
    scalp = std::numeric_limits<double>::infinity();
    return p;
  };
  exit.chord_crossing = [](const Vec3& a, const Vec3& b, bool, ChordCrossing& first) {
    if ((a.y() < 2.0) == (b.y() < 2.0)) return false;
    first.t = (2.0 - a.y()) / (b.y() - a.y());
    first.point = a + first.t * (b - a);
    first.normal = Vec3(1, 0, 0);
    return true;
  };
  StrandOptions o;
  o.wisp.points = 16;
  StrandSurroundings plain, against_sheet;
  against_sheet.out_of_head = exit;
  const Strands loose = make_strands(guides, pores, o, plain, Exec{2, {}}).strands;
  Strands reference;
  for (int threads : {1, 3}) {
    const Strands s = make_strands(guides, pores, o, against_sheet, Exec{threads, {}}).strands;
    CHECK(s.scalp_crossings == 0);
    int reaching = 0;
    for (std::size_t f = 0; f < s.fibres.count(); ++f) {
      CAPTURE(f);
      const auto begin = s.fibres.points.begin() + s.fibres.offsets[f], end = s.fibres.points.begin() + s.fibres.offsets[f + 1];
      const std::vector<Vec3> fibre(begin, end);
      const std::vector<Vec3> whole(loose.fibres.points.begin() + loose.fibres.offsets[f],
                                    loose.fibres.points.begin() + loose.fibres.offsets[f + 1]);
      CHECK(fibre.front() == pores.positions[f]);
      for (const Vec3& p : fibre) CHECK(p.y() < 2.0);
      const bool reaches = std::any_of(whole.begin(), whole.end(), [](const Vec3& p) { return p.y() >= 2.0; });
      reaching += reaches;
      CHECK(s.cut[f] == reaches);
      if (!reaches) CHECK(fibre == whole);  // untouched where the sheet is not met
    }
    CHECK(reaching > 20);
    CHECK(reaching < 60);
    CHECK(s.cut_at_scalp == reaching);
    CHECK(s.cut_count == reaching);
    if (threads == 1) reference = s;
    else CHECK(s.fibres.points == reference.fibres.points);
  }
}

TEST_CASE("fibre layer depths: evenly spaced between the margins, the furthest upstream on top") {
  CHECK(fibre_layer_depth(0, 1) == doctest::Approx(0.5).epsilon(1e-15));
  const double expected[] = {0.8, 0.6, 0.4, 0.2};
  for (int rank = 0; rank < 4; ++rank) CHECK(fibre_layer_depth(rank, 4) == doctest::Approx(expected[rank]).epsilon(1e-14));
  for (int count : {2, 7, 100}) {
    CHECK(fibre_layer_depth(0, count) < 1.0 - kLayerMargin);
    CHECK(fibre_layer_depth(count - 1, count) > kLayerMargin);
  }
}

TEST_CASE("fibres spread through the layer: each at its own depth past the settle, root and length kept") {
  // The layer 0 ≤ y ≤ 2 over the scalp y = 0: λ = y / 2, and the placement moves a point to
  // λ + w·(depth − λ) exactly. A guide rising to y = 1 and running along +x; 60 pores around its
  // root, in two wisps (alternate pores) so that ranks are per wisp.
  Curves guides;
  guides.add(rising_guide(1.0), 0);
  guides.add(rising_guide(1.0), 1);
  Pores pores;
  Random r(21, RandomStage::test, 0);
  for (int i = 0; i < 60; ++i) {
    pores.positions.push_back(Vec3(r.uniform(-0.3, 0.3), 0.0, r.uniform(-0.3, 0.3)));
    pores.lengths.push_back(r.uniform(5.0, 9.0));
    pores.guide.push_back(i % 2);
  }
  StrandOptions o;
  o.wisp.points = 20;
  o.layer_depth = true;
  StrandSurroundings around;
  around.to_layer_depth = [](const Vec3& p, const Vec3&, double depth, double weight) {
    const double lambda = 0.5 * p.y();
    return Vec3(p.x(), 2.0 * (lambda + weight * (depth - lambda)), p.z());
  };
  const std::vector<WispStation> stations = wisp_stations(o.wisp);
  Strands reference;
  for (int threads : {1, 2, 4}) {
    const Strands s = make_strands(guides, pores, o, around, Exec{threads, {}}).strands;
    REQUIRE(s.fibres.count() == pores.positions.size());
    if (threads == 1) reference = s;
    CHECK(s.fibres.points == reference.fibres.points);
  }
  // Within each wisp the fibres' depths past the settle are the ranks' depths, upstream on top:
  // the guide leaves its root along (1, 1, 0)/√2, so on the scalp y = 0 upstream is smaller x.
  for (int g = 0; g < 2; ++g) {
    std::vector<std::pair<double, std::size_t>> upstream;
    for (std::size_t i = g; i < pores.positions.size(); i += 2) upstream.push_back({pores.positions[i].x(), i});
    std::sort(upstream.begin(), upstream.end());
    const int count = static_cast<int>(upstream.size());
    for (int rank = 0; rank < count; ++rank) {
      const std::size_t i = upstream[rank].second;
      const std::size_t begin = reference.fibres.offsets[i], end = reference.fibres.offsets[i + 1];
      std::vector<Vec3> fibre(reference.fibres.points.begin() + begin, reference.fibres.points.begin() + end);
      CHECK(fibre[0] == pores.positions[i]);
      CHECK(std::fabs(polyline_length(fibre) - pores.lengths[i]) <= 1e-9 * pores.lengths[i]);
      for (std::size_t k = 0; k < fibre.size(); ++k)
        // Past the settle by the smoothing's reach: near the guide's turn the smoothed moves blur
        // the depth a little; along its straight end, where the moves are constant, exactly.
        if (k >= kLayerMoveSmoothing && stations[k - kLayerMoveSmoothing].w == 1.0) {
          CHECK(std::fabs(0.5 * fibre[k].y() - fibre_layer_depth(rank, count)) < 0.05);
          if (k + 3 >= fibre.size())
            CHECK(0.5 * fibre[k].y() == doctest::Approx(fibre_layer_depth(rank, count)).epsilon(1e-12));
        }
    }
  }
  // Without the placement (or without the option) the fibres are the paper's wisps, unchanged.
  StrandOptions paper = o;
  paper.layer_depth = false;
  const Strands plain = make_strands(guides, pores, paper, {}, Exec{1, {}}).strands;
  CHECK(make_strands(guides, pores, paper, around, Exec{1, {}}).strands.fibres.points == plain.fibres.points);
  CHECK(make_strands(guides, pores, o, {}, Exec{1, {}}).strands.fibres.points == plain.fibres.points);
  CHECK(plain.fibres.points != reference.fibres.points);
}

TEST_CASE("a fibre whose length jumps with its reach still has exactly its length") {
  // A straight guide along +x; the adjustment throws point 5 sideways once it passes x = 2, so
  // the fibre's length jumps there and no reach gives it exactly. A small jump is trimmed off the
  // last chord of the fibre just too long; one longer than the last chord is made up by the fibre
  // just too short going on along its last chord.
  std::vector<Vec3> line;
  for (int i = 0; i <= 60; ++i) line.emplace_back(0.25 * i, 0.0, 0.0);
  const GuideTrack track(line);
  WispShape shape;
  shape.points = 16;
  const std::vector<WispStation> stations = wisp_stations(shape);
  std::vector<Vec3> points(stations.size());
  std::vector<WispPoint> layout(stations.size());
  for (double jump : {0.05, 0.3, 3.0}) {
    int jumped = 0;
    const FibreAdjust adjust = [&](Vec3* p, int n) {
      if (n > 5 && p[5].x() > 2.0) p[5] += Vec3(0.0, jump, 0.0), ++jumped;
    };
    for (double length : {7.0, 8.0, 9.5}) {
      const Vec3 pore(0.0, 0.0, 0.1);
      fibre_along(track, pore, length, 0.3, stations, &adjust, points.data(), layout.data());
      CHECK(points[0] == pore);
      CHECK(polyline_length(points) == doctest::Approx(length).epsilon(1e-9));
      for (const Vec3& p : points) CHECK(p.allFinite());
    }
    CHECK(jumped > 0);
  }
}

TEST_CASE("a pore in a hollow of the scalp: its first chord turns up about the root until it clears the triangle beside it") {
  // The pore at the origin on a scalp facing +y; beside it the scalp rises as the triangle on the
  // plane y = 0.5x + 0.01 (0.02 ≤ x ≤ 3, |z| ≤ 1), whose plane passes above the pore. The fibre
  // leaves along its guide at slope 0.6, so its first chord runs from behind that plane through
  // the triangle (at x = 0.1), and lifting the chord's far end cannot clear a root behind the
  // plane. Turned up about the root, at the rise 0.75 (slope 1.13) it meets the plane at
  // x = 0.0159, off the triangle.
  std::vector<Vec3> line;
  for (int k = 0; k <= 20; ++k) line.push_back(0.25 * k * Vec3(1.0, 0.6, 0.0).normalized());
  Curves guides;
  guides.add(line, 0);
  Pores pores;
  pores.positions = {Vec3::Zero()};
  pores.lengths = {5.0};
  pores.guide = {0};
  HeadExit exit = [](const Vec3& p, double& scalp) {
    scalp = std::numeric_limits<double>::infinity();
    return p;
  };
  const Vec3 wall_normal = Vec3(-0.5, 1.0, 0.0).normalized();
  exit.chord_crossing = [wall_normal](const Vec3& a, const Vec3& b, bool, ChordCrossing& first) {
    const double fa = a.y() - 0.5 * a.x() - 0.01, fb = b.y() - 0.5 * b.x() - 0.01;
    if ((fa < 0.0) == (fb < 0.0)) return false;
    const double t = fa / (fa - fb);
    const Vec3 p = a + t * (b - a);
    if (p.x() < 0.02 || p.x() > 3.0 || std::fabs(p.z()) > 1.0) return false;
    first.t = t;
    first.point = p;
    first.normal = wall_normal;
    return true;
  };
  StrandOptions o;
  o.wisp.points = 16;
  StrandSurroundings around;
  around.out_of_head = exit;
  const Strands without = make_strands(guides, pores, o, around, Exec{1, {}}).strands;
  CHECK(without.scalp_crossings == 1);  // without the pore's normal the crossing stays
  pores.normals = {Vec3(0, 1, 0)};
  const Strands with = make_strands(guides, pores, o, around, Exec{1, {}}).strands;
  CHECK(with.scalp_crossings == 0);
  CHECK(with.cut_count == 0);
  const std::vector<Vec3> fibre(with.fibres.points.begin(), with.fibres.points.end());
  REQUIRE(fibre.size() == 16);
  CHECK(fibre[0] == Vec3::Zero());
  const Vec3 first = fibre[1] - fibre[0];
  CHECK(first.y() / first.norm() == doctest::Approx(0.75).epsilon(1e-12));
  ChordCrossing hit;
  for (int k = 1; k < 16; ++k) CHECK(!exit.chord_crossing(fibre[k - 1], fibre[k], k == 1, hit));
  double length = 0.0;
  for (int k = 1; k < 16; ++k) length += (fibre[k] - fibre[k - 1]).norm();
  CHECK(length == doctest::Approx(5.0).epsilon(1e-9));  // the turn runs inside the length solve
}

TEST_CASE("a fibre too short for its own wisp offset, laid straight along the root tangent, is kept out of the head too") {
  // The scalp y = 0 (the head below). The guide leaves its root 3° into the head; a pore 0.8 cm
  // from the guide's root, with 0.5 cm of hair, is shorter than its own offset in the wisp, so it
  // is laid straight along the root tangent, into the head, unless the keep-out pass sees it.
  std::vector<Vec3> guide;
  for (int i = 0; i <= 20; ++i) guide.push_back(0.25 * i * Vec3(1.0, -0.05, 0.0).normalized());
  const Vec3 pore(0.0, 0.0, 0.8);
  StrandOptions o;
  o.wisp.points = 8;
  const std::vector<Vec3> loose = make_fibre(guide, pore, 0.5, 1.0, o);
  REQUIRE(loose.size() == 8);
  CHECK(loose.back().y() < -0.02);  // straight along the root tangent, 3° down
  for (std::size_t k = 1; k < loose.size(); ++k)
    CHECK((loose[k] - loose[k - 1]).normalized().dot(Vec3(1.0, -0.05, 0.0).normalized()) == doctest::Approx(1.0).epsilon(1e-12));
  const std::vector<Vec3> kept = make_fibre(guide, pore, 0.5, 1.0, o, plane_scalp_exit());
  REQUIRE(kept.size() == 8);
  CHECK(kept.front() == pore);
  for (const Vec3& p : kept) CHECK(p.y() >= 0.0);
}

TEST_CASE("smooth_along: the ¼ ½ ¼ filter keeps what is before `first`, constants and interior lines, and spreads a kink") {
  std::vector<Vec3> v(10);
  for (int k = 0; k < 10; ++k) v[k] = Vec3(k, 2.0, k < 2 ? 7.0 : 0.0);
  std::vector<Vec3> w = v;
  smooth_along(w, 2, 3);
  CHECK(w[0] == v[0]);
  CHECK(w[1] == v[1]);
  for (int k = 2; k < 10; ++k) CHECK(w[k].y() == doctest::Approx(2.0).epsilon(1e-15));
  // x = k is a line: the filter keeps it, up to the end.
  for (int k = 2; k < 10; ++k) CHECK(w[k].x() == doctest::Approx(k).epsilon(1e-14));
  // The step in z at k = 2 (7 before, 0 from there on) decays: after one pass ¼·7 at k = 2.
  std::vector<Vec3> one = v;
  smooth_along(one, 2, 1);
  CHECK(one[2].z() == doctest::Approx(0.25 * 7.0).epsilon(1e-15));
  CHECK(one[3].z() == 0.0);
  // A kink (one value off the line) is spread to its neighbours, its peak lowered to half.
  std::vector<Vec3> kink(9, Vec3::Zero());
  kink[4] = Vec3(0, 0, 1);
  smooth_along(kink, 1, 1);
  CHECK(kink[3].z() == doctest::Approx(0.25).epsilon(1e-15));
  CHECK(kink[4].z() == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(kink[5].z() == doctest::Approx(0.25).epsilon(1e-15));
}
