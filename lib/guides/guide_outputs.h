#pragma once
#include <filesystem>

#include "guides/guides.h"

namespace hairfit {

// One row per guide: root, loads (dimensionless and cgs), terminal torque, iterations,
// evaluations, each term's value and the converged flag. Full precision, byte-stable. `origin` is
// added to the roots (from the run's frame to the scene's, pipeline/inputs.h).
void write_guides_csv(const std::filesystem::path& path, const Guides& guides, const Vec3& origin = Vec3::Zero());

}  // namespace hairfit
