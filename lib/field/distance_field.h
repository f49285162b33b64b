// Narrow-band signed distance fields of raw triangle meshes (paper §3.2, docs/design.md §2).
//
// What the values mean (full statement: spec/fields.md):
// - Magnitude. Within the band (|d| ≤ band·voxel) a grid sample is the exact Euclidean distance
//   from the sample point to the closest point of the mesh, to round-off (≤ 1e-9 voxel), found by
//   the closest-point transform: every face, edge and vertex scan-converts a polyhedron bounding
//   its Voronoi region within the band (Mauch 2003). Beyond the band a sample is the trilinear
//   interpolation of a coarse grid (spacing H = floor(2·band) voxels) of distances to mesh points:
//   coarse nodes within band + √3·H of the mesh are exact (a CPT scan of the coarse grid), farther
//   ones hold the distance to a mesh point handed on by their neighbours (closest-point
//   propagation, never below the true distance). Where that interpolant is not above the band's
//   width, the sample is the exact distance to the nearest of the features the cell's corners are
//   closest to, so no sample beyond the band reads less than the band's width.
// - Sign. With a RobustInside (docs/design.md §2: generalized winding numbers), every band sample
//   and every coarse node takes the sign of w > ½ at its own node: decided from the winding
//   number's exact jumps across the triangles on the grid's edges and a bound on its change that
//   only the rims make (field/winding_signs.h), the winding number itself asked only where those
//   do not decide. A sample beyond the band takes the sign its coarse cell agrees on (its 8
//   corners and every band sample in it), or where the cell does not agree the robust inside's at
//   its node. Without one, the sign is the side of the closest feature's angle-weighted
//   pseudo-normal (Bærentzen & Aanæs 2005): behind the sheet itself, + beyond an open rim; beyond
//   the band, the sign of the interpolated signed coarse values.
// - No phantom surface. Where a cell's corners differ in sign although no surface can pass
//   between them (|d_a| + |d_b| > |a − b| for every such pair of corners, as across the seam where
//   an open mesh's inside changes in empty space), a lookup reads the interpolated magnitude with
//   the sign of the interpolated signed samples: the value jumps there but never comes near zero,
//   so the mesh is the field's only zero level set. Beyond the band |value| ≥ the band's width.
// - Queries interpolate the samples trilinearly (a continuous, piecewise-trilinear field except
//   across such seams); the gradient is that of the interpolant, defined everywhere. Outside the
//   grid, value = value at the clamped point + sign · distance to the grid box. The guide optimiser
//   builds Ceres jets from value and gradient by the chain rule (no Ceres here).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/types.h"
#include "field/winding_soup.h"

namespace hairfit {

struct FieldSpec {
  double voxel = 0.25;         // cm: grid spacing h
  double band = 4.0;           // voxels: half-width of the band of exact distances (≥ 1)
  double margin = 2.0;         // cm of grid beyond the mesh's bounding box on every side
  double max_memory_gib = 4.0; // refuse (InputError) grids whose build needs more than this
  std::string name = "mesh";   // names the mesh (its file) in error messages
};

struct FieldValueGradient {
  double value = 0.0;        // cm, signed
  Vec3 gradient = Vec3::Zero();  // dimensionless (cm per cm)
};

struct FieldSmooth {
  double value = 0.0;            // cm, signed
  Vec3 gradient = Vec3::Zero();  // dimensionless
  Mat3 hessian = Mat3::Zero();   // 1/cm
};

struct CarriedField;

// What a field is rebuilt from (the stage cache stores a field as these): its grid, its band and
// every node's sample and lookup flags, as DistanceField's accessors give them.
struct DistanceFieldParts {
  Vec3 origin = Vec3::Zero();
  double voxel = 1.0;
  Vec3i dims = Vec3i::Zero();
  double band_width = 0.0;
  int64_t band_voxels = 0;
  std::vector<double> samples;
  std::vector<std::uint8_t> flags;
};

class DistanceField {
 public:
  // The field a DistanceField's parts describe. Throws std::invalid_argument where they cannot be
  // one: negative dimensions, a voxel that is not finite and > 0, or sample and flag counts that
  // are not one per node.
  static DistanceField from_parts(DistanceFieldParts parts);
  // A signed implicit function sampled on a grid (not a mesh's distance): no node is in a band of
  // exact distances, so distance_lower_bound() bounds nothing; the lookup flags follow from the
  // samples as make_distance_field's do. Throws std::invalid_argument as from_parts does.
  static DistanceField from_samples(const Vec3& origin, double voxel, const Vec3i& dims, std::vector<double> samples,
                                    int threads = 1);
  // The samples (x fastest) and their lookup flags, as from_parts takes them.
  const std::vector<double>& samples() const { return *samples_; }
  const std::vector<std::uint8_t>& flags() const { return *flags_; }

  // Grid geometry: sample (i,j,k) sits at origin + h·(i,j,k), 0 ≤ i < dims.x() etc.
  const Vec3& origin() const { return origin_; }
  double voxel() const { return h_; }
  const Vec3i& dims() const { return dims_; }
  double band_width() const { return band_cm_; }  // cm: |d| ≤ this is exact
  int64_t band_voxels() const { return band_voxels_; }

  // The sample at a grid node (cm, signed); exact when in_band(i,j,k).
  double sample(int i, int j, int k) const;
  bool in_band(int i, int j, int k) const;

  // Trilinear interpolation of the samples at a point p (cm), and its gradient. Defined for any
  // finite p, also outside the grid (see the header comment).
  double value(const Vec3& p) const;
  Vec3 gradient(const Vec3& p) const;
  FieldValueGradient value_and_gradient(const Vec3& p) const;
  // The uniform cubic B-spline whose control points are the samples, at p: C² (where the
  // trilinear interpolant is only C⁰), so forces built from its gradient are C¹ (the scalp's
  // contact). It reproduces linear fields exactly and smooths others by about a voxel. Node
  // indices beyond the grid clamp to its faces.
  FieldSmooth smooth(const Vec3& p) const;
  // The sample at the grid node nearest p (clamped to the grid). The 4×4×4 samples smooth(p)
  // blends lie within 2√3 voxels of that node, so where samples are distances (1-Lipschitz)
  // smooth(p).value ≥ nearest_sample(p) − 2√3·h.
  double nearest_sample(const Vec3& p) const;
  // A distance (cm) that the true distance from p to the mesh is never below: at the grid node
  // nearest p its exact |sample| in the band, the band's width beyond it (every node nearer the
  // mesh is in the band), less the node's distance from p (distance is 1-Lipschitz). May be
  // negative; exact tests (the strands' chords against the scalp) skip what it rules out.
  double distance_lower_bound(const Vec3& p) const;
  // Which side of the surface p lies on, when the samples alone decide it: +1 where value(p) > 0
  // and −1 where value(p) < 0 for certain (every sample the interpolation at p reads lies on that
  // side, beyond 1e-290 cm), 0 where only value(p) can tell (near the surface; non-finite p).
  // Several times cheaper than value(), for callers that need only the sign.
  int side(const Vec3& p) const;
  // side() at every point (x[i], y[j], z[k]) of a lattice, out[i + nx·(j + ny·k)]: the same
  // answers, found from per-axis cell tables instead of point by point.
  std::vector<std::int8_t> sides_on_lattice(const std::vector<double>& x, const std::vector<double>& y,
                                            const std::vector<double>& z, int threads = 1) const;

  // Bytes of the field's samples. The lookup flags (one byte per node, see below) are not counted.
  int64_t memory_bytes() const;

 private:
  friend DistanceField make_distance_field(const Mesh&, const FieldSpec&, int, const RobustInside&);
  friend CarriedField make_distance_field_carrying(const Mesh&, const std::vector<double>&, const FieldSpec&, int,
                                                  const RobustInside&);
  DistanceField() = default;  // built only by make_distance_field
  // Both builders: with `vertex_values`, the carried values go to `carried`.
  static DistanceField build(const Mesh& mesh, const FieldSpec& spec, int threads, const RobustInside& inside,
                             const std::vector<double>* vertex_values, std::vector<double>* carried);
  // Sets the lookup flags from the samples (every node's, band and beyond), and the geometry.
  void finish(std::vector<double> samples, std::vector<std::uint8_t> in_band, int threads);
  void set_geometry();  // upper_, last_node_ and stride_ from origin_, h_ and dims_
  template <bool kGradient>
  void inside_grid(const Vec3& p, double& value, Vec3* gradient) const;  // p within the grid box
  int64_t index(int i, int j, int k) const { return i + int64_t(dims_.x()) * (j + int64_t(dims_.y()) * k); }

  // flags_ bits: the node is in the band; the cell whose lowest corner is this node is a seam (its
  // corners differ in sign but no surface passes between them: lookups read sign × magnitude);
  // every sample its lookups read is > 1e-290 (positive) or < −1e-290 (negative), so the value
  // has that sign.
  static constexpr std::uint8_t kInBand = 1, kCellSeam = 2, kCellPositive = 4, kCellNegative = 8;

  Vec3 origin_ = Vec3::Zero();
  double h_ = 1.0;
  Vec3i dims_ = Vec3i::Zero();
  double band_cm_ = 0.0;
  int64_t band_voxels_ = 0;
  Vec3 upper_ = Vec3::Zero();      // the grid's far corner, origin + h·(dims − 1)
  Vec3 last_node_ = Vec3::Zero();  // dims − 1, as doubles
  std::array<int64_t, 3> stride_{};  // index steps along x, y, z
  // Samples: the signed distance in the band, the signed far-field value elsewhere, so that a
  // lookup reads its 8 corners without asking which kind each is.
  std::shared_ptr<const std::vector<double>> samples_;
  std::shared_ptr<const std::vector<std::uint8_t>> flags_;
};

// Builds the field of `mesh` (positions in cm) on a grid covering its bounding box plus
// spec.margin. Exact in the band; signed by `inside` where given (see the header comment for the
// rest). Throws InputError for an empty mesh, a non-finite coordinate, an index out of range, a
// bad spec, or a grid needing more than spec.max_memory_gib (the message names the grid and a
// voxel size that would fit). `threads` (0 = all) changes only the speed: the result is
// bit-identical for any count.
DistanceField make_distance_field(const Mesh& mesh, const FieldSpec& spec, int threads = 0,
                                  const RobustInside& inside = {});

// The field, and a value given at the mesh's vertices carried to every band sample: the value at
// the sample's closest point on the mesh, interpolated linearly over the closest face or edge
// (vertices at one position take the smallest of their values). NaN beyond the band. What a
// caller needs who reads a quantity of the surface's nearest point at grid nodes (prepare's
// distance from the hairline), exactly and without a search of its own.
struct CarriedField {
  DistanceField field;
  std::vector<double> carried;  // per node, x fastest (DistanceField's node order)
};
CarriedField make_distance_field_carrying(const Mesh& mesh, const std::vector<double>& vertex_values,
                                          const FieldSpec& spec, int threads = 0, const RobustInside& inside = {});

// The grid make_distance_field would allocate, and the bytes its build needs at peak.
struct FieldGridPlan {
  Vec3 origin = Vec3::Zero();
  Vec3i dims = Vec3i::Zero();
  int coarse_factor = 1;
  double bytes = 0.0;
};
FieldGridPlan plan_field_grid(const Mesh& mesh, const FieldSpec& spec);

// Throws the InputError make_distance_field would throw for a grid larger than
// spec.max_memory_gib (or a bad spec or mesh), without building anything: how inputs are checked
// before a run writes its first file.
void require_field_fits(const Mesh& mesh, const FieldSpec& spec);

}  // namespace hairfit
