#pragma once
#include <filesystem>

#include "guides/guides.h"

namespace hairfit {

// One row per guide: root, loads (dimensionless and cgs), terminal torque, iterations,
// evaluations, each term's value and the converged flag. Full precision, byte-stable.
void write_guides_csv(const std::filesystem::path& path, const Guides& guides);

}  // namespace hairfit
