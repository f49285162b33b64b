// A smooth unit tangent field on a surface mesh, aligned with guidance where it is given
// (Knöppel, Crane, Pinkall and Schröder 2013, "Globally optimal direction fields", §6 with the
// alignment term, for 1-direction fields): one sparse symmetric positive definite solve for the
// per-vertex vectors u minimising
//
//   E(u) = Σ_edges w_ij |u_j − r_ij u_i|²  +  (1/ℓ²) Σ_i M_i c_i |u_i − q̂_i|²,
//
// where u_i is a complex number in vertex i's tangent basis, w_ij are the cotangent weights
// (clamped at 0), r_ij = e^{iρ_ij} transports a tangent vector from i to j (the minimal rotation
// taking n_i to n_j, so a flat or developable patch transports exactly), M_i is the vertex's
// lumped area, q̂_i the unit guidance and c_i ∈ [0, 1] its confidence (the guidance's length).
// ℓ (cm) is the smoothing length: the field averages the guidance over about that distance, and
// where no guidance is given it is the smoothest continuation. The field is u/|u|; it vanishes only
// at its singularities, where |u| falls to nothing.
#pragma once
#include <vector>

#include "core/mesh.h"

namespace hairfit {

struct DirectionFieldOptions {
  double smoothing = 2.0;  // ℓ, cm (> 0)
};

struct DirectionField {
  std::vector<Vec3> directions;  // per vertex: unit tangent (world axes); zero at an isolated zero of u
  std::vector<double> magnitude; // per vertex: |u_i| (≈ 1 where guidance agrees, → 0 at singularities)
};

// `normals` are unit vertex normals (one side, consistently); `guidance` per vertex is a vector
// whose tangential part gives the direction and whose length (clamped to 1) its confidence; zero
// where there is none. Throws std::invalid_argument for mismatched sizes or ℓ ≤ 0.
DirectionField smoothest_aligned_field(const Mesh& mesh, const std::vector<Vec3>& normals,
                                       const std::vector<Vec3>& guidance, const DirectionFieldOptions& options = {});

// The field at a point of triangle t with barycentric weights b and unit normal `normal`: the
// corner directions weighted by b, projected onto the tangent plane and normalised; `fallback`
// (a unit tangent) where they cancel.
Vec3 field_direction(const Mesh& mesh, const DirectionField& field, int triangle, const Vec3& barycentric,
                     const Vec3& normal, const Vec3& fallback);

// Per triangle, the field's index (its turning about the triangle relative to the transport,
// plus the transport's holonomy, over 2π): 0 where the field is regular, ±1 at a simple
// singularity. Triangles are traversed in their own winding, normals as given.
std::vector<int> field_indices(const Mesh& mesh, const std::vector<Vec3>& normals, const DirectionField& field);

}  // namespace hairfit
