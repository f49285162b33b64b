// The rod with interior point forces (rod_point_forces.h) against independent answers: the
// Euler–Bernoulli cantilever under point loads (small loads, superposed), the global moment
// balance of a strongly bent rod, and integrate_rod itself where there are no forces.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "rod/rod.h"
#include "rod/rod_point_forces.h"

using namespace hairfit;

namespace {

Mat3 tilted_frame() {  // a general root frame, so no test leans on the identity
  return (Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * Eigen::AngleAxisd(-0.4, Vec3::UnitX()))
      .toRotationMatrix();
}

RodModel straight_model(const Mat3& root) {
  RodModel m;
  m.root_frame = root;
  return m;
}

struct Traced {
  std::vector<double> nodes, moments;
  Vec3 terminal_moment;
  Vec3 node(int i) const { return Vec3(nodes[3 * i], nodes[3 * i + 1], nodes[3 * i + 2]); }
  Vec3 moment(int i) const { return Vec3(moments[3 * i], moments[3 * i + 1], moments[3 * i + 2]); }
};

Traced trace(const RodModel& model, int segments, const Vec3& f, const Vec3& m0, const std::vector<Vec3>& forces) {
  Traced t;
  t.nodes.assign(3 * (segments + 1), 0.0);
  t.moments.assign(3 * (segments + 1), 0.0);
  std::vector<double> flat;
  for (const Vec3& F : forces) flat.insert(flat.end(), F.data(), F.data() + 3);
  integrate_rod_with_point_forces<double>(model, RodIntegrator::rk4, segments, f.data(), m0.data(), flat.data(),
                                          static_cast<int>(forces.size()), t.terminal_moment.data(),
                                          RodTrace<double>{t.nodes.data(), nullptr, nullptr, t.moments.data()});
  return t;
}

// Deflection at x of a unit-stiffness cantilever of unit length under a unit transverse load at a
// (Euler–Bernoulli): x²(3a − x)/6 up to the load, a²(3x − a)/6 beyond it.
double cantilever(double x, double a) { return x <= a ? x * x * (3.0 * a - x) / 6.0 : a * a * (3.0 * x - a) / 6.0; }

}  // namespace

TEST_CASE("point forces at their nodes: evenly spaced, the root and the tip bounding the pieces") {
  CHECK(point_force_node(0, 3, 64) == 0);
  CHECK(point_force_node(1, 3, 64) == 16);
  CHECK(point_force_node(2, 3, 64) == 32);
  CHECK(point_force_node(3, 3, 64) == 48);
  CHECK(point_force_node(4, 3, 64) == 64);
  CHECK(point_force_node(1, 2, 64) == 21);  // 64/3 rounded
  CHECK(point_force_node(1, 1, 7) == 4);    // 3.5 rounded away from zero
}

TEST_CASE("without point forces, or with zero ones, the rod is integrate_rod's bit for bit") {
  const RodModel model = straight_model(tilted_frame());
  const Vec3 f(1.5, -0.7, 2.0), m0(0.3, 1.1, -0.4);
  const int segments = 48;
  std::vector<double> nodes(3 * (segments + 1));
  Vec3 m1;
  integrate_rod<double>(model, RodIntegrator::rk4, segments, f.data(), m0.data(), m1.data(),
                        RodTrace<double>{nodes.data(), nullptr, nullptr, nullptr});
  for (const std::vector<Vec3>& forces : {std::vector<Vec3>{}, std::vector<Vec3>(3, Vec3::Zero())}) {
    const Traced t = trace(model, segments, f, m0, forces);
    CHECK(t.nodes == nodes);
    CHECK(t.terminal_moment == m1);
  }
}

TEST_CASE("small point loads bend the cantilever as Euler–Bernoulli superposes them") {
  // Three loads in different transverse directions at s = ¼, ½, ¾ and one at the tip; the linear
  // beam's deflections superpose per axis. m(0) is their moment about the root on the straight
  // rod, exact to first order, so the rod departs from the beam by O(P²) (its geometric
  // nonlinearity and the levers' shift): the error relative to P falls tenfold with P.
  const Mat3 root = tilted_frame();
  const RodModel model = straight_model(root);
  const Vec3 d1 = root.col(0), d2 = root.col(1), axis = root.col(2);
  const double at[3] = {0.25, 0.5, 0.75};
  const int segments = 64;
  double relative[2];
  for (int level = 0; level < 2; ++level) {
    const double p = level == 0 ? 1e-3 : 1e-4;
    const Vec3 tip = p * (0.5 * d1 - 0.2 * d2);
    const std::vector<Vec3> forces = {p * d1, p * (-0.8 * d2), p * (0.3 * d1 + 0.6 * d2)};
    Vec3 m0 = axis.cross(tip);
    for (int k = 0; k < 3; ++k) m0 += at[k] * axis.cross(forces[k]);
    const Traced t = trace(model, segments, tip, m0, forces);
    double worst = 0.0;
    for (int i = 0; i <= segments; ++i) {
      const double x = static_cast<double>(i) / segments;
      Vec3 expected = x * axis + cantilever(x, 1.0) * tip;
      for (int k = 0; k < 3; ++k) expected += cantilever(x, at[k]) * forces[k];
      worst = std::max(worst, (t.node(i) - expected).norm());
    }
    relative[level] = worst / p;
    CHECK(t.terminal_moment.norm() < 10.0 * p * p);
  }
  CAPTURE(relative[0]);
  CAPTURE(relative[1]);
  CHECK(relative[1] < 1e-4);
  CHECK(relative[0] / relative[1] == doctest::Approx(10.0).epsilon(0.05));
}

TEST_CASE("a strongly bent rod with point forces is in global moment balance") {
  // m(0) − m(1) = (r(1) − r(0)) × f_L + Σ (r(s_k) − r(0)) × F_k for a weightless rod: the moment
  // of every force about the root, whatever the shape. Checked on the traced nodes and moments;
  // the scheme keeps it to round-off at any step (each step's moment change is its chord × n).
  const RodModel model = straight_model(tilted_frame());
  const Vec3 f(3.0, -1.0, 2.0), m0(1.0, -2.0, 0.5);
  const std::vector<Vec3> forces = {Vec3(-4.0, 2.0, 1.0), Vec3(0.5, 3.0, -2.0), Vec3(2.0, -1.5, 0.5)};
  for (const int segments : {16, 64, 256}) {
    CAPTURE(segments);
    const Traced t = trace(model, segments, f, m0, forces);
    Vec3 balance = t.node(segments).cross(f);
    for (int k = 0; k < 3; ++k) balance += t.node(point_force_node(k + 1, 3, segments)).cross(forces[k]);
    CHECK((m0 - t.terminal_moment - balance).norm() < 1e-12 * m0.norm());
    CHECK(t.moment(segments) == t.terminal_moment);
  }
}

TEST_CASE("point forces that share a node, or sit at the tip, act as their sum there") {
  // On 2 segments, three forces land at nodes 1, 1 and 2: the same rod as one force F1 + F2 at
  // node 1 and the terminal force f_L + F3 (the piece beyond the tip is empty).
  const RodModel model = straight_model(tilted_frame());
  const Vec3 f(0.4, -1.2, 0.3), m0(0.2, 0.5, -0.1);
  const std::vector<Vec3> three = {Vec3(1.0, 0.5, -0.3), Vec3(-0.2, 0.8, 0.4), Vec3(0.6, -0.1, 0.9)};
  REQUIRE(point_force_node(1, 3, 2) == 1);
  REQUIRE(point_force_node(2, 3, 2) == 1);
  REQUIRE(point_force_node(3, 3, 2) == 2);
  const Traced a = trace(model, 2, f, m0, three);
  const Traced b = trace(model, 2, f + three[2], m0, {three[0] + three[1]});
  for (int i = 0; i <= 2; ++i) CHECK((a.node(i) - b.node(i)).norm() < 1e-14);
  CHECK((a.terminal_moment - b.terminal_moment).norm() < 1e-14);
  for (double v : a.nodes) CHECK(std::isfinite(v));
}
