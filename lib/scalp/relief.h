// The hull's grain over the scalp (hair.flow = "relief", issue 23): on a sculpture the carved
// locks, on a character's shell its cards, run where the hair runs. Their ridges and grooves are
// the hull's edges with large dihedral angles lying along them, so the normal-cycle curvature
// tensor (Cohen-Steiner and Morvan 2003) T = Σ_e β_e·|e|·ê êᵀ over the edges near a point has its
// largest eigenvector along the ridges (the direction of least curvature) wherever they are
// parallel. Per scalp vertex the tensor of the hull edges within `radius` is projected onto the
// vertex's tangent plane; its principal direction, scaled by how sure it is, is the grain: a line,
// not an arrow (either sign), zero where the hull is smooth or its relief runs every way. Sure is
// min(1, a / kSureAnisotropy) with a = (λ1 − λ2)/(λ1 + λ2): with unsigned angles an edge at α to
// a family of parallel grooves bends by cos²α of the most, so such grooves read at most a = ½
// over a triangulation, less on a curved hull (a sphere's own bending adds to both eigenvalues).
// Grooves 0.3 cm deep every 2 cm on a sphere of radius 9 read 0.13–0.4; the smooth sphere 0.001.
#pragma once
#include <vector>

#include "core/mesh.h"
#include "scalp/chart.h"

namespace hairfit {

constexpr double kSureAnisotropy = 0.25;

// Rim edges (on one triangle only: a card's or a sheet's border) count with β = π/2.
std::vector<Vec3> relief_grain(const ScalpChart& chart, const Mesh& hull, double radius, int threads);

}  // namespace hairfit
