// The principal-guide objective's residuals, F1–F4 (paper eq. 6–9, docs/design.md §5), templated
// on the scalar so that Ceres' jets flow through the rod and the fields: what one guide's rod
// shape pays at its samples, with each term's equation beside its code. Internal to lib/guides:
// objective.cpp minimises it.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "guides/objective.h"
#include "rod/rod_jet.h"
#include "rod/rod_point_forces.h"

namespace hairfit {

using Jet = RodJet6;

// A value tabulated in double, read at a jet point p: the value at p's scalar part, and its
// derivative by the chain rule through the table's gradient there (STYLE.md).
template <int N>
RodJet<N> chained(double value, const Vec3& gradient, const RodJet<N>* p) {
  RodJet<N> out(value);
  out.v = gradient.x() * p[0].v + gradient.y() * p[1].v + gradient.z() * p[2].v;
  return out;
}

// A distance field's value.
inline double field_at(const DistanceField& field, const double* p) { return field.value(Vec3(p[0], p[1], p[2])); }
template <int N>
RodJet<N> field_at(const DistanceField& field, const RodJet<N>* p) {
  const FieldValueGradient vg = field.value_and_gradient(Vec3(p[0].a, p[1].a, p[2].a));
  return chained(vg.value, vg.gradient, p);
}

// The grid's trilinear value (BOM occupancy) and, for jets, its exact piecewise-trilinear gradient.
inline double density_at(const DensityGrid& grid, const double* p) { return grid.value(Vec3(p[0], p[1], p[2])); }
template <int N>
RodJet<N> density_at(const DensityGrid& grid, const RodJet<N>* p) {
  const DensityValueGradient vg = grid.value_and_gradient(Vec3(p[0].a, p[1].a, p[2].a));
  return chained(vg.value, vg.gradient, p);
}

// CDM: ⟨∇Φρ(p), t⟩ with ∇Φρ by central differences; for jets d⟨g, t⟩ = (Jᵀt)·dp + g·dt, J the
// derivative of the central-difference gradient in p.
inline double density_slope(const DensityGrid& grid, const double* p, const double* t) {
  return grid.central_gradient(Vec3(p[0], p[1], p[2])).dot(Vec3(t[0], t[1], t[2]));
}
template <int N>
RodJet<N> density_slope(const DensityGrid& grid, const RodJet<N>* p, const RodJet<N>* t) {
  const DensityGradientJacobian gj = grid.central_gradient_and_jacobian(Vec3(p[0].a, p[1].a, p[2].a));
  const Vec3 ta(t[0].a, t[1].a, t[2].a);
  const Vec3 jt = gj.jacobian.transpose() * ta;  // ∂⟨g, t⟩/∂p
  RodJet<N> out(gj.gradient.dot(ta));
  out.v = jt.x() * p[0].v + jt.y() * p[1].v + jt.z() * p[2].v;
  for (int a = 0; a < 3; ++a) out.v += gj.gradient[a] * t[a].v;
  return out;
}

// The C¹ surcharge step of surcharge_step (density_term.h), for jets too.
template <typename T>
T surcharge_residual(const T& occupancy, double threshold, double width) {
  const T x = (occupancy - T(threshold)) / T(width) + T(0.5);
  if (!(x > T(0))) return T(0);
  if (!(x < T(1))) return T(1);
  return x * x * (T(3) - T(2) * x);
}

// How far a sample lies outside the acceptable region, as a C¹ step over one density voxel `h`:
// 0 inside, 1 from h beyond a surface on; the two surfaces add (a sample is never beyond both).
template <typename T>
T outside_step(const T& u, double h) {
  if (!(u > T(0))) return T(0);
  if (!(u < T(h))) return T(1);
  const T x = u / T(h);
  return x * x * (T(3) - T(2) * x);
}

// The boundary residual φ(u) of a sample lying u cm beyond a surface (u > 0: outside the
// acceptable region). Smooth form: √c_d·S((u + w)/w) + H(u): the step of eq. 9 rises over the last
// w cm inside the surface (S the C¹ smoothstep), so the full c_d applies at the surface itself and
// the optimiser feels it coming; beyond the surface the C¹ Huber ramp H grows like u.
// Paper form: √(|u| + c_d·[u > 0]), eq. 9 exactly (not differentiable at u = 0).
// Layer form: w replaced by min(w, ¼·thickness), thickness = Φ_S − Φ_V at the sample (−(u_S + u_V),
// the sum of both surfaces' u negated), floored at a hundredth of w; √c_d·x² over the ramp and the
// line of the same slope beyond (C¹, strictly increasing from the ramp on: the smooth form's
// steps are flat at the surface, where a thin shell's samples sit).
template <typename T>
T boundary_residual(const T& u, BoundaryForm form, double c_d, double w_cm, const T& both) {
  using std::sqrt;
  if (form == BoundaryForm::paper) {
    const T cost = (u > T(0) ? u + T(c_d) : -u) + T(1e-12);
    return sqrt(cost);
  }
  T w = T(w_cm);
  if (form == BoundaryForm::layer) {
    const T quarter = T(-0.25) * both;
    if (quarter < w) w = quarter > T(0.01 * w_cm) ? quarter : T(0.01 * w_cm);
    // √c_d·x² over the ramp, then on with the slope it reaches: strictly increasing through the
    // surface, so a sample just inside or just beyond it is still pushed back.
    if (!(u > -w)) return T(0);
    const T x = (u + w) / w;
    if (u <= T(0)) return T(std::sqrt(c_d)) * x * x;
    return T(std::sqrt(c_d)) * (T(1) + T(2) * u / w);
  }
  if (!(u > -w)) return T(0);
  const T ramp = u <= T(0) ? T(0) : (u >= w ? u - T(0.5) * w : u * u / (T(2) * w));
  if (u >= T(0)) return T(std::sqrt(c_d)) + ramp;
  const T x = (u + w) / w;
  return T(std::sqrt(c_d)) * x * x * (T(3) - T(2) * x);
}

// The F1 and F2 residuals of all neighbours at one sample share the guide's d3 (or Darboux vector)
// u: Σ_j s_j²|u − a_j|² = S|u − ā|² + Σ_j s_j²|a_j − ā|² with S = Σ_j s_j² and ā = Σ_j s_j²a_j / S.
// So the optimiser sees one residual √S·(u − ā) per sample and term, and the rest is a constant.
struct MergedTargets {
  std::vector<double> scale;  // √S per sample
  std::vector<Vec3> mean;     // ā per sample
  double constant = 0.0;      // Σ over samples of Σ_j s_j²|a_j − ā|²
};

// `square_scale(nb, k)`: s_j² of neighbour nb at sample k; `target(nb, k)`: a_j.
template <typename SquareScale, typename Target>
MergedTargets merge_targets(const GuideTargets& t, const SquareScale& square_scale, const Target& target) {
  MergedTargets m;
  const std::size_t samples = t.sample_nodes.size();
  m.scale.resize(samples);
  m.mean.resize(samples);
  for (std::size_t k = 0; k < samples; ++k) {
    double total = 0.0;
    Vec3 sum = Vec3::Zero();
    for (const GuideTargets::Neighbour& nb : t.neighbours) {
      total += square_scale(nb, k);
      sum += square_scale(nb, k) * target(nb, k);
    }
    m.scale[k] = std::sqrt(total);
    m.mean[k] = total > 0.0 ? Vec3(sum / total) : Vec3::Zero();
    for (const GuideTargets::Neighbour& nb : t.neighbours)
      m.constant += square_scale(nb, k) * (target(nb, k) - m.mean[k]).squaredNorm();
  }
  return m;
}

class GuideCost {
 public:
  // `merged`: the F1 and F2 blocks as MergedTargets (3 residuals per sample each, the sum of
  // squares short by merged_constant()), as the optimiser sees them; otherwise one block of 3 per
  // neighbour and sample, each term's residuals as the paper writes them (guide_residuals, terms).
  explicit GuideCost(const GuideTargets& t, bool merged = false)
      : t_(t), merged_(merged), is_sample_(t.rod.segments + 1, 0) {
    for (int node : t.sample_nodes) is_sample_[node] = 1;
    if (!merged) return;
    const GuideWeights& w = t.weights;
    direction_ = merge_targets(
        t, [&](const GuideTargets::Neighbour& nb, std::size_t k) { return w.direction * nb.weight_at(k) * t.sample_weights[k] / 2.0; },
        [](const GuideTargets::Neighbour& nb, std::size_t k) { return nb.tangents[k]; });
    similarity_ = merge_targets(
        t, [&](const GuideTargets::Neighbour& nb, std::size_t k) { return w.similarity * nb.weight_at(k) * t.sample_weights[k]; },
        [](const GuideTargets::Neighbour& nb, std::size_t k) { return nb.darboux[k]; });
  }

  int residual_count() const { return shape_residual_count() + 3 * t_.point_forces; }
  // The residuals of the shape alone (F1–F4), before the point forces' (F5).
  int shape_residual_count() const {
    const std::size_t per_term = merged_ ? 3 : 3 * t_.neighbours.size();
    return static_cast<int>(t_.sample_nodes.size() * (2 * per_term + 2 + density_per_sample()));
  }
  // Σr² of the full residuals minus Σr² of these (0 unless merged).
  double merged_constant() const { return direction_.constant + similarity_.constant; }
  // F4 residuals per sample: none without a grid; CDM the slope, BOM occupancy and surcharge;
  // both then the outside residual.
  int density_per_sample() const {
    if (!t_.density) return 0;
    return t_.density_term.model == GuideDensityModel::continuous ? 2 : 3;
  }

  // Residuals in blocks: F1 (3 per neighbour and sample; merged: 3 per sample), F2 (the same),
  // F3 (scalp and volume per sample), F4 (density_per_sample per sample, only with a grid), F5
  // (3 per interior point force). Σr² (+ merged_constant()) = Σ wᵢFᵢ + w5·F5 exactly, with the
  // trapezoidal rule for ∫ds. eta: (f_L, m(0), F_1 … F_K), K = targets.point_forces.
  template <typename T>
  bool operator()(const T* eta, T* residuals) const {
    const int n = t_.rod.segments + 1;
    // Every evaluation rewrites the sample nodes of the trace, the only ones the residuals read,
    // so each thread keeps one buffer: fresh vectors of jets would be zero-filled and freed at
    // every evaluation (2.6 % of the guide solve).
    thread_local std::vector<T> trace;
    trace.resize(15 * static_cast<std::size_t>(n));
    T* nodes = trace.data();
    T* frames = nodes + 3 * n;
    T* curvature = frames + 9 * n;
    T m1[3];
    const int point_forces = std::min(t_.point_forces, kPointForcesCarried<T>);
    integrate_rod_with_point_forces<T>(t_.model, t_.rod.integrator, t_.rod.segments, eta, eta + 3, eta + 6,
                                       point_forces, m1,
                                       RodTrace<T>{nodes, frames, curvature, nullptr, is_sample_.data()});
    // F5 = Σ|F_k|²: the layer pushes no harder than the shape needs.
    T* forces = residuals + shape_residual_count();
    const T scale = T(std::sqrt(t_.point_force_weight));
    for (int i = 0; i < 3 * point_forces; ++i) forces[i] = scale * eta[6 + i];
    return residuals_of_shape(nodes, frames, curvature, residuals);
  }

  // The residuals of a multiple-shooting solution, traced piece by piece.
  bool residuals_of_solution(const ShootingResult& solution, double* residuals) const {
    const int n = t_.rod.segments + 1;
    std::vector<double> nodes(3 * n), frames(9 * n), curvature(3 * n);
    trace_pieces(t_.model, t_.rod.integrator, t_.rod.segments, solution,
                 RodTrace<double>{nodes.data(), frames.data(), curvature.data(), nullptr});
    return residuals_of_shape(nodes.data(), frames.data(), curvature.data(), residuals);
  }

  // The residuals of a traced rod shape (nodes with the root at the origin in units of L, frames,
  // material curvature), however it was solved.
  template <typename T>
  bool residuals_of_shape(const T* nodes, const T* frames, const T* curvature, T* residuals) const {
    T* r = residuals;
    const std::size_t samples = t_.sample_nodes.size();
    if (merged_) {
      for (std::size_t k = 0; k < samples; ++k) {
        const T scale = T(direction_.scale[k]);
        const T* d3 = &frames[9 * t_.sample_nodes[k] + 6];
        for (int a = 0; a < 3; ++a) *r++ = scale * (d3[a] - T(direction_.mean[k][a]));
      }
      for (std::size_t k = 0; k < samples; ++k) {
        const T scale = T(similarity_.scale[k]);
        const T* R = &frames[9 * t_.sample_nodes[k]];
        const T* kappa = &curvature[3 * t_.sample_nodes[k]];
        for (int a = 0; a < 3; ++a) {
          const T omega = R[a] * kappa[0] + R[3 + a] * kappa[1] + R[6 + a] * kappa[2];
          *r++ = scale * (omega - T(similarity_.mean[k][a]));
        }
      }
    } else {
      full_direction_and_similarity(frames, curvature, r);
    }
    return boundary_and_density(nodes, frames, r);
  }

 private:
  template <typename T>
  void full_direction_and_similarity(const T* frames, const T* curvature, T*& r) const {
    const GuideWeights& w = t_.weights;
    const std::size_t samples = t_.sample_nodes.size();
    for (const GuideTargets::Neighbour& nb : t_.neighbours)
      for (std::size_t k = 0; k < samples; ++k) {
        // 1 − cos φ = ½|t_G − t_j|² for unit tangents (the frame keeps d3 unit exactly).
        const T scale = T(std::sqrt(w.direction * nb.weight_at(k) * t_.sample_weights[k] / 2.0));
        const T* d3 = &frames[9 * t_.sample_nodes[k] + 6];
        for (int a = 0; a < 3; ++a) *r++ = scale * (d3[a] - T(nb.tangents[k][a]));
      }
    for (const GuideTargets::Neighbour& nb : t_.neighbours)
      for (std::size_t k = 0; k < samples; ++k) {
        // Darboux vectors in world axes, per unit normalised arc length: R·κ·L.
        const T scale = T(std::sqrt(w.similarity * nb.weight_at(k) * t_.sample_weights[k]));
        const T* R = &frames[9 * t_.sample_nodes[k]];
        const T* kappa = &curvature[3 * t_.sample_nodes[k]];
        for (int a = 0; a < 3; ++a) {
          const T omega = R[a] * kappa[0] + R[3 + a] * kappa[1] + R[6 + a] * kappa[2];
          *r++ = scale * (omega - T(nb.darboux[k][a]));
        }
      }
  }

  template <typename T>
  bool boundary_and_density(const T* nodes, const T* frames, T* r) const {
    const GuideWeights& w = t_.weights;
    const std::size_t samples = t_.sample_nodes.size();
    // One pass over the samples: each sample's two field values serve its boundary residuals
    // (first, two per sample) and its density residuals (after them, `per_sample` each), where a
    // pass per term looked the fields up twice.
    const DensityTermOptions& d = t_.density_term;
    const std::size_t per_sample = d.model == GuideDensityModel::continuous ? 2 : 3;
    T* density_r = r + 2 * samples;
    for (std::size_t k = 0; k < samples; ++k) {
      const int node = t_.sample_nodes[k];
      T p[3];
      for (int a = 0; a < 3; ++a) p[a] = T(t_.root[a]) + T(t_.length) * nodes[3 * node + a];
      const T beyond_scalp = -field_at(*t_.boundary->scalp, p);
      const T beyond_volume = field_at(*t_.boundary->volume, p);
      const T scale = T(std::sqrt(w.boundary * t_.sample_weights[k]));
      const T both = beyond_scalp + beyond_volume;  // −(the layer's thickness here), for the layer form
      r[2 * k] = scale * boundary_residual(beyond_scalp, t_.form, t_.outside_penalty, t_.boundary_width, both);
      r[2 * k + 1] = scale * boundary_residual(beyond_volume, t_.form, t_.outside_penalty, t_.boundary_width, both);
      if (!t_.density) continue;
      T* out = density_r + per_sample * k;
      if (d.model == GuideDensityModel::continuous) {
        *out++ = T(std::sqrt(w.density * d.strength * t_.sample_weights[k])) *
                 density_slope(*t_.density, p, &frames[9 * node + 6]);
      } else {
        const T occupancy = density_at(*t_.density, p);
        *out++ = T(std::sqrt(w.density * t_.sample_weights[k])) * occupancy;
        *out++ = T(std::sqrt(w.density * d.surcharge * t_.sample_weights[k])) *
                 surcharge_residual(occupancy, d.threshold, d.surcharge_width);
      }
      // Outside the acceptable region the sample pays the grid's largest F4 integrand on top
      // (GuideTargets::density_ceiling): the head and the space beyond the volume
      // count as full, so a guide never escapes crowding by leaving the region.
      const double h = t_.density->geometry().voxel;
      *out = T(std::sqrt(w.density * t_.density_ceiling * t_.sample_weights[k])) *
             (outside_step(beyond_scalp, h) + outside_step(beyond_volume, h));
    }
    return true;
  }

  const GuideTargets& t_;
  bool merged_ = false;
  std::vector<unsigned char> is_sample_;  // per node: the residuals read it (RodTrace::only)
  MergedTargets direction_, similarity_;
};

}  // namespace hairfit
