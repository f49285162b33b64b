// A clamped rod that also carries point forces at interior points: the rod of integrate_rod with
// K forces F_1 … F_K (dimensionless, world axes) applied at the evenly spaced nodes
// s_k ≈ k/(K + 1). Between two of them the force resultant is again known in closed form,
//   n(s) = f_L + f·(1 − s) + Σ_{k : s_k > s} F_k,
// so the rod is integrated piece by piece, each piece with its own constant part of n; m and the
// frame run on continuously across s_k (a point force makes m' jump, not m). The shape stays C²
// and its curvature continuous. With K = 0 this is integrate_rod, operation for operation.
// Weightless or weighted rods only: a support's force resultant is integrated as a state, and the
// point forces would have to enter it (not supported; the caller refuses that combination).
#pragma once
#include <cmath>

#include "rod/rod_integrate.h"

namespace hairfit {

// The node at which point force k (1 ≤ k ≤ count) acts on a rod of `segments` steps; node 0 for
// k = 0 and the tip for k = count + 1, so that piece p runs from node p to node p + 1.
inline int point_force_node(int k, int count, int segments) {
  return static_cast<int>(std::lround(static_cast<double>(k) * segments / (count + 1)));
}

// integrate_rod with `count` point forces (3·count scalars, F_1 first; null when count is 0) at
// point_force_node; integrate_rod is this with none.
template <typename T>
void integrate_rod_with_point_forces(const RodModel& model, RodIntegrator integrator, int segments,
                                     const T* terminal_force, const T* root_moment, const T* point_forces, int count,
                                     T* terminal_moment, const RodTrace<T>& trace) {
  RodState<T> state;
  for (int a = 0; a < 3; ++a) {
    state.position[a] = T(0.0);
    state.moment[a] = root_moment[a];
  }
  for (int a = 0; a < 9; ++a) state.frame[a] = T(model.root_frame.data()[a]);
  for (int p = 0; p <= count; ++p) {
    const int first = point_force_node(p, count, segments), last = point_force_node(p + 1, count, segments);
    if (last <= first) continue;
    // The constant part of n on piece p: f_L plus every point force beyond the piece, summed from
    // the tip (each piece's sum afresh, so that no force is added and taken off again).
    T force[3] = {terminal_force[0], terminal_force[1], terminal_force[2]};
    for (int k = count - 1; k >= p; --k)
      for (int a = 0; a < 3; ++a) force[a] = force[a] + point_forces[3 * k + a];
    integrate_rod_steps(model, integrator, segments, first, last, force, state, trace);
  }
  for (int a = 0; a < 3; ++a) terminal_moment[a] = state.moment[a];
}

}  // namespace hairfit
