// What several benchmarks share: the bumpy torus they time on, and process CPU time.
#pragma once
#include <cmath>
#include <ctime>

#include "core/mesh.h"

namespace hairfit::bench {

// Closed torus (major radius 10 cm, minor 4 cm) with bumps, n×n quads split in two.
inline Mesh bumpy_torus(int n) {
  Mesh m;
  const double R = 10, r0 = 4;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / n;
      const double r = r0 * (1 + 0.08 * std::sin(5 * u) * std::sin(3 * v) + 0.03 * std::cos(11 * u + 7 * v));
      m.positions.push_back(Vec3((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)));
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j, b = ((i + 1) % n) * n + j, c = ((i + 1) % n) * n + (j + 1) % n, d = i * n + (j + 1) % n;
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  return m;
}

// CPU seconds of the whole process (all threads): the machine is shared, so wall time measures
// the other users as much as us; CPU time does not.
inline double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

}  // namespace hairfit::bench
