// Density grids (paper §3.5, docs/design.md §6): the rectilinear grid on which the binary occupancy model
// (BOM) and the continuous density model (CDM) live.
//
// Conventions: cell (i,j,k) is the box origin + h·([i,i+1] × [j,j+1] × [k,k+1]) in cm
// (core/grid_geometry.h); its value sits at its centre origin + h·(i+½, j+½, k+½). Values are interpolated trilinearly between cell
// centres; cells outside the grid count as 0 (no hair there), so every query is defined for any
// finite point and continuous. A DensityGrid is immutable and shares its buffer (cheap to copy);
// it is built by a DensityAccumulator (lib/density/accumulator.h) and its freeze().
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/grid_geometry.h"
#include "core/types.h"

namespace hairfit {


// The grid of cells of edge `voxel` (cm) covering the box [lower, upper] (cm), centred on it
// (the box grows to a whole number of cells). Throws InputError for a non-finite or empty box, a
// voxel that is not finite and > 0, or a grid of more than max_memory_gib of doubles (the message
// names a voxel size that would fit).
GridGeometry make_grid_geometry(const Vec3& lower, const Vec3& upper, double voxel,
                                double max_memory_gib = 4.0);

struct DensityValueGradient {
  double value = 0.0;            // the grid's unit (BOM: occupancy 0..1; CDM: cell diagonals)
  Vec3 gradient = Vec3::Zero();  // value per cm
};

struct DensityGradientJacobian {
  Vec3 gradient = Vec3::Zero();  // ∇Φρ by central differences (value per cm)
  Mat3 jacobian = Mat3::Zero();  // ∂(∇Φρ)/∂p (value per cm²): row r = ∂gradient_r/∂(x,y,z)
};

class DensityGrid {
 public:
  DensityGrid() = default;  // empty: no cells, every query returns 0
  // The grid of these cell values (geometry's index order). Throws std::invalid_argument for
  // negative dimensions, a voxel that is not finite and > 0, or not one value per cell.
  static DensityGrid from_values(const GridGeometry& geometry, std::vector<double> values);
  const GridGeometry& geometry() const { return geometry_; }
  // The cell's value; 0 outside the grid.
  double cell(int i, int j, int k) const;
  // All cell values, geometry().index order.
  const std::vector<double>& values() const { return *values_; }

  // Trilinear interpolation of the cell-centre values at p (cm) and its exact gradient (piecewise
  // trilinear, so the gradient jumps across cell-centre planes). BOM: the occupancy the F4 term
  // samples at a guide's points (§3.5), smooth enough for Levenberg–Marquardt.
  double value(const Vec3& p) const;
  DensityValueGradient value_and_gradient(const Vec3& p) const;

  // CDM: ∇Φρ at p by central differences of the grid, as the paper computes it:
  // (Φ(p + h·e) − Φ(p − h·e)) / 2h per axis e, Φ the trilinear interpolant. This equals the
  // trilinear interpolation of the cell-centred differences (Φ[i+1] − Φ[i−1]) / 2h, so it is
  // continuous; `jacobian` is its derivative in p, for building the F4 jet √(w4·c_ρ·Δs)·⟨∇Φρ, t⟩
  // by the chain rule.
  Vec3 central_gradient(const Vec3& p) const;
  DensityGradientJacobian central_gradient_and_jacobian(const Vec3& p) const;

 private:
  // The central gradient at p, and its Jacobian when `jacobian` is given (the gradient's bits are
  // the same either way; the guides' cost-only evaluations skip the Jacobian).
  void central_gradient_at(const Vec3& p, Vec3& gradient, Mat3* jacobian) const;

  friend class DensityAccumulator;
  DensityGrid(const GridGeometry& g, std::shared_ptr<const std::vector<double>> v)
      : geometry_(g), values_(std::move(v)) {}
  GridGeometry geometry_;
  std::shared_ptr<const std::vector<double>> values_ = std::make_shared<const std::vector<double>>();
};

}  // namespace hairfit
