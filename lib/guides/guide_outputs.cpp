#include "guides/guide_outputs.h"

#include <cstdio>

#include "io/atomic_file.h"

namespace hairfit {

void write_guides_csv(const std::filesystem::path& path, const Guides& guides) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "guide,root_x,root_y,root_z,length_cm,force_x,force_y,force_z,root_moment_x,root_moment_y,root_moment_z,"
           "terminal_torque_x,terminal_torque_y,terminal_torque_z,force_scale_dyn,moment_scale_dyn_cm,iterations,"
           "evaluations,f1_direction,f2_similarity,f3_boundary,f4_density,cost,converged,termination\n";
    char line[1024];
    for (std::size_t i = 0; i < guides.items.size(); ++i) {
      const Guide& g = guides.items[i];
      std::snprintf(line, sizeof line,
                    "%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d,"
                    "%.17g,%.17g,%.17g,%.17g,%.17g,%d,%s\n",
                    i, g.root.x(), g.root.y(), g.root.z(), g.length, g.force.x(), g.force.y(), g.force.z(),
                    g.root_moment.x(), g.root_moment.y(), g.root_moment.z(), g.terminal_torque.x(),
                    g.terminal_torque.y(), g.terminal_torque.z(), g.force_scale, g.moment_scale, g.iterations,
                    g.evaluations, g.f1, g.f2, g.f3, g.f4, g.cost, g.converged ? 1 : 0, g.termination.c_str());
      out << line;
    }
  });
}

}  // namespace hairfit
