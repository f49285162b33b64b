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

// hair.relief_grain = "normals" (issue 48): the grain read from the spread of the hull's face
// normals over the hull above each scalp vertex (`lift`: cm along the vertex normal to the hull, the
// layer's thickness there), so that a thick layer's grain is read on its own surface and not from
// whatever edges lie within reach of the skin. Grooves tilt the normals across themselves only: the
// covariance of the normals' tangential parts about their mean (the mean removes the layer's own
// slope) has its minor eigenvector along them. It is taken at ½, 1 and 2 × `radius` and the most
// anisotropic kept, since grooves are 0.3–2 cm wide; sure is min(1, a / kSureSpread) with
// a = (λ1 − λ2)/(λ1 + λ2), which is 1 for ideal parallel grooves and falls with the head's own
// curvature, scan noise and grooves that run several ways.
constexpr double kSureSpread = 0.5;

std::vector<Vec3> relief_grain_of_normals(const ScalpChart& chart, const Mesh& hull, const std::vector<double>& lift,
                                          double radius, int threads);

}  // namespace hairfit
