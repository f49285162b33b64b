// Stage files of the chart and roots stages (`hairfit run --until roots`).
#pragma once
#include <filesystem>

#include "scalp/chart.h"
#include "scalp/roots.h"

namespace hairfit {

// chart.obj: the scalp (cm) with its chart as texture coordinates vt = ((x+1)/2, (y+1)/2), so a
// DCC tool shows the density/tilt/length images on the scalp the way hairfit reads them.
void write_chart_obj(const std::filesystem::path& path, const ScalpChart& chart, const Vec3& origin = Vec3::Zero());

// roots.ply: one vertex per pore with x y z (cm), nx ny nz (outward normal), dx dy dz (growth
// direction), length (cm), cluster (int), height ([0, 1]), chart_x chart_y (chart coordinates).
// `origin` (both writers): added to every position, from the run's frame to the scene's (pipeline/inputs.h).
void write_roots_ply(const std::filesystem::path& path, const Roots& roots, const Clusters& clusters,
                     const Vec3& origin = Vec3::Zero());

}  // namespace hairfit
