// The two solution schemes against each other, jet derivatives against finite differences, bad
// input, and the `hairfit rod` command.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.h"
#include "rod/rod.h"
#include "rod/rod_jet.h"
#include "rod/rod_sensitivity.h"
#include "rod/rod_shooting.h"
#include "load_derivatives.h"
#include "rod_references.h"

using namespace hairfit;

namespace {

Rod test_rod() {
  Rod rod;
  rod.length = 2.0;
  rod.stiffness = Vec3(1.5, 2.5, 0.8);
  rod.natural_curvature = {Vec3(0.3, -0.2, 0.1), Vec3(-0.4, 0.5, 0.0)};
  rod.force_per_length = Vec3(0.1, -0.3, -0.6);
  return rod;
}

RodRoot test_root() {
  RodRoot root;
  root.position = Vec3(0.5, 0.2, -1.0);
  root.frame = Eigen::AngleAxisd(0.9, Vec3(1.0, -1.0, 0.5).normalized()).toRotationMatrix();
  return root;
}

}  // namespace

TEST_CASE("round trip: the terminal torque of the initial-value form, fed to shooting, returns the root moment") {
  const Rod rod = test_rod();
  const RodRoot root = test_root();
  const Vec3 moments[] = {Vec3(0.2, -0.5, 0.1), Vec3(-1.0, 0.5, 0.3), Vec3(0.0, 2.0, -0.8)};
  const Vec3 forces[] = {Vec3(0.3, 0.0, -0.2), Vec3(-0.6, 1.0, 0.3), Vec3(0.0, -1.5, 1.0)};
  for (const RodIntegrator integrator : {RodIntegrator::rk2, RodIntegrator::rk4})
    for (int i = 0; i < 3; ++i) {
      CAPTURE(i);
      RodOptions forward;
      forward.solver = RodSolver::initial_value;
      forward.integrator = integrator;
      RodLoad given;
      given.terminal_force = forces[i];
      given.root_moment = moments[i];
      const SolvedRod iv = solve_rod(rod, root, given, forward);
      CHECK(iv.iterations == 0);
      CHECK((iv.root_moment - moments[i]).norm() == 0.0);

      RodOptions shooting = forward;
      shooting.solver = RodSolver::shooting;
      RodLoad target;
      target.terminal_force = forces[i];
      target.terminal_torque = iv.terminal_torque;
      // Cold start: continuation follows the equilibrium connected to the unloaded rod, so these
      // loads are moderate (a larger m(0) may sit on another branch; the warm start below finds it).
      const SolvedRod shot = solve_rod(rod, root, target, shooting);
      CHECK(shot.converged);
      CHECK((shot.root_moment - moments[i]).norm() <= 1e-9);
      CHECK((shot.tip() - iv.tip()).norm() <= 1e-9 * rod.length);

      target.root_moment = moments[i] + Vec3(0.01, -0.02, 0.01);  // warm start next to the answer
      const SolvedRod warm = solve_rod(rod, root, target, shooting);
      CHECK(warm.converged);
      CHECK(warm.iterations <= 4);
      CHECK((warm.root_moment - moments[i]).norm() <= 1e-9);
    }
}

TEST_CASE("shooting Newton converges quadratically from a warm start") {
  // The residual of each Newton step is about the square of the previous one: from an error of
  // 1e-2 the solver needs at most 3 steps to reach 1e-11.
  const Rod rod = test_rod();
  RodLoad load;
  load.terminal_force = Vec3(0.5, -0.4, 0.2);
  load.terminal_torque = Vec3(0.1, 0.2, -0.1);
  const SolvedRod cold = solve_rod(rod, test_root(), load);
  REQUIRE(cold.converged);
  load.root_moment = cold.root_moment * 1.01;
  const SolvedRod warm = solve_rod(rod, test_root(), load);
  CHECK(warm.converged);
  CHECK(warm.iterations <= 3);
}

TEST_CASE("jet derivatives of the forward integration agree with central finite differences") {
  RodModel model = make_rod_model(test_rod(), test_root());
  const int segments = 32;
  const int nodes = segments + 1;
  const double eta[6] = {0.7, -0.3, 0.5, 0.4, 1.1, -0.6};  // (f_L, m(0)), dimensionless
  // All outputs of one integration stacked: nodes, frames, curvature, moments, m(1).
  auto outputs = [&](const double* p) {
    std::vector<double> out(nodes * 18 + 3);
    RodTrace<double> trace{&out[0], &out[3 * nodes], &out[12 * nodes], &out[15 * nodes]};
    integrate_rod<double>(model, RodIntegrator::rk4, segments, p, p + 3, &out[18 * nodes], trace);
    return out;
  };
  std::vector<RodJet6> jet_out(nodes * 18 + 3);
  RodJet6 parameters[6];
  for (int i = 0; i < 6; ++i) parameters[i] = RodJet6(eta[i], i);
  integrate_rod<RodJet6>(model, RodIntegrator::rk4, segments, parameters, parameters + 3, &jet_out[18 * nodes],
                         RodTrace<RodJet6>{&jet_out[0], &jet_out[3 * nodes], &jet_out[12 * nodes], &jet_out[15 * nodes]});
  const std::vector<double> value = outputs(eta);
  double worst = 0.0;
  for (int i = 0; i < 6; ++i) {
    const double h = 1e-5;
    double plus[6], minus[6];
    std::copy(eta, eta + 6, plus);
    std::copy(eta, eta + 6, minus);
    plus[i] += h;
    minus[i] -= h;
    const std::vector<double> up = outputs(plus), down = outputs(minus);
    for (std::size_t k = 0; k < value.size(); ++k) {
      CHECK(jet_out[k].a == doctest::Approx(value[k]).epsilon(1e-13));  // the value part is the double computation
      const double difference = (up[k] - down[k]) / (2 * h);
      worst = std::max(worst, std::fabs(jet_out[k].v[i] - difference) / (1.0 + std::fabs(difference)));
    }
  }
  CHECK(worst <= 1e-8);

  // The 3-parameter jet used by shooting gives the same ∂m(1)/∂m(0).
  RodJet3 force[3], moment[3], end[3];
  for (int i = 0; i < 3; ++i) {
    force[i] = RodJet3(eta[i]);
    moment[i] = RodJet3(eta[3 + i], i);
  }
  integrate_rod<RodJet3>(model, RodIntegrator::rk4, segments, force, moment, end, RodTrace<RodJet3>{});
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) CHECK(end[r].v[c] == doctest::Approx(jet_out[18 * nodes + r].v[3 + c]).epsilon(1e-14));
}

TEST_CASE("a shooting solve that cannot finish keeps a finite best iterate and says so") {
  Rod rod;
  RodLoad load;
  load.terminal_force = Vec3(0.0, 800.0, 0.0);
  load.terminal_torque = Vec3(900.0, 0.0, 0.0);
  RodOptions options;
  options.max_iterations = 3;
  const SolvedRod solved = solve_rod(rod, RodRoot{}, load, options);
  CHECK_FALSE(solved.converged);
  CHECK(std::isfinite(solved.residual));
  CHECK(solved.residual > 0.0);
  for (const Vec3& r : solved.nodes) CHECK(r.allFinite());
  CHECK(solved.root_moment.allFinite());
}

TEST_CASE("bad rods and loads are rejected with a message naming the problem") {
  auto message = [](const Rod& rod, const RodLoad& load, const RodOptions& options, const RodRoot& root = {}) {
    try {
      solve_rod(rod, root, load, options);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const double nan = std::nan("");
  Rod rod;
  RodLoad load;
  RodOptions options;
  rod.length = -1.0;
  CHECK(message(rod, load, options).find("length") != std::string::npos);
  rod.length = 0.0;
  CHECK(message(rod, load, options).find("length") != std::string::npos);
  rod = Rod{};
  rod.stiffness = Vec3(1.0, -2.0, 1.0);
  CHECK(message(rod, load, options).find("EI2") != std::string::npos);
  rod.stiffness = Vec3(1.0, 1.0, 0.0);
  CHECK(message(rod, load, options).find("GJ") != std::string::npos);
  rod = Rod{};
  rod.natural_curvature = {Vec3(nan, 0, 0)};
  CHECK(message(rod, load, options).find("natural curvature") != std::string::npos);
  rod = Rod{};
  rod.force_per_length = Vec3(0, 0, INFINITY);
  CHECK(message(rod, load, options).find("force per length") != std::string::npos);
  rod = Rod{};
  load.terminal_force = Vec3(nan, 0, 0);
  CHECK(message(rod, load, options).find("terminal force") != std::string::npos);
  load = RodLoad{};
  load.terminal_torque = Vec3(0, INFINITY, 0);
  CHECK(message(rod, load, options).find("terminal torque") != std::string::npos);
  load = RodLoad{};
  options.segments = 0;
  CHECK(message(rod, load, options).find("segments") != std::string::npos);
  options = RodOptions{};
  RodRoot skewed;
  skewed.frame(0, 1) = 0.5;
  CHECK(message(rod, load, options, skewed).find("root frame") != std::string::npos);
  CHECK_THROWS_AS(parse_rod_integrator("rk3"), InputError);
  CHECK_THROWS_AS(make_circular_rod(30.0, -1.0, 1.0, 1e-5), InputError);
}

namespace {

struct Run {
  int status;
  std::string out;
};

Run run_cli(const std::string& arguments) {
  const std::string command = std::string(HAIRFIT_BINARY) + " rod " + arguments + " 2>/dev/null";
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string out;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
  const int status = pclose(pipe);
  return Run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

Vec3 json_vector(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\": [");
  REQUIRE(at != std::string::npos);
  Vec3 v;
  REQUIRE(std::sscanf(json.c_str() + at + key.size() + 4, "[%lf, %lf, %lf]", &v[0], &v[1], &v[2]) == 3);
  return v;
}

}  // namespace

TEST_CASE("hairfit rod prints the solved rod as JSON") {
  const Run run = run_cli("--length=2 --bend=0.5 --twist 0.3 --force=-0.3,0.1,0 --segments=16");
  REQUIRE(run.status == 0);
  Rod rod;
  rod.length = 2.0;
  rod.stiffness = Vec3(0.5, 0.5, 0.3);
  RodLoad load;
  load.terminal_force = Vec3(-0.3, 0.1, 0.0);
  RodOptions options;
  options.segments = 16;
  const SolvedRod expected = solve_rod(rod, RodRoot{}, load, options);
  CHECK((json_vector(run.out, "tip") - expected.tip()).norm() <= 1e-15);  // %.17g round-trips
  CHECK((json_vector(run.out, "root_moment") - expected.root_moment).norm() <= 1e-15);
  for (const char* key : {"\"tip_frame\"", "\"terminal_torque\"", "\"nodes\"", "\"iterations\"", "\"residual\""})
    CHECK(run.out.find(key) != std::string::npos);

  const Run iv = run_cli("--solver initial-value --root-moment=0,-1,0 --integrator rk2");
  REQUIRE(iv.status == 0);
  CHECK(json_vector(iv.out, "terminal_torque").isApprox(Vec3(0, -1, 0), 1e-15));  // no force: m constant
  CHECK(json_vector(iv.out, "tip").x() < 0.0);
  CHECK(run_cli("--help").status == 0);
}

TEST_CASE("hairfit rod rejects bad input with exit code 2") {
  for (const char* bad : {"--length=-1", "--length 0", "--bend=-2", "--bend1=1 --bend2=0", "--twist=-1",
                          "--segments 0", "--segments=2.5", "--force=nan,0,0", "--force=1,2", "--torque=inf,0,0",
                          "--gravity=0,0,1e999", "--natural-curvature=1,2,nan", "--solver=newton",
                          "--integrator=rk3", "--solver=initial-value --torque=1,0,0", "--bend=1 --bend1=2",
                          "--unknown=1", "stray"}) {
    CAPTURE(std::string(bad));
    CHECK(run_cli(bad).status == 2);
  }
}

TEST_CASE("warm starts from an earlier solution's pieces follow a heavy cantilever to load 1000") {
  // A tip force α normal to the rod: the tip tends to the pull and the root moment to √(2α), while
  // m(1) depends on m(0) like exp(√α) ≈ e³¹ at the end. Each level starts from the previous one's
  // pieces (traced under the previous loads when the piece count grows) and must converge from
  // there, without the restart from the unloaded rod, to the elliptic-integral answer.
  const RodModel model = make_rod_model(Rod{}, RodRoot{});
  ShootingOptions options;
  options.segments = 256;
  options.max_iterations = 8;
  options.restart_from_rest = false;
  ShootingResult at = shoot_root_moment(model, Vec3(10.0, 0.0, 0.0), Vec3::Zero(), Vec3::Zero(), ShootingOptions{});
  REQUIRE(at.converged);
  int levels = 0;
  for (double alpha = 12.5; alpha <= 1000.0; alpha *= 1.25, ++levels) {
    CAPTURE(alpha);
    const ShootingResult next = shoot_root_moment(model, Vec3(alpha, 0.0, 0.0), Vec3::Zero(), at, options);
    REQUIRE(next.converged);
    CHECK(next.iterations <= 6);
    const int n = options.segments + 1;
    std::vector<double> nodes(3 * n), frames(9 * n);
    const Vec3 m1 = trace_pieces(model, options.integrator, options.segments, next,
                                 RodTrace<double>{nodes.data(), frames.data(), nullptr, nullptr});
    CHECK(m1.norm() <= 1e-8 * alpha);
    const test::CantileverTip exact = test::cantilever_tip(alpha, true);
    CHECK((Eigen::Map<const Vec3>(&nodes[3 * (n - 1)]) - Vec3(exact.x, 0.0, exact.z)).norm() <= 2e-5);
    // The elastica's first integral: m(0)² = 2α·sin θ_L, with θ_L the tip angle from the axis.
    CHECK(next.root_moment.squaredNorm() == doctest::Approx(2.0 * alpha * std::sin(exact.angle)).epsilon(1e-4));
    at = next;
  }
  CHECK(levels == 20);  // 12.5 · 1.25^19 ≈ 870
}

TEST_CASE("load derivatives of a heavy rod's solution agree with finite differences of the boundary-value solve") {
  // A hanging rod of dimensionless weight 500 (15 pieces would be needed for 1800): the initial-value
  // form cannot differentiate it (m(1) depends on m(0) like e²²), the implicit derivative can.
  RodModel model = make_rod_model(Rod{}, RodRoot{Vec3::Zero(), Eigen::AngleAxisd(1.2, Vec3::UnitX()).toRotationMatrix()});
  model.force_per_length = Vec3(0.0, -500.0, 0.0);
  ShootingOptions options;
  options.segments = 64;
  const Vec3 force(3.0, -2.0, 1.0), torque(0.5, 0.2, -0.3);
  const ShootingResult at = shoot_root_moment(model, force, torque, Vec3::Zero(), options);
  REQUIRE(at.converged);
  REQUIRE(at.breaks.size() > 3);
  const double worst = test::worst_load_derivative_error(model, options, at, force, torque);
  MESSAGE("worst relative derivative error " << worst << ", pieces " << at.breaks.size() - 1);
  CHECK(worst <= 1e-6);
}

TEST_CASE("the value part of a jet integration is bit for bit the double integration") {
  // The pre-guides rely on it: a converged Newton iterate's end (position, frame) and m(1) are
  // taken from whichever of the two integrations confirmed it.
  for (const RodIntegrator integrator : {RodIntegrator::rk2, RodIntegrator::rk4}) {
    for (const bool weight : {false, true}) {
      Rod rod = test_rod();
      if (!weight) rod.force_per_length = Vec3::Zero();
      const RodModel model = make_rod_model(rod, test_root());
      const double force[3] = {0.7, -0.3, 0.5}, moment[3] = {0.4, 1.1, -0.6};
      RodState<double> plain;
      RodState<RodJet3> jets;
      RodJet3 jet_force[3];
      for (int a = 0; a < 3; ++a) {
        plain.position[a] = 0.0;
        plain.moment[a] = moment[a];
        jets.position[a] = RodJet3(0.0);
        jets.moment[a] = RodJet3(moment[a], a);
        jet_force[a] = RodJet3(force[a]);
      }
      for (int a = 0; a < 9; ++a) {
        plain.frame[a] = model.root_frame.data()[a];
        jets.frame[a] = RodJet3(model.root_frame.data()[a]);
      }
      integrate_rod_steps<double>(model, integrator, 48, 0, 48, force, plain, RodTrace<double>{});
      integrate_rod_steps<RodJet3>(model, integrator, 48, 0, 48, jet_force, jets, RodTrace<RodJet3>{});
      CAPTURE(weight);
      for (int a = 0; a < 3; ++a) {
        CHECK(jets.position[a].a == plain.position[a]);  // exact, not approximate
        CHECK(jets.moment[a].a == plain.moment[a]);
      }
      for (int a = 0; a < 9; ++a) CHECK(jets.frame[a].a == plain.frame[a]);
    }
  }
}

TEST_CASE("six-tangent jets (the guides' Jacobians, one AVX-512 pack where the CPU has one) carry the three-tangent jets' derivatives bit for bit") {
  // Every tangent lane does the same IEEE operations whatever the pack width, so the derivatives
  // by (f_L, m(0)) of a six-tangent run are those of two three-tangent runs, one seeded on f_L and
  // one on m(0), exactly; and the value part is the double run's.
  for (const RodIntegrator integrator : {RodIntegrator::rk2, RodIntegrator::rk4}) {
    const RodModel model = make_rod_model(test_rod(), test_root());
    const double force[3] = {0.7, -0.3, 0.5}, moment[3] = {0.4, 1.1, -0.6};
    RodJet6 force6[3], moment6[3], end6[3];
    RodJet3 force_seeded[3], moment_seeded[3], force_plain[3], moment_plain[3], end_by_force[3], end_by_moment[3];
    for (int a = 0; a < 3; ++a) {
      force6[a] = RodJet6(force[a], a);
      moment6[a] = RodJet6(moment[a], 3 + a);
      force_seeded[a] = RodJet3(force[a], a);
      moment_seeded[a] = RodJet3(moment[a], a);
      force_plain[a] = RodJet3(force[a]);
      moment_plain[a] = RodJet3(moment[a]);
    }
    const int n = 40;
    std::vector<RodJet6> nodes6(3 * (n + 1));
    std::vector<RodJet3> nodes_by_force(3 * (n + 1)), nodes_by_moment(3 * (n + 1));
    std::vector<double> nodes(3 * (n + 1));
    double end[3];
    integrate_rod<RodJet6>(model, integrator, n, force6, moment6, end6, RodTrace<RodJet6>{nodes6.data()});
    integrate_rod<RodJet3>(model, integrator, n, force_seeded, moment_plain, end_by_force, RodTrace<RodJet3>{nodes_by_force.data()});
    integrate_rod<RodJet3>(model, integrator, n, force_plain, moment_seeded, end_by_moment, RodTrace<RodJet3>{nodes_by_moment.data()});
    integrate_rod<double>(model, integrator, n, force, moment, end, RodTrace<double>{nodes.data()});
    auto same = [](const RodJet6& six, const RodJet3& by_force, const RodJet3& by_moment, double value) {
      for (int k = 0; k < 3; ++k) {
        if (six.v[k] != by_force.v[k] || six.v[3 + k] != by_moment.v[k]) return false;
      }
      return six.a == value && by_force.a == value && by_moment.a == value;
    };
    for (int a = 0; a < 3; ++a) CHECK(same(end6[a], end_by_force[a], end_by_moment[a], end[a]));
    int differing = 0;
    for (std::size_t i = 0; i < nodes6.size(); ++i) differing += !same(nodes6[i], nodes_by_force[i], nodes_by_moment[i], nodes[i]);
    CHECK(differing == 0);
  }
}

TEST_CASE("single shooting: a pure terminal torque bends the rod into a circular arc, m(0) = t_L exactly") {
  // No force: m(s) ≡ t_L, so the rod of unit bending compliance is an arc of curvature |t_L|
  // about the torque's axis; with t_L = κ·d2 the arc bends toward d1: r(1) = ((1 − cos κ)/κ, 0,
  // sin κ/κ) in the root frame, d3(1) = (sin κ, 0, cos κ).
  const RodModel model = make_rod_model(Rod{}, RodRoot{});
  RodDiscretisation rod;
  rod.segments = 200;
  for (double kappa : {0.3, 1.5, 3.0}) {
    const Vec3 torque(0.0, kappa, 0.0);
    const SingleShot shot = shoot_single(model, rod, Vec3::Zero(), torque, Vec3::Zero(), 1e-12, 10);
    REQUIRE(shot.converged);
    CHECK((shot.root_moment - torque).norm() < 1e-12);
    const Vec3 end((1.0 - std::cos(kappa)) / kappa, 0.0, std::sin(kappa) / kappa);
    CHECK((shot.end_position - end).norm() < 1e-9);
    CHECK((shot.end_tangent - Vec3(std::sin(kappa), 0.0, std::cos(kappa))).norm() < 1e-9);
  }
}

TEST_CASE("single shooting agrees with multiple shooting on a light cantilever, and stops on a non-finite load") {
  const RodModel model = make_rod_model(Rod{}, RodRoot{});
  ShootingOptions options;
  options.segments = 64;
  const Vec3 force(2.0, 0.5, -1.0), torque(0.3, -0.2, 0.1);
  const ShootingResult multiple = shoot_root_moment(model, force, torque, Vec3::Zero(), options);
  REQUIRE(multiple.converged);
  const SingleShot shot = shoot_single(model, options, force, torque, Vec3::Zero(), 1e-10, 20);
  REQUIRE(shot.converged);
  CHECK((shot.root_moment - multiple.root_moment).norm() < 1e-9);
  CHECK(shot.integrations <= 10);  // quadratic convergence from the straight rod
  const SingleShot bad =
      shoot_single(model, options, Vec3(std::nan(""), 0.0, 0.0), torque, Vec3::Zero(), 1e-11, 20);
  CHECK(!bad.converged);
  CHECK(bad.root_moment.allFinite());
}
