#include "rod/rod.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "rod/rod_shooting.h"

namespace hairfit {

namespace {

std::string text(const Vec3& v) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "%g,%g,%g", v.x(), v.y(), v.z());
  return buffer;
}

// The message's number is formatted only when the check fails: these checks run for every guide
// and fibre, and formatting eagerly cost more than the checks (0.55 G instructions of the
// paper-scale guide stage, callgrind).
void require(bool ok, const char* message) {
  if (!ok) throw InputError("rod", message);
}
void require(bool ok, const char* message, int value) {
  if (!ok) throw InputError("rod", message + std::to_string(value));
}
void require(bool ok, const char* message, double value) {
  if (!ok) throw InputError("rod", message + std::to_string(value));
}
void require(bool ok, const char* message, const Vec3& value) {
  if (!ok) throw InputError("rod", message + text(value));
}

}  // namespace

Rod make_circular_rod(double length, double youngs_modulus, double shear_modulus, double area) {
  require(std::isfinite(youngs_modulus) && youngs_modulus > 0.0,
          "Young's modulus must be a positive number of dyn/cm², not ", youngs_modulus);
  require(std::isfinite(shear_modulus) && shear_modulus > 0.0,
          "shear modulus must be a positive number of dyn/cm², not ", shear_modulus);
  require(std::isfinite(area) && area > 0.0, "cross-section area must be a positive number of cm², not ", area);
  const double pi = 3.14159265358979323846;
  const double i = area * area / (4.0 * pi);  // second moment of a disk of area A: πr⁴/4 = A²/(4π)
  Rod rod;
  rod.length = length;
  rod.stiffness = Vec3(youngs_modulus * i, youngs_modulus * i, shear_modulus * 2.0 * i);
  validate_rod(rod);
  return rod;
}

void validate_rod(const Rod& rod) {
  require(std::isfinite(rod.length) && rod.length > 0.0,
          "length must be a positive number of cm, not ", rod.length);
  const char* messages[3] = {"bending stiffness EI1 must be a positive number of dyn·cm², not ",
                             "bending stiffness EI2 must be a positive number of dyn·cm², not ",
                             "torsional stiffness GJ must be a positive number of dyn·cm², not "};
  for (int k = 0; k < 3; ++k)
    require(std::isfinite(rod.stiffness[k]) && rod.stiffness[k] > 0.0, messages[k], rod.stiffness[k]);
  for (const Vec3& k : rod.natural_curvature)
    require(k.allFinite(), "natural curvature must be finite (1/cm), not ", k);
  require(rod.force_per_length.allFinite(),
          "force per length (gravity) must be finite (dyn/cm), not ", rod.force_per_length);
}

RodScales rod_scales(const Rod& rod) {
  const double ei = rod.stiffness[0];
  return RodScales{rod.length, ei / (rod.length * rod.length), ei / rod.length};
}

RodModel make_rod_model(const Rod& rod, const RodRoot& root) {
  validate_rod(rod);
  require(root.position.allFinite() && root.frame.allFinite(), "the root position and frame must be finite");
  require((root.frame.transpose() * root.frame - Mat3::Identity()).norm() < 1e-9 && root.frame.determinant() > 0.0,
          "the root frame must be a rotation (orthonormal, right-handed)");
  const RodScales scale = rod_scales(rod);
  RodModel model;
  model.compliance = Vec3::Constant(rod.stiffness[0]).cwiseQuotient(rod.stiffness);
  for (const Vec3& k : rod.natural_curvature) model.kappa_hat.push_back(k * rod.length);
  model.force_per_length = rod.force_per_length * (rod.length / scale.force);
  model.root_frame = root.frame;
  return model;
}

SolvedRod solve_rod(const Rod& rod, const RodRoot& root, const RodLoad& load, const RodOptions& options) {
  const RodModel model = make_rod_model(rod, root);
  require(options.segments >= 1 && options.segments <= 10000000,
          "segments must be between 1 and 10^7, not ", options.segments);
  require(load.terminal_force.allFinite(), "terminal force must be finite (dyn), not ", load.terminal_force);
  require(load.terminal_torque.allFinite(),
          "terminal torque must be finite (dyn·cm), not ", load.terminal_torque);
  require(load.root_moment.allFinite(), "root moment must be finite (dyn·cm), not ", load.root_moment);

  const RodScales scale = rod_scales(rod);
  const Vec3 force = load.terminal_force / scale.force;
  const int n = options.segments + 1;
  std::vector<double> nodes(3 * n), frames(9 * n), curvature(3 * n);
  const RodTrace<double> trace{nodes.data(), frames.data(), curvature.data(), nullptr};
  SolvedRod solved;
  Vec3 m0 = load.root_moment / scale.moment, m1;
  if (options.solver == RodSolver::shooting) {
    ShootingOptions shooting;
    static_cast<RodDiscretisation&>(shooting) = options;
    shooting.tolerance = options.tolerance;
    shooting.max_iterations = options.max_iterations;
    const ShootingResult s = shoot_root_moment(model, force, load.terminal_torque / scale.moment, m0, shooting);
    m1 = trace_pieces(model, options.integrator, options.segments, s, trace);
    m0 = s.root_moment;
    solved.iterations = s.iterations;
    solved.residual = s.residual;
    solved.converged = s.converged;
  } else {
    integrate_rod<double>(model, options.integrator, options.segments, force.data(), m0.data(), m1.data(), trace);
  }

  solved.nodes.resize(n);
  solved.frames.resize(n);
  solved.curvature.resize(n);
  for (int i = 0; i < n; ++i) {
    solved.nodes[i] = root.position + rod.length * Eigen::Map<const Vec3>(&nodes[3 * i]);
    solved.frames[i] = Eigen::Map<const Mat3>(&frames[9 * i]);
    solved.curvature[i] = Eigen::Map<const Vec3>(&curvature[3 * i]) / rod.length;
  }
  solved.terminal_force = load.terminal_force;
  solved.root_moment = m0 * scale.moment;
  solved.terminal_torque = m1 * scale.moment;
  return solved;
}

}  // namespace hairfit
