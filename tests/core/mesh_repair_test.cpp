#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "core/mesh_repair.h"
#include "core/shapes.h"

using namespace hairfit;

namespace {

bool same_mesh(const Mesh& a, const Mesh& b) { return a.positions == b.positions && a.triangles == b.triangles; }

// The triangles sharing an edge with triangle t.
std::vector<int> neighbours(const Mesh& m, int t) {
  std::vector<int> out;
  for (int u = 0; u < static_cast<int>(m.triangles.size()); ++u) {
    int shared = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) shared += m.triangles[t][i] == m.triangles[u][j];
    if (u != t && shared == 2) out.push_back(u);
  }
  return out;
}

// The first `count` triangles reached from triangle `seed` across edges, breadth first.
std::vector<int> grow(const Mesh& m, int seed, int count) {
  std::vector<int> region{seed};
  for (std::size_t i = 0; i < region.size() && static_cast<int>(region.size()) < count; ++i)
    for (int u : neighbours(m, region[i]))
      if (std::find(region.begin(), region.end(), u) == region.end() && static_cast<int>(region.size()) < count)
        region.push_back(u);
  return region;
}

void flip(Mesh& m, const std::vector<int>& triangles) {
  for (int t : triangles) std::swap(m.triangles[t][1], m.triangles[t][2]);
}

// Each triangle with its own three copies of its vertices, copy i moved by i·step.
Mesh soup(const Mesh& m, const Vec3& step = Vec3::Zero()) {
  Mesh s;
  for (const Vec3i& t : m.triangles) {
    const int base = static_cast<int>(s.positions.size());
    for (int k = 0; k < 3; ++k) s.positions.push_back(m.positions[t[k]] + (base + k) * step);
    s.triangles.emplace_back(base, base + 1, base + 2);
  }
  return s;
}

// A flat card: an n×1 strip of unit squares at height z, two triangles each.
void add_card(Mesh& m, int n, double z) {
  const int base = static_cast<int>(m.positions.size());
  for (int i = 0; i <= n; ++i) {
    m.positions.emplace_back(3 + i, 0, z);
    m.positions.emplace_back(3 + i, 1, z);
  }
  for (int i = 0; i < n; ++i) {
    const int a = base + 2 * i;
    m.triangles.emplace_back(a, a + 2, a + 3);
    m.triangles.emplace_back(a, a + 3, a + 1);
  }
}

double perimeter(const Mesh& m, int t) {
  const Vec3i& f = m.triangles[t];
  return (m.positions[f[1]] - m.positions[f[0]]).norm() + (m.positions[f[2]] - m.positions[f[1]]).norm() +
         (m.positions[f[0]] - m.positions[f[2]]).norm();
}

}  // namespace

TEST_CASE("a clean icosphere comes back unchanged: closed, one part, no loops") {
  const Mesh sphere = icosphere(2);
  const CleanMesh c = clean_mesh(sphere, 0.0);
  CHECK(same_mesh(c.mesh, sphere));
  CHECK(c.report.closed());
  CHECK(c.report.parts == 1);
  CHECK(c.report.part_triangles == std::vector<int>{320});
  CHECK(c.report.boundary_loops == 0);
  CHECK(c.report.holes == 0);
  CHECK(c.report.welded_vertices == 0);
  CHECK(c.report.duplicate_triangles + c.report.degenerate_triangles == 0);
  CHECK(c.report.flipped_patches == 0);
  CHECK(c.report.misoriented_edges == 0);
  CHECK(c.report.input_vertices == 162);
  CHECK(c.report.input_triangles == 320);
  for (int i = 0; i < 162; ++i) CHECK(c.old_to_new_vertex[i] == i);
}

TEST_CASE("duplicate triangles, either way round, are dropped and counted") {
  const Mesh sphere = icosphere(2);
  Mesh doubled = sphere;
  int added = 0;
  for (int t = 0; t < 320; t += 3) {
    const Vec3i& f = sphere.triangles[t];
    doubled.triangles.push_back(f);
    doubled.triangles.emplace_back(f[0], f[2], f[1]);
    doubled.triangles.emplace_back(f[1], f[2], f[0]);  // the same triangle, started at another corner
    added += 3;
  }
  const CleanMesh c = clean_mesh(doubled, 0.0);
  CHECK(c.report.duplicate_triangles == added);
  CHECK(c.report.degenerate_triangles == 0);
  CHECK(same_mesh(c.mesh, sphere));
  CHECK(c.report.closed());
  CHECK(c.report.nonmanifold_edges == 0);
}

TEST_CASE("a triangle soup welds back to the sphere it came from") {
  const Mesh sphere = icosphere(2);
  const MeshTopology original = analyse_topology(sphere);
  // Exact copies, and copies up to 1.5e-8 apart welded at 1e-6.
  for (const std::pair<double, double>& step_and_tolerance : {std::pair{0.0, 0.0}, std::pair{1e-11, 1e-6}}) {
    const double step = step_and_tolerance.first, tolerance = step_and_tolerance.second;
    CAPTURE(tolerance);
    const Mesh raw = soup(sphere, Vec3(step, -step, 0.5 * step));
    const CleanMesh c = clean_mesh(raw, tolerance);
    CHECK(c.report.welded_vertices == 3 * 320 - 162);
    CHECK(c.mesh.positions.size() == 162);
    const MeshTopology t = analyse_topology(c.mesh);
    CHECK(t.vertices == original.vertices);
    CHECK(t.edges == original.edges);
    CHECK(t.closed());
    CHECK(t.orientation_consistent);
    CHECK(c.report.closed());
    CHECK(c.report.parts == 1);
    // The same triangles as the sphere's: each output vertex is the first copy of one sphere vertex.
    std::map<int, int> sphere_vertex;  // output vertex → sphere vertex
    for (int t3 = 0; t3 < 320; ++t3)
      for (int k = 0; k < 3; ++k) sphere_vertex.emplace(c.old_to_new_vertex[3 * t3 + k], sphere.triangles[t3][k]);
    CHECK(sphere_vertex.size() == 162);
    REQUIRE(c.mesh.triangles.size() == 320);
    for (int t3 = 0; t3 < 320; ++t3)
      for (int k = 0; k < 3; ++k) CHECK(sphere_vertex[c.mesh.triangles[t3][k]] == sphere.triangles[t3][k]);
  }
  // A tolerance below the copies' spacing merges nothing: 320 separate triangles.
  const CleanMesh apart = clean_mesh(soup(sphere, Vec3(1e-6, 0, 0)), 0.9e-6);
  CHECK(apart.report.welded_vertices == 0);
  CHECK(apart.report.parts == 320);
  CHECK(apart.report.boundary_loops == 320);
  CHECK(apart.report.holes == 0);
}

TEST_CASE("two holes in a sphere: two loops, the shorter one a hole") {
  Mesh sphere = icosphere(2);
  const Vec3 a = sphere.positions[sphere.triangles[0][0]];
  // Triangle 0 and, on the far side, a triangle and one of its neighbours.
  int far = 0;
  for (int t = 0; t < 320; ++t)
    if (sphere.positions[sphere.triangles[t][0]].dot(a) < sphere.positions[sphere.triangles[far][0]].dot(a)) far = t;
  const int beside = neighbours(sphere, far)[0];
  const double small_hole = perimeter(sphere, 0);
  std::vector<Vec3i> kept;
  for (int t = 0; t < 320; ++t)
    if (t != 0 && t != far && t != beside) kept.push_back(sphere.triangles[t]);
  sphere.triangles = kept;
  const CleanMesh c = clean_mesh(sphere, 0.0);
  CHECK(c.report.parts == 1);
  CHECK(c.report.boundary_loops == 2);
  CHECK(c.report.holes == 1);
  CHECK(c.report.longest_hole == doctest::Approx(small_hole));
  CHECK_FALSE(c.report.closed());
  CHECK(analyse_topology(c.mesh).boundary_loops.size() == 2);
}

TEST_CASE("a flipped patch is turned back; so is a patch when the rest is the flipped part") {
  const Mesh sphere = icosphere(2);
  const std::vector<int> patch = grow(sphere, 17, 5);
  REQUIRE(patch.size() == 5);
  Mesh raw = sphere;
  flip(raw, patch);
  REQUIRE_FALSE(analyse_topology(raw).orientation_consistent);
  const CleanMesh c = clean_mesh(raw, 0.0);
  CHECK(c.report.flipped_patches == 1);
  CHECK(c.report.flipped_triangles == 5);
  CHECK(c.report.misoriented_edges == 0);
  CHECK(analyse_topology(c.mesh).orientation_consistent);
  CHECK(same_mesh(c.mesh, sphere));

  // The other 315 triangles turned instead: they cover more area, so the 5 follow them and the
  // whole sphere comes out inside out.
  std::vector<int> rest;
  for (int t = 0; t < 320; ++t)
    if (std::find(patch.begin(), patch.end(), t) == patch.end()) rest.push_back(t);
  Mesh mostly_flipped = sphere;
  flip(mostly_flipped, rest);
  const CleanMesh d = clean_mesh(mostly_flipped, 0.0);
  CHECK(d.report.flipped_patches == 1);
  CHECK(d.report.flipped_triangles == 5);
  CHECK(analyse_topology(d.mesh).orientation_consistent);
  Mesh inside_out = sphere;
  std::vector<int> all(320);
  std::iota(all.begin(), all.end(), 0);
  flip(inside_out, all);
  CHECK(same_mesh(d.mesh, inside_out));
}

TEST_CASE("equal areas either way: the region's first triangle keeps its winding") {
  // Two unit squares side by side, wound against each other: the first stays, the second turns.
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
  m.triangles = {{0, 1, 4}, {0, 4, 3}, {1, 5, 2}, {1, 4, 5}};  // the second square clockwise
  const CleanMesh c = clean_mesh(m, 0.0);
  CHECK(c.report.flipped_patches == 1);
  CHECK(c.report.flipped_triangles == 2);
  CHECK(c.mesh.triangles == std::vector<Vec3i>{{0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}});
  CHECK(c.report.boundary_loops == 1);
  CHECK(c.report.holes == 0);
}

TEST_CASE("three triangles on one edge: one non-manifold edge, nothing flipped") {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const CleanMesh c = clean_mesh(m, 0.0);
  CHECK(c.report.nonmanifold_edges == 1);
  CHECK(c.report.parts == 1);
  CHECK(c.report.flipped_patches == 0);
  CHECK(same_mesh(c.mesh, m));
  CHECK_FALSE(c.report.closed());
  CHECK(c.report.boundary_loops >= 1);
}

TEST_CASE("two tetrahedra on one edge, one inside out: left as they are") {
  // Patches joined only through a non-manifold edge have no defined agreement.
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0.2}, {0.5, 0.3, 1}, {0.5, -1, 0.2}, {0.5, -0.3, -1}};
  const auto tetrahedron = [&](int a, int b, int c, int d) {  // outward when a, b, c is counter-clockwise from d
    m.triangles.insert(m.triangles.end(), {Vec3i(a, c, b), Vec3i(a, b, d), Vec3i(b, c, d), Vec3i(c, a, d)});
  };
  tetrahedron(0, 1, 2, 3);
  tetrahedron(1, 0, 4, 5);  // wound the other way round from the first
  const CleanMesh c = clean_mesh(m, 0.0);
  CHECK(c.report.nonmanifold_edges == 1);
  CHECK(c.report.parts == 1);
  CHECK(c.report.boundary_loops == 0);
  CHECK(c.report.flipped_patches == 0);
  CHECK(c.report.misoriented_edges == 0);
  CHECK(same_mesh(c.mesh, m));
  CHECK_FALSE(c.report.closed());
}

TEST_CASE("a Möbius strip: one loop, an edge left misoriented") {
  Mesh m;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double angle = 2 * M_PI * i / n;
    const Vec3 radial(std::cos(angle), std::sin(angle), 0);
    const Vec3 across = 0.3 * (std::cos(angle / 2) * radial + std::sin(angle / 2) * Vec3::UnitZ());
    m.positions.push_back(3 * radial + across);
    m.positions.push_back(3 * radial - across);
  }
  for (int i = 0; i < n; ++i) {
    const int top = 2 * i, bottom = 2 * i + 1;
    // After a full turn the strip's top edge comes back as its bottom edge.
    const int next_top = i + 1 < n ? top + 2 : 1, next_bottom = i + 1 < n ? bottom + 2 : 0;
    m.triangles.emplace_back(top, bottom, next_bottom);
    m.triangles.emplace_back(top, next_bottom, next_top);
  }
  const CleanMesh c = clean_mesh(m, 0.0);
  CHECK(c.report.parts == 1);
  CHECK(c.report.boundary_loops == 1);
  CHECK(c.report.misoriented_edges == 1);
  CHECK(c.report.flipped_patches == 0);
}

TEST_CASE("zero-area triangles are dropped and counted") {
  const Mesh sphere = icosphere(1);
  Mesh raw = sphere;
  const int n = static_cast<int>(raw.positions.size());
  raw.positions.push_back(raw.positions[0]);  // an exact copy of vertex 0
  raw.positions.insert(raw.positions.end(), {{5, 0, 0}, {6, 0, 0}, {7, 0, 0}});
  raw.triangles.emplace_back(n + 1, n + 3, n + 2);  // collinear
  raw.triangles.emplace_back(1, 1, 2);              // a repeated vertex
  raw.triangles.emplace_back(n, 0, 3);              // a repeated vertex once welded
  const CleanMesh c = clean_mesh(raw, 0.0);
  CHECK(c.report.degenerate_triangles == 3);
  CHECK(c.report.welded_vertices == 1);
  CHECK(same_mesh(c.mesh, sphere));  // the extra vertices are used by dropped triangles only
  CHECK(c.old_to_new_vertex[n] == 0);
  CHECK(c.old_to_new_vertex[n + 1] == -1);
  CHECK(c.report.closed());

  // The rule: height over the longest edge at most 1e-12 of it.
  Mesh slivers;
  slivers.positions = {{0, 0, 0}, {2, 0, 0}, {1, 2e-13, 0}, {0, 0, 1}, {2, 0, 1}, {1, 4e-12, 1}};
  slivers.triangles = {{0, 1, 2}, {3, 4, 5}};
  const CleanMesh s = clean_mesh(slivers, 0.0);
  CHECK(s.report.degenerate_triangles == 1);
  CHECK(s.mesh.triangles.size() == 1);
  CHECK(s.mesh.positions[s.mesh.triangles[0][2]].z() == 1.0);
}

TEST_CASE("a shell and loose cards: parts counted, largest first") {
  Mesh m;
  add_card(m, 1, 0.0);   // 2 triangles
  const Mesh sphere = icosphere(2);
  const int base = static_cast<int>(m.positions.size());
  m.positions.insert(m.positions.end(), sphere.positions.begin(), sphere.positions.end());
  for (const Vec3i& t : sphere.triangles) m.triangles.emplace_back(t + Vec3i::Constant(base));
  add_card(m, 2, 0.5);   // 4 triangles
  add_card(m, 1, 1.0);   // 2 triangles
  const CleanMesh c = clean_mesh(m, 0.0);
  CHECK(c.report.parts == 4);
  CHECK(c.report.part_triangles == std::vector<int>{320, 4, 2, 2});
  CHECK(c.report.boundary_loops == 3);
  CHECK(c.report.holes == 0);
  CHECK(c.report.nonmanifold_edges == 0);
  CHECK_FALSE(c.report.closed());
  CHECK(same_mesh(c.mesh, m));
  CHECK(describe(c.report) ==
        "4 parts (320, 4, 2, 2 triangles), 3 boundary loops (3 rims), 0 holes, 0 non-manifold edges, "
        "0 flipped patches, 0 welded vertices, 0 duplicate and 0 zero-area triangles dropped");
}

TEST_CASE("describe: singulars, holes, flips and the parts beyond the eighth") {
  MeshReport r;
  r.parts = 1;
  r.part_triangles = {1};
  r.boundary_loops = 1;
  r.nonmanifold_edges = 1;
  r.flipped_patches = 1;
  r.flipped_triangles = 1;
  r.welded_vertices = 1;
  r.duplicate_triangles = 1;
  r.degenerate_triangles = 1;
  CHECK(describe(r) ==
        "1 part (1 triangle), 1 boundary loop (the rim), 0 holes, 1 non-manifold edge, 1 flipped patch "
        "(1 triangle), 1 welded vertex, 1 duplicate and 1 zero-area triangles dropped");
  r.parts = 10;
  r.part_triangles = {90, 8, 7, 6, 5, 4, 3, 2, 2, 1};
  r.boundary_loops = 12;
  r.holes = 2;
  r.longest_hole = 0.25;
  r.flipped_patches = 0;
  r.nonmanifold_edges = 0;
  r.misoriented_edges = 2;
  CHECK(describe(r) ==
        "10 parts (90, 8, 7, 6, 5, 4, 3, 2 triangles and 2 smaller parts), 12 boundary loops (10 rims), "
        "2 holes (longest perimeter 0.25), 0 non-manifold edges, 0 flipped patches, 2 edges left misoriented "
        "(a non-orientable part), 1 welded vertex, 1 duplicate and 1 zero-area triangles dropped");
  CHECK(describe(MeshReport{}) ==
        "0 parts, 0 boundary loops, 0 holes, 0 non-manifold edges, 0 flipped patches, 0 welded vertices, "
        "0 duplicate and 0 zero-area triangles dropped");
}

TEST_CASE("bad input throws") {
  Mesh m = icosphere(0);
  CHECK_THROWS_AS(clean_mesh(m, -1.0), std::invalid_argument);
  m.triangles.emplace_back(0, 1, 99);
  CHECK_THROWS_AS(clean_mesh(m, 0.0), std::out_of_range);
  m.triangles.pop_back();
  m.positions[0].x() = NAN;
  CHECK_THROWS_AS(clean_mesh(m, 0.0), std::invalid_argument);
}

namespace {

// The `v` and `f` lines of an OBJ file (the MakeHuman files hold nothing else); empty when the
// file cannot be read.
Mesh read_obj(const std::filesystem::path& path) {
  Mesh m;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "v") {
      Vec3 p;
      fields >> p.x() >> p.y() >> p.z();
      m.positions.push_back(p);
    } else if (tag == "f") {
      std::vector<int> corners;
      std::string corner;
      while (fields >> corner) corners.push_back(std::stoi(corner) - 1);  // "7/3/2" reads as 7
      for (std::size_t k = 2; k < corners.size(); ++k) m.triangles.emplace_back(corners[0], corners[k - 1], corners[k]);
    }
  }
  return m;
}

std::filesystem::path makehuman(const std::string& file) { return "/work/shared/data/makehuman/" + file; }

}  // namespace

TEST_CASE("MakeHuman short01, all parts: 200 open parts with a rim each, as its stats.json says") {
  const std::filesystem::path file = makehuman("hair_short01_full.obj");
  if (!std::filesystem::exists(file)) {
    MESSAGE("skipped: " << file << " is not there");
    return;
  }
  const Mesh raw = read_obj(file);
  REQUIRE(raw.triangles.size() == 3678);
  const CleanMesh c = clean_mesh(raw, 0.0);
  const MeshReport& r = c.report;
  CHECK(r.parts == 200);
  CHECK(r.boundary_loops == 200);
  CHECK(r.holes == 0);
  CHECK(r.nonmanifold_edges == 0);
  CHECK(r.flipped_patches == 0);
  CHECK(r.misoriented_edges == 0);
  CHECK(r.welded_vertices == 0);
  CHECK(r.duplicate_triangles + r.degenerate_triangles == 0);
  CHECK(c.mesh.positions.size() == 2984);
  CHECK(std::vector<int>(r.part_triangles.begin(), r.part_triangles.begin() + 8) ==
        std::vector<int>{2200, 36, 36, 28, 20, 10, 10, 10});
  CHECK(same_mesh(clean_mesh(raw, 1e-3).mesh, c.mesh));  // its parts lie more than 1e-3 dm apart
}

TEST_CASE("MakeHuman meshes without repeated positions: parts and loops as stats.json counts them") {
  struct Expected {
    const char* file;
    int parts, loops;
  };
  for (const Expected& e : {Expected{"head.obj", 1, 1}, {"scalp.obj", 1, 1}, {"hair_short01_shell.obj", 1, 1},
                            {"hair_short04_shell.obj", 1, 1}, {"hair_short04_full.obj", 22, 22},
                            {"hair_bob01_shell.obj", 1, 1}, {"hair_braid01_shell.obj", 1, 1},
                            {"hair_ponytail01_shell.obj", 1, 2}}) {
    const std::string file = e.file;
    CAPTURE(file);
    if (!std::filesystem::exists(makehuman(e.file))) continue;
    const MeshReport r = clean_mesh(read_obj(makehuman(e.file)), 0.0).report;
    CHECK(r.welded_vertices == 0);
    CHECK(r.parts == e.parts);
    CHECK(r.boundary_loops == e.loops);
    CHECK(r.holes == e.loops - e.parts);
    CHECK(r.nonmanifold_edges + r.flipped_patches + r.misoriented_edges == 0);
  }
}

TEST_CASE("MakeHuman ponytail, braid and bob: their parts repeat positions exactly, and welding joins them") {
  // stats.json counts parts by vertex index; at tolerance 0 the vertices some parts repeat exactly
  // are welded, so the parts that share them become one and some of their triangles repeat.
  for (const std::string name : {"hair_ponytail01_full.obj", "hair_braid01_full.obj", "hair_bob01_full.obj"}) {
    CAPTURE(name);
    if (!std::filesystem::exists(makehuman(name))) continue;
    const Mesh raw = read_obj(makehuman(name));
    const CleanMesh c = clean_mesh(raw, 0.0);
    std::set<std::array<double, 3>> distinct;
    std::set<int> used;
    for (const Vec3i& t : raw.triangles)
      for (int k = 0; k < 3; ++k) {
        used.insert(t[k]);
        distinct.insert({raw.positions[t[k]].x(), raw.positions[t[k]].y(), raw.positions[t[k]].z()});
      }
    CHECK(c.report.welded_vertices > 0);
    CHECK(c.report.welded_vertices == static_cast<int>(used.size() - distinct.size()));
    CHECK(c.mesh.positions.size() == distinct.size());  // no vertex is used only by dropped triangles
    CHECK(analyse_topology(c.mesh).orientation_consistent);
  }
}
