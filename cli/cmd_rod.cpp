// `hairfit rod`: solve one clamped Cosserat rod and print it as JSON (docs/design.md §1, §9).
#include <cmath>
#include <cstdio>
#include <string>

#include "args.h"
#include "commands.h"
#include "rod/rod.h"

namespace hairfit::cli {

namespace {

const char* kRodHelp =
    "hairfit rod [OPTIONS]: solve one static Cosserat rod, clamped at the origin with d1 = +x,\n"
    "d2 = +y, d3 = +z, and print it as JSON. Units are cgs; every option also takes --option=value.\n"
    "  --length L                   rod length, cm (default 1)\n"
    "  --bend EI                    isotropic bending stiffness, dyn·cm² (default 1)\n"
    "  --bend1 EI1 --bend2 EI2      anisotropic bending stiffness instead of --bend\n"
    "  --twist GJ                   torsional stiffness, dyn·cm² (default 1)\n"
    "  --force fx,fy,fz             terminal force f_L, dyn, world axes (default 0)\n"
    "  --torque tx,ty,tz            terminal torque t_L, dyn·cm (shooting only; default 0)\n"
    "  --gravity gx,gy,gz           distributed force per length, dyn/cm (default 0)\n"
    "  --natural-curvature k1,k2,tau  constant natural curvature and twist, 1/cm (default 0)\n"
    "  --solver shooting|initial-value  (default shooting)\n"
    "  --root-moment mx,my,mz       root moment m(0), dyn·cm: given (initial-value) or the\n"
    "                               starting guess (shooting); default 0\n"
    "  --integrator rk2|rk4         (default rk4)\n"
    "  --segments N                 integration steps (default 64)\n"
    "Output keys: tip, tip_frame [d1,d2,d3], root_moment, terminal_force, terminal_torque, nodes,\n"
    "iterations, residual (|m(L) - t_L|·L/EI), converged. Exit 1 when shooting does not converge.\n";

void print_vector(const Vec3& v) { std::printf("[%.17g, %.17g, %.17g]", v.x(), v.y(), v.z()); }

double positive(const Args& args, const std::string& name, double fallback) {
  const double x = args.number(name, fallback);
  if (!(x > 0.0)) throw UsageError{"--" + name + " must be > 0, not " + *args.text(name)};
  return x;
}

}  // namespace

int command_rod(const Arguments& argv) {
  const Args args(argv,
                  {"length", "bend", "bend1", "bend2", "twist", "force", "torque", "gravity", "natural-curvature",
                   "solver", "root-moment", "integrator", "segments"},
                  {"help"});
  if (args.has("help")) {
    std::fputs(kRodHelp, stdout);
    return 0;
  }
  if (!args.positionals().empty()) throw UsageError{"unexpected argument \"" + args.positionals()[0] + "\""};
  if (args.has("bend") && (args.has("bend1") || args.has("bend2")))
    throw UsageError{"give either --bend (isotropic) or --bend1/--bend2, not both"};

  Rod rod;
  rod.length = positive(args, "length", 1.0);
  const double bend = positive(args, "bend", 1.0);
  rod.stiffness = Vec3(positive(args, "bend1", bend), positive(args, "bend2", bend), positive(args, "twist", 1.0));
  if (args.has("natural-curvature")) rod.natural_curvature = {args.vector3("natural-curvature", Vec3::Zero())};
  rod.force_per_length = args.vector3("gravity", Vec3::Zero());

  RodOptions options;
  const std::string solver = args.text("solver").value_or("shooting");
  if (solver == "shooting")
    options.solver = RodSolver::shooting;
  else if (solver == "initial-value")
    options.solver = RodSolver::initial_value;
  else
    throw UsageError{"--solver must be shooting or initial-value, not \"" + solver + "\""};
  const std::string integrator = args.text("integrator").value_or("rk4");
  if (integrator != "rk2" && integrator != "rk4")
    throw UsageError{"--integrator must be rk2 (2nd order) or rk4 (4th order), not \"" + integrator + "\""};
  options.integrator = parse_rod_integrator(integrator);
  options.segments = args.integer("segments", 64);
  if (options.segments < 1 || options.segments > 1000000)
    throw UsageError{"--segments must be between 1 and 1000000, not " + *args.text("segments")};

  RodLoad load;
  load.terminal_force = args.vector3("force", Vec3::Zero());
  load.root_moment = args.vector3("root-moment", Vec3::Zero());
  if (options.solver == RodSolver::initial_value && args.has("torque"))
    throw UsageError{"--torque is an output of --solver initial-value (give --root-moment instead)"};
  load.terminal_torque = args.vector3("torque", Vec3::Zero());

  const SolvedRod solved = solve_rod(rod, RodRoot{}, load, options);

  std::printf("{\n  \"solver\": \"%s\",\n  \"integrator\": \"%s\",\n  \"segments\": %d,\n  \"length\": %.17g,\n",
              solver.c_str(), integrator.c_str(), options.segments, rod.length);
  std::printf("  \"tip\": ");
  print_vector(solved.tip());
  std::printf(",\n  \"tip_frame\": [");
  for (int k = 0; k < 3; ++k) {
    if (k) std::printf(", ");
    print_vector(solved.tip_frame().col(k));
  }
  std::printf("],\n  \"root_moment\": ");
  print_vector(solved.root_moment);
  std::printf(",\n  \"terminal_force\": ");
  print_vector(solved.terminal_force);
  std::printf(",\n  \"terminal_torque\": ");
  print_vector(solved.terminal_torque);
  std::printf(",\n  \"iterations\": %d,\n  \"residual\": %.17g,\n  \"converged\": %s,\n  \"nodes\": [",
              solved.iterations, solved.residual, solved.converged ? "true" : "false");
  for (std::size_t i = 0; i < solved.nodes.size(); ++i) {
    std::printf(i ? ",\n    " : "\n    ");
    print_vector(solved.nodes[i]);
  }
  std::printf("\n  ]\n}\n");
  if (!solved.converged) {
    std::fprintf(stderr, "hairfit rod: shooting did not converge (residual %.3g); printed the best iterate\n",
                 solved.residual);
    return 1;
  }
  return 0;
}

}  // namespace hairfit::cli
