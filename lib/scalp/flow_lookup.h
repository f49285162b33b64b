// The growth field read anywhere near the scalp (for pre-guides that follow it along their whole
// length): the Gaussian-weighted mean of the field's vertex directions within a radius, a
// continuous function of the point, as the optimiser's finite differences need. The vertices are
// gathered by cells an eighth of the radius wide first (each cell weighs as its vertices, at their
// mean position), so a lookup costs the same on a scalp of 50 000 triangles as on one of 2 000.
#pragma once
#include <vector>

#include "core/mesh.h"
#include "core/point_grid.h"
#include "scalp/direction_field.h"

namespace hairfit {

// The radius the pipeline reads the growth field over (cm): a few scalp edges.
constexpr double kFlowLookupRadius = 2.0;

class FlowLookup {
 public:
  // `radius` (cm): the reach of the average (the weight falls as exp(−d²/(radius/2)²) and is cut at radius).
  FlowLookup(const Mesh& scalp, const std::vector<Vec3>& normals, const DirectionField& field, double radius);

  // The unit field direction near p, in the plane across the mean normal there (also returned in
  // `normal`); zero where no scalp vertex lies within the radius.
  Vec3 at(const Vec3& p, Vec3* normal = nullptr) const;

 private:
  struct Gathered {
    std::vector<Vec3> positions, directions, normals;
  };
  static Gathered gather(const Mesh& scalp, const std::vector<Vec3>& normals, const DirectionField& field,
                         double radius);
  FlowLookup(Gathered gathered, double radius);

  std::vector<Vec3> positions_, normals_, directions_;  // per gathered cell
  PointGrid grid_;
  double radius_;
};

}  // namespace hairfit
