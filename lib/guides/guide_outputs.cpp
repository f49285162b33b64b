#include "guides/guide_outputs.h"

#include <string>

#include "io/atomic_file.h"
#include "io/number_text.h"

namespace hairfit {

void write_guides_csv(const std::filesystem::path& path, const Guides& guides, const Vec3& origin) {
  // With guides.point_forces = K, K·3 more columns at the end: F5 and each point force.
  const std::size_t point_forces = guides.items.empty() ? 0 : guides.items.front().point_forces.size();
  write_file_atomically(path, [&](std::ostream& out) {
    out << "guide,root_x,root_y,root_z,length_cm,force_x,force_y,force_z,root_moment_x,root_moment_y,root_moment_z,"
           "terminal_torque_x,terminal_torque_y,terminal_torque_z,force_scale_dyn,moment_scale_dyn_cm,iterations,"
           "evaluations,f1_direction,f2_similarity,f3_boundary,f4_density,cost,converged,termination,contact_force_dyn_cm,"
           "contact_share";
    if (point_forces > 0) out << ",f5_point_forces";
    for (std::size_t k = 1; k <= point_forces; ++k)
      for (const char* axis : {"x", "y", "z"}) out << ",point_force_" << k << '_' << axis;
    out << '\n';
    // Every number round-trips: 17 significant digits, as printf's %.17g writes them.
    std::string line;
    char buffer[64];
    auto number = [&](double v) {
      line += ',';
      line.append(buffer, format_general(buffer, v, 17));
    };
    auto vector = [&](const Vec3& v) {
      for (int a = 0; a < 3; ++a) number(v[a]);
    };
    for (std::size_t i = 0; i < guides.items.size(); ++i) {
      const Guide& g = guides.items[i];
      line = std::to_string(i);
      vector(origin == Vec3::Zero() ? g.root : Vec3(g.root + origin));
      number(g.length);
      vector(g.force);
      vector(g.root_moment);
      vector(g.terminal_torque);
      number(g.force_scale);
      number(g.moment_scale);
      line += ',' + std::to_string(g.iterations) + ',' + std::to_string(g.evaluations);
      for (double f : {g.f1, g.f2, g.f3, g.f4, g.cost}) number(f);
      line += g.converged ? ",1," : ",0,";
      line += g.termination;
      number(g.contact_force);
      number(g.contact_share);
      if (point_forces > 0) number(g.f5);
      for (const Vec3& f : g.point_forces) vector(f);
      line += '\n';
      out << line;
    }
  });
}

}  // namespace hairfit
