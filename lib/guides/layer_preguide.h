// Pre-guides that stay in a thin hair layer (preguides.immersion = "layer", issue 23). The paper's
// pre-guide is pulled by a terminal force held normal to its initial axis until its tip is
// immersed: its curvature falls linearly to zero at the tip, so on a curved head a long pre-guide
// in a thin shell runs straight out of the layer before its tip dips back in. Here the rod is bent,
// in the same plane (the normal's and the growth direction's), by a terminal force P·d1 and a root
// couple μ·d2 together: curvature that can be uniform (the couple) or fall toward the tip (the
// force), so the rod can follow the head's curve. (P, μ) are the load whose shape lies closest,
// past its first quarter, to the immersion depth: the layer coordinate
//
//   λ(p) = Φ_S(p) / (Φ_S(p) − Φ_V(p))   (0 on the scalp, 1 on the hull; < 0 in the head, > 1 outside)
//
// at 1 − depth share (preguides.depth_range, shallow at the top of the head, deeper low down),
// with every excursion outside [0, 1] penalised, by Levenberg–Marquardt on the two parameters.
// With the growth field the rod also follows it, on all six load components; a rod styled along
// its flow (PreguideOptions::styled, guides/styled_rest.h) follows its rest shape's tangents
// instead, climb included, so that the loads only correct the path it rests along.
// Internal to lib/guides.
#pragma once
#include "guides/preguides.h"

namespace hairfit {

// λ(p) as above inside the layer, continued outside it by the distance in units of `scale` (cm,
// the layer's thickness at the root): 1 + Φ_V/scale beyond the hull, Φ_S/scale in the head, so
// it is continuous, grows with the distance out of the layer and never divides by a vanishing
// thickness.
double layer_coordinate(const Boundary& boundary, const Vec3& p, double scale);

// The pre-guide of root i, in the layer (see above). Weightless rods only: under gravity the
// pipeline uses the paper's construction.
PreGuide solve_layer_preguide(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& options);

// The cost the fit minimises for root i at terminal force P = `force` along d1 and root couple
// μ = `couple` along d2 (dimensionless), for checking the solution.
double layer_preguide_cost(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& options,
                           double force, double couple);

}  // namespace hairfit
