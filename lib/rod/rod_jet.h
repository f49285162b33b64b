// The rod integrator over Ceres jets, for code that needs derivatives of a rod with respect to
// its loads (the guides optimiser: η̃ = (f_L, m(0)), six parameters). Include this header only
// where jets are needed; everything else uses rod/rod.h and rod/rod_integrate.h, which name no
// Ceres type.
//
// integrate_rod<T> (rod_integrate.h) is instantiated, in rod_integrate.cpp, for exactly:
//   double, RodJet3 (Newton on m(0) in shooting), RodJet6 (the six load parameters);
// integrate_rod_steps also for RodJet<9>, RodJet<12> and RodJet<15> (the six plus 1–3 interior
// point forces, rod_point_forces.h). Any other scalar fails to link: add its instantiation there.
#pragma once
#include <ceres/jet.h>

#include "rod/rod_integrate.h"

namespace hairfit {

using RodJet3 = ceres::Jet<double, 3>;
using RodJet6 = ceres::Jet<double, 6>;
template <int N>
using RodJet = ceres::Jet<double, N>;

}  // namespace hairfit
