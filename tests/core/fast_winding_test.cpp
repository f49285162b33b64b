// FastWindingNumber against exact answers: closed meshes (1 inside, 0 outside), a spherical cap
// whose solid angle follows from spherical trigonometry, soups whose winding number decomposes
// into known parts, and the direct sum everywhere (within the estimate's bound).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/fast_winding.h"
#include "core/mesh.h"
#include "core/random.h"
#include "core/shapes.h"

using namespace hairfit;

namespace {

// The cube [-1, 1]³, each side an n×n grid split into triangles, counter-clockwise from outside.
Mesh grid_cube(int n) {
  Mesh m;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = -1; side <= 1; side += 2) {
      // u, v span the side so that u × v points along side·axis.
      Vec3 normal = Vec3::Zero(), u = Vec3::Zero(), v = Vec3::Zero();
      normal[axis] = side;
      u[(axis + 1) % 3] = 1;
      v[(axis + 2) % 3] = side;
      const int base = static_cast<int>(m.positions.size());
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
          m.positions.push_back(normal + (2.0 * i / n - 1) * u + (2.0 * j / n - 1) * v);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const int a = base + j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
          m.triangles.push_back({a, b, c});
          m.triangles.push_back({a, c, d});
        }
    }
  return m;
}

// Torus about the z axis (major radius R, minor r), nu × nv quads split in two, outward.
Mesh torus(double R, double r, int nu, int nv) {
  Mesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      m.positions.push_back(Vec3((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)));
    }
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const int a = i * nv + j, b = ((i + 1) % nu) * nv + j, c = ((i + 1) % nu) * nv + (j + 1) % nv,
                d = i * nv + (j + 1) % nv;
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  return m;
}

// Solid angle of n spherical triangles, each with two sides of arc θ about an apex angle 2π/n:
// a regular spherical n-gon of circumradius θ. Spherical excess from two sides a = b = θ and the
// included angle C: tan(E/2) = tan(a/2) tan(b/2) sin C / (1 + tan(a/2) tan(b/2) cos C).
double regular_polygon_solid_angle(double theta, int n) {
  const double t2 = std::pow(std::tan(theta / 2), 2), c = 2 * M_PI / n;
  return n * 2 * std::atan2(t2 * std::sin(c), 1 + t2 * std::cos(c));
}

// The exact winding number of spherical_cap(theta0, ·, n) at (0, 0, z), z ≠ cos θ0, z ≠ 1. All
// rim vertices lie in the plane z = cos θ0 on a circle of radius sin θ0, so the cap and the flat
// rim polygon (oriented alike) differ by a closed surface: their winding numbers agree outside
// the lens between them and differ by 1 inside. From the axis, at distance |H| from the plane,
// the polygon's fan of triangles about its centre projects to a regular spherical n-gon of
// circumradius atan(sin θ0/|H|), seen from behind (positive) below the plane.
double cap_winding_on_axis(double theta0, int n, double z) {
  const double h = std::cos(theta0) - z;
  const double disk = (h > 0 ? 1 : -1) * regular_polygon_solid_angle(std::atan(std::sin(theta0) / std::fabs(h)), n) / (4 * M_PI);
  return disk + ((z > std::cos(theta0) && z < 1) ? 1.0 : 0.0);
}

Mesh inverted(Mesh m) {
  for (Vec3i& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

Mesh subset(const Mesh& m, const std::function<bool(const Vec3&)>& keep_centroid) {
  Mesh out{m.positions, {}};
  for (const Vec3i& t : m.triangles)
    if (keep_centroid((m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) / 3)) out.triangles.push_back(t);
  return out;
}

Vec3 random_in_box(Random& r, const Vec3& lo, const Vec3& hi) {
  return Vec3(r.uniform(lo.x(), hi.x()), r.uniform(lo.y(), hi.y()), r.uniform(lo.z(), hi.z()));
}

// A point on a random triangle of the mesh, moved along its normal by up to ±offset.
Vec3 random_near_surface(Random& r, const Mesh& m, double offset) {
  const int t = static_cast<int>(r.below(m.triangles.size()));
  double s = r.uniform(), u = r.uniform();
  if (s + u > 1) s = 1 - s, u = 1 - u;
  const Vec3i& f = m.triangles[t];
  const Vec3 a = m.positions[f[0]], b = m.positions[f[1]], c = m.positions[f[2]];
  return a + s * (b - a) + u * (c - a) + r.uniform(-offset, offset) * triangle_normal(m, t);
}

double longest_side(const Mesh& m) {
  const auto [lo, hi] = bounding_box(m);
  return (hi - lo).maxCoeff();
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// `count` random triangles in a row along x (a single leaf for up to 8), the mean of their
// vertices and the farthest vertex's distance from it.
struct Cluster {
  Mesh mesh;
  Vec3 centre = Vec3::Zero();
  double radius = 0;
};
Cluster random_cluster(Random& r, int count) {
  Cluster c;
  for (int t = 0; t < count; ++t) {
    const Vec3 offset(0.3 * t, 0, 0);
    for (int v = 0; v < 3; ++v) c.mesh.positions.push_back(offset + Vec3(r.normal(), r.normal(), r.normal()) / count);
    c.mesh.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  for (const Vec3& v : c.mesh.positions) c.centre += v / static_cast<double>(c.mesh.positions.size());
  for (const Vec3& v : c.mesh.positions) c.radius = std::max(c.radius, (v - c.centre).norm());
  return c;
}

}  // namespace

TEST_CASE("closed meshes: 1 inside, 0 outside, -1 inside an inward copy; above(p, 0.5) exact") {
  struct Case {
    std::string name;
    Mesh mesh;
    // +1 inside, -1 outside, 0 too close to the surface (within 0.05 × size) to test
    std::function<int(const Vec3&)> side;
  };
  const double cube_margin = 0.05 * 2, sphere_margin = 0.05 * 2, torus_margin = 0.05 * 2.8;
  const std::vector<Case> cases = {
      // The icosphere's faces lie within 0.01 of the unit sphere at level 3.
      {"icosphere", icosphere(3, 1.0),
       [&](const Vec3& p) { return p.norm() < 0.99 - sphere_margin ? 1 : p.norm() > 1 + sphere_margin ? -1 : 0; }},
      {"cube", grid_cube(12),
       [&](const Vec3& p) {
         const double m = p.cwiseAbs().maxCoeff();
         return m < 1 - cube_margin ? 1 : m > 1 + cube_margin ? -1 : 0;
       }},
      // The polygonal torus lies within 0.004 inside the smooth one (its chords' sagitta).
      {"torus", torus(1.0, 0.4, 48, 24),
       [&](const Vec3& p) {
         const double q = std::hypot(std::hypot(p.x(), p.y()) - 1.0, p.z());
         return q < 0.4 - 0.004 - torus_margin ? 1 : q > 0.4 + torus_margin ? -1 : 0;
       }},
  };
  for (const Case& c : cases) {
    const FastWindingNumber fast(c.mesh), inward(inverted(c.mesh));
    const auto [lo, hi] = bounding_box(c.mesh);
    Random r(7, RandomStage::test, 0);
    int inside = 0, outside = 0;
    double max_error = 0, max_bound = 0;
    while (inside + outside < 600) {
      const Vec3 p = random_in_box(r, 1.5 * lo, 1.5 * hi);
      const int side = c.side(p);
      if (side == 0) continue;
      const double exact = side > 0 ? 1.0 : 0.0;
      (side > 0 ? inside : outside)++;
      CHECK(std::fabs(fast.direct(p) - exact) < 1e-12);
      const WindingEstimate e = fast.estimate(p), back = inward.estimate(p);
      CHECK(std::fabs(e.value - exact) <= e.error_bound);
      CHECK(std::fabs(back.value + exact) <= back.error_bound);
      CHECK(fast.above(p, 0.5) == (side > 0));
      CHECK(inward.above(p, -0.5) == (side < 0));
      max_error = std::max(max_error, std::fabs(e.value - exact));
      max_bound = std::max(max_bound, e.error_bound);
    }
    CHECK(inside > 50);
    CHECK(outside > 50);
    MESSAGE(c.name << " (" << c.mesh.triangles.size() << " triangles), beta 2, at least 0.05 × size off the surface: max |fast − exact| "
                   << max_error << ", max error bound " << max_bound);
    CHECK(max_error < 0.1);  // order 2 at beta = 2: a few 1e-2 near the surface, far less away
  }
}

TEST_CASE("a spherical cap: exact solid angle at the centre and on the axis, second-order convergence") {
  for (double theta0 : {1.0, 2.0}) {
    CAPTURE(theta0);
    const double smooth = (1 - std::cos(theta0)) / 2;  // the smooth cap's solid angle over 4π
    double previous_deficit = 0;
    for (int sectors : {32, 64, 128}) {
      const Mesh cap = spherical_cap(theta0, sectors / 2, sectors);
      const FastWindingNumber fast(cap);
      // The flat triangles' vertices lie on the sphere, so from its centre they tile the regular
      // spherical polygon on the rim vertices.
      const double polygon = regular_polygon_solid_angle(theta0, sectors) / (4 * M_PI);
      CHECK(std::fabs(fast.direct(Vec3::Zero()) - polygon) < 1e-12);
      CHECK(std::fabs(winding_number(cap, Vec3::Zero()) - polygon) < 1e-12);
      // The great-circle arcs between rim vertices bow towards the nearer pole: the polygon is
      // smaller than the smooth cap short of the equator and larger beyond it.
      const double deficit = smooth - polygon;
      CHECK((deficit > 0) == (theta0 < M_PI / 2));
      if (previous_deficit > 0) CHECK(previous_deficit / deficit == doctest::Approx(4.0).epsilon(0.01));
      previous_deficit = deficit;

      for (double z : {-3.0, -1.0, -0.4, 0.3, 0.7, 0.95, 1.05, 1.5, 4.0}) {
        CAPTURE(z);
        const Vec3 p(0, 0, z);
        const double exact = cap_winding_on_axis(theta0, sectors, z);
        CHECK(std::fabs(fast.direct(p) - exact) < 1e-12);
        const WindingEstimate e = fast.estimate(p);
        CHECK(std::fabs(e.value - exact) <= e.error_bound);
      }
      Random r(11, RandomStage::test, static_cast<std::uint64_t>(sectors));
      for (int i = 0; i < 300; ++i) {
        const Vec3 p = i % 2 ? random_in_box(r, Vec3::Constant(-2), Vec3::Constant(2)) : random_near_surface(r, cap, 0.05);
        const WindingEstimate e = fast.estimate(p);
        CHECK(std::fabs(e.value - fast.direct(p)) <= e.error_bound);
      }
    }
  }
}

TEST_CASE("soups: duplicates, a hole, a flipped patch and a fin decompose into known parts") {
  const Mesh sphere = icosphere(3, 1.0);
  const auto inside = [](const Vec3& p) { return p.norm() < 0.95 ? 1.0 : 0.0; };  // faces lie beyond 0.99
  const auto removed = [](const Vec3& g) { return g.x() > 0.8; };
  const auto flipped = [](const Vec3& g) { return g.y() > 0.75; };

  Mesh doubled = sphere;
  doubled.triangles.insert(doubled.triangles.end(), sphere.triangles.begin(), sphere.triangles.end());
  const Mesh holed = subset(sphere, [&](const Vec3& g) { return !removed(g); });
  const Mesh hole_faces = subset(sphere, removed);
  Mesh patched = sphere;
  for (Vec3i& t : patched.triangles)
    if (flipped((sphere.positions[t[0]] + sphere.positions[t[1]] + sphere.positions[t[2]]) / 3)) std::swap(t[1], t[2]);
  const Mesh patch = subset(sphere, flipped);
  // A fin: a triangle on an edge of the sphere, reaching out of it (a non-manifold edge).
  Mesh finned = sphere;
  Mesh fin{sphere.positions, {}};
  {
    const Vec3i e = sphere.triangles[0];
    finned.positions.push_back(1.8 * (sphere.positions[e[0]] + sphere.positions[e[1]]) / 2);
    fin.positions = finned.positions;
    const Vec3i t(e[0], e[1], static_cast<int>(finned.positions.size()) - 1);
    finned.triangles.push_back(t);
    fin.triangles.push_back(t);
  }

  struct Case {
    std::string name;
    const Mesh& mesh;
    std::function<double(const Vec3&)> exact;
  };
  const std::vector<Case> cases = {
      {"doubled", doubled, [&](const Vec3& p) { return 2 * inside(p); }},
      {"holed", holed, [&](const Vec3& p) { return inside(p) - winding_number(hole_faces, p); }},
      {"flipped patch", patched, [&](const Vec3& p) { return inside(p) - 2 * winding_number(patch, p); }},
      {"fin", finned, [&](const Vec3& p) { return inside(p) + winding_number(fin, p); }},
  };
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const FastWindingNumber fast(c.mesh);
    CHECK(fast.size() == c.mesh.triangles.size());
    Random r(13, RandomStage::test, 0);
    std::vector<Vec3> points = {Vec3::Zero(), Vec3(0.3, -0.2, 0.1), Vec3(0, 0, 2.5), Vec3(1.5, 0.1, 0)};
    while (points.size() < 400) {
      const Vec3 p = random_in_box(r, Vec3::Constant(-2), Vec3::Constant(2));
      if (std::fabs(p.norm() - 1) > 0.05) points.push_back(p);
    }
    for (const Vec3& p : points) {
      const double exact = c.exact(p), direct = fast.direct(p);
      CHECK(std::fabs(direct - exact) < 1e-12);
      const WindingEstimate e = fast.estimate(p);
      CHECK(std::fabs(e.value - direct) <= e.error_bound);
      for (double threshold : {0.5, 1.5})
        CHECK(fast.above(p, threshold) == (direct > threshold));
    }
  }
}

TEST_CASE("random points near and far: |fast − direct| within the bound, above() as the direct sum decides") {
  Mesh bumpy = icosphere(4, 1.0);
  for (Vec3& p : bumpy.positions) p *= 1 + 0.1 * std::sin(5 * p.x()) * std::cos(3 * p.y() + p.z());
  const Mesh open_cap = spherical_cap(1.2, 20, 48);
  Mesh messy = subset(icosphere(3, 1.0), [](const Vec3& g) { return g.x() < 0.8; });
  for (Vec3i& t : messy.triangles)
    if (messy.positions[t[0]].y() > 0.75) std::swap(t[1], t[2]);

  for (const Mesh* mesh : std::vector<const Mesh*>{&bumpy, &open_cap, &messy}) {
    const double size = longest_side(*mesh);
    const auto [lo, hi] = bounding_box(*mesh);
    std::vector<Vec3> points;
    Random r(17, RandomStage::test, mesh->triangles.size());
    for (int i = 0; i < 1500; ++i) {
      switch (i % 5) {
        case 0: points.push_back(random_in_box(r, lo - size * Vec3::Ones(), hi + size * Vec3::Ones())); break;
        case 1: points.push_back(10 * size * Vec3(r.normal(), r.normal(), r.normal())); break;
        case 2: points.push_back(random_near_surface(r, *mesh, 0.02 * size)); break;
        case 3: points.push_back(random_near_surface(r, *mesh, 1e-9 * size)); break;
        default: {  // on the surface: a vertex, or a triangle's centroid
          const Vec3i& t = mesh->triangles[r.below(mesh->triangles.size())];
          points.push_back(i % 2 ? mesh->positions[t[0]]
                                 : Vec3((mesh->positions[t[0]] + mesh->positions[t[1]] + mesh->positions[t[2]]) / 3));
        }
      }
    }
    for (double beta : {1.5, 2.0, 3.0}) {
      const FastWindingNumber fast(*mesh, beta);
      double max_error = 0, max_bound = 0;
      int violations = 0, disagreements = 0;
      for (const Vec3& p : points) {
        const WindingEstimate e = fast.estimate(p);
        const double direct = fast.direct(p), error = std::fabs(e.value - direct);
        violations += !(error <= e.error_bound);
        max_error = std::max(max_error, error);
        max_bound = std::max(max_bound, e.error_bound);
        for (double threshold : {0.5, 0.25, -0.5}) disagreements += fast.above(p, threshold) != (direct > threshold);
      }
      CHECK(violations == 0);
      CHECK(disagreements == 0);
      MESSAGE(mesh->triangles.size() << " triangles, beta " << beta << ": max |fast − direct| " << max_error
                                     << ", max error bound " << max_bound << " over " << points.size() << " points");
      if (beta == 2.0) CHECK(max_error < 0.1);
    }
  }
}

TEST_CASE("the bound holds where it is tightest, within a factor of a few of the actual error") {
  // Single random triangles and clusters of 8 (one leaf, so the root's expansion serves), seen
  // from just beyond beta × radius, where the truncation error is largest relative to the bound.
  Random r(23, RandomStage::test, 0);
  for (double beta : {1.01, 1.5, 2.0, 4.0}) {
    double worst = 0;
    int violations = 0;
    for (int k = 0; k < 4000; ++k) {
      const Cluster cluster = random_cluster(r, k % 2 ? 1 : 8);
      const FastWindingNumber fast(cluster.mesh, beta);
      const Vec3& centre = cluster.centre;
      const double radius = cluster.radius;
      const Vec3 direction = Vec3(r.normal(), r.normal(), r.normal()).normalized();
      for (double s : {1.5, 1.6, 2.0, 3.0, 6.0}) {
        const Vec3 p = centre + s * beta * radius * direction;
        const WindingEstimate e = fast.estimate(p);
        const double error = std::fabs(e.value - fast.direct(p));
        violations += !(error <= e.error_bound);
        if (e.error_bound > 0) worst = std::max(worst, error / e.error_bound);
      }
    }
    CAPTURE(beta);
    CHECK(violations == 0);
    CHECK(worst > 0.25);
  }
}

namespace {

// Random cards: n rectangles of two triangles each, of random size and orientation in [-1, 1]³,
// every fifth one turned the other way (an open, unwelded, overlapping soup, as card hair is).
Mesh random_cards(Random& r, int n) {
  Mesh m;
  for (int k = 0; k < n; ++k) {
    const Vec3 centre = random_in_box(r, Vec3::Constant(-1), Vec3::Constant(1));
    const Vec3 u = r.uniform(0.1, 0.8) * Vec3(r.normal(), r.normal(), r.normal()).normalized();
    Vec3 v = Vec3(r.normal(), r.normal(), r.normal()).cross(u).normalized() * r.uniform(0.05, 0.3);
    const int base = static_cast<int>(m.positions.size());
    for (const Vec3& x : {Vec3(centre - u - v), Vec3(centre + u - v), Vec3(centre + u + v), Vec3(centre - u + v)}) m.positions.push_back(x);
    if (k % 5 == 4) {
      m.triangles.push_back({base, base + 2, base + 1});
      m.triangles.push_back({base, base + 3, base + 2});
    } else {
      m.triangles.push_back({base, base + 1, base + 2});
      m.triangles.push_back({base, base + 2, base + 3});
    }
  }
  return m;
}

// An s×s×s lattice of points filling the cube of side `side` about `centre`.
std::vector<Vec3> lattice_box(const Vec3& centre, double side, int s) {
  std::vector<Vec3> points;
  for (int k = 0; k < s; ++k)
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) points.push_back(centre + side * (Vec3(i, j, k) / (s - 1) - Vec3::Constant(0.5)));
  return points;
}

}  // namespace

TEST_CASE("estimate_box: within its bound of the direct sum at every point of random boxes near random card soups") {
  Random r(31, RandomStage::test, 0);
  int boxes = 0, points_checked = 0, violations = 0, decided = 0;
  double worst = 0;
  for (int soup = 0; soup < 6; ++soup) {
    const Mesh cards = random_cards(r, 20 + 40 * soup);
    const FastWindingNumber fast(cards, 1.5);
    for (int b = 0; b < 40; ++b) {
      // Boxes of 4³ lattice points, from a hundredth to half the soup's size, centred anywhere
      // from on a card to well away from the soup; and the same points shuffled with random ones.
      const double side = std::pow(10.0, r.uniform(-2.0, -0.3));
      const Vec3 centre = b % 2 ? random_near_surface(r, cards, 0.1) : random_in_box(r, Vec3::Constant(-1.5), Vec3::Constant(1.5));
      std::vector<Vec3> points = lattice_box(centre, side, 4);
      for (int extra = 0; extra < 8; ++extra)
        points.push_back(random_in_box(r, centre - 0.5 * side * Vec3::Ones(), centre + 0.5 * side * Vec3::Ones()));
      ++boxes;
      for (double beta : {1.5, 2.0, 4.0}) {
        std::vector<WindingEstimate> e;
        fast.estimate_box(points, beta, e);
        REQUIRE(e.size() == points.size());
        for (std::size_t q = 0; q < points.size(); ++q) {
          const double error = std::fabs(e[q].value - fast.direct(points[q]));
          violations += !(error <= e[q].error_bound);
          if (e[q].error_bound > 0) worst = std::max(worst, error / e[q].error_bound);
          decided += std::fabs(e[q].value - 0.5) > e[q].error_bound;
          ++points_checked;
        }
      }
    }
  }
  MESSAGE(boxes << " boxes, " << points_checked << " estimates, " << decided << " decide ½; worst error/bound " << worst);
  CHECK(violations == 0);
  CHECK(decided > points_checked / 2);  // the bound is of use: most estimates decide w > ½
}

TEST_CASE("estimate_box: a box's linear expansion where its bound is tightest, and exact answers") {
  // Clusters of 8 random triangles (one leaf, whose expansion serves the whole box), seen from
  // just beyond beta × (radius + the box's radius): the bound holds, within a factor of the error.
  Random r(37, RandomStage::test, 0);
  for (double beta : {1.5, 2.0, 4.0}) {
    double worst = 0;
    int violations = 0;
    for (int k = 0; k < 1000; ++k) {
      const Cluster cluster = random_cluster(r, 8);
      const FastWindingNumber fast(cluster.mesh, beta);
      const Vec3& centre = cluster.centre;
      const double radius = cluster.radius;
      const Vec3 direction = Vec3(r.normal(), r.normal(), r.normal()).normalized();
      const double box_radius = radius * r.uniform(0.1, 2.0);
      for (double s : {1.1, 1.5, 3.0}) {
        // A box of points within box_radius of its centre (its corners on the sphere).
        const Vec3 c = centre + s * beta * (radius + box_radius) * direction;
        std::vector<Vec3> points = lattice_box(c, 2 * box_radius / std::sqrt(3.0), 3);
        std::vector<WindingEstimate> e;
        fast.estimate_box(points, beta, e);
        for (std::size_t q = 0; q < points.size(); ++q) {
          const double error = std::fabs(e[q].value - fast.direct(points[q]));
          violations += !(error <= e[q].error_bound);
          if (e[q].error_bound > 0) worst = std::max(worst, error / e[q].error_bound);
        }
      }
    }
    MESSAGE("beta " << beta << ": worst error/bound " << worst);
    CHECK(violations == 0);
    CHECK(worst > 0.1);
  }
  // Exact: a closed icosphere's winding number is 1 inside, 0 outside; a spherical cap's on its
  // axis follows from spherical trigonometry.
  const Mesh sphere = icosphere(3, 1.0);
  const FastWindingNumber closed(sphere, 2.0);
  for (const auto& [c, w] : {std::pair{Vec3(0.1, 0.0, -0.2), 1.0}, std::pair{Vec3(2.5, 1.0, 0.0), 0.0}}) {
    const std::vector<Vec3> points = lattice_box(c, 0.4, 4);
    std::vector<WindingEstimate> e;
    closed.estimate_box(points, 2.0, e);
    for (const WindingEstimate& x : e) CHECK(std::fabs(x.value - w) <= x.error_bound);
  }
  const double theta0 = 1.0;
  const int sectors = 64;
  const Mesh cap = spherical_cap(theta0, sectors / 2, sectors);
  const FastWindingNumber fast_cap(cap);
  std::vector<Vec3> axis;
  for (double z : {-3.0, -2.5, -2.0, 2.0, 2.5, 3.0, 3.5, 4.0}) axis.push_back(Vec3(0, 0, z));
  for (std::size_t from = 0; from < axis.size(); from += 4) {
    const std::vector<Vec3> points(axis.begin() + from, axis.begin() + from + 4);
    std::vector<WindingEstimate> e;
    fast_cap.estimate_box(points, 2.0, e);
    for (std::size_t q = 0; q < points.size(); ++q) {
      CAPTURE(points[q].z());
      CHECK(std::fabs(e[q].value - cap_winding_on_axis(theta0, sectors, points[q].z())) <= e[q].error_bound);
    }
  }
}

TEST_CASE("zero-area and duplicate-vertex triangles never give NaN; an empty mesh gives 0") {
  Mesh m = icosphere(2, 1.0);
  const Vec3i e = m.triangles[3];
  m.triangles.push_back({e[0], e[0], e[1]});  // a repeated index
  m.positions.push_back(0.5 * (m.positions[e[0]] + m.positions[e[1]]));
  const int mid = static_cast<int>(m.positions.size()) - 1;
  m.triangles.push_back({e[0], mid, e[1]});  // collinear
  m.positions.push_back(m.positions[e[2]]);  // a duplicated vertex, used by a copy of a triangle
  m.triangles.push_back({e[0], e[1], static_cast<int>(m.positions.size()) - 1});
  m.triangles.push_back({e[2], e[2], e[2]});  // a point

  const FastWindingNumber fast(m);
  CHECK(fast.size() == m.triangles.size());
  std::vector<Vec3> points = {m.positions[e[0]], m.positions[e[2]], m.positions[mid],
                              0.25 * m.positions[e[0]] + 0.75 * m.positions[e[1]], Vec3::Zero()};
  for (const Vec3& p : m.positions) points.push_back(p);
  for (const Vec3& p : points) {
    const WindingEstimate est = fast.estimate(p);
    CHECK_FALSE(std::isnan(est.value));
    CHECK_FALSE(std::isnan(est.error_bound));
    CHECK_FALSE(std::isnan(fast(p)));
    CHECK_FALSE(std::isnan(fast.direct(p)));
    (void)fast.above(p, 0.5);
  }
  // Off the surface the degenerate triangles add nothing.
  for (const Vec3& p : {Vec3(0.1, 0.2, -0.1), Vec3(2, 1, 0)})
    CHECK(std::fabs(fast.direct(p) - winding_number(m, p)) < 1e-12);

  Mesh degenerate;
  degenerate.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  degenerate.triangles = {{0, 1, 2}, {0, 0, 1}, {2, 2, 2}};
  for (const Mesh& nothing : {Mesh{}, degenerate}) {
    const FastWindingNumber none(nothing);
    CHECK(none.size() == nothing.triangles.size());
    for (const Vec3& p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.3, -2)}) {
      CHECK(none(p) == 0.0);
      CHECK(none.estimate(p).error_bound == 0.0);
      CHECK(none.direct(p) == 0.0);
      CHECK_FALSE(none.above(p, 0.5));
      CHECK(none.above(p, -0.5));
    }
  }
  CHECK_THROWS_AS(FastWindingNumber(m, 1.0), std::invalid_argument);
}

TEST_CASE("deterministic: the same bits in any order, on any thread; operator() is estimate().value") {
  const FastWindingNumber fast(torus(1.0, 0.4, 40, 20));
  Random r(19, RandomStage::test, 0);
  std::vector<Vec3> points(2000);
  for (Vec3& p : points) p = random_in_box(r, Vec3::Constant(-1.6), Vec3::Constant(1.6));
  std::vector<double> forward(points.size()), backward(points.size()), threaded(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) forward[i] = fast(points[i]);
  for (std::size_t i = points.size(); i-- > 0;) backward[i] = fast(points[i]);
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t)
    threads.emplace_back([&, t] {
      for (std::size_t i = t; i < points.size(); i += 2) threaded[i] = fast(points[i]);
    });
  for (std::thread& t : threads) t.join();
  int differ = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    differ += !same_bits(forward[i], backward[i]) || !same_bits(forward[i], threaded[i]) ||
              !same_bits(forward[i], fast.estimate(points[i]).value);
  CHECK(differ == 0);
}

TEST_CASE("a tree built on several threads is the tree built on one: the same bits everywhere") {
  // Large enough that the top levels hand whole subtrees to the threads (1/16 of the triangles).
  const Mesh mesh = torus(1.0, 0.4, 160, 60);
  const FastWindingNumber one(mesh, 2.0, 1), four(mesh, 2.0, 4);
  Random r(23, RandomStage::test, 0);
  int differ = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 p = random_in_box(r, Vec3::Constant(-1.6), Vec3::Constant(1.6));
    const WindingEstimate a = one.estimate(p), b = four.estimate(p);
    differ += !same_bits(a.value, b.value) || !same_bits(a.error_bound, b.error_bound) ||
              !same_bits(one.direct(p), four.direct(p));
  }
  CHECK(differ == 0);
}
