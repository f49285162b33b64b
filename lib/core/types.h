// Small vocabulary shared by every stage: fixed-size Eigen vectors in double precision.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace hairfit {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec3i = Eigen::Vector3i;
using Mat3 = Eigen::Matrix3d;

}  // namespace hairfit
