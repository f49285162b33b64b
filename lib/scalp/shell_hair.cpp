#include "scalp/shell_hair.h"

#include <algorithm>
#include <cmath>

#include "scalp/growth_field.h"

namespace hairfit {

ShellHair hair_for_shell(double thickness, double reach) {
  ShellHair h;
  h.layer_ends = true;
  h.thickness = thickness;
  h.reach = std::max(reach, 1e-3);
  h.tilt = std::min(kMaxShellTilt, std::round(90.0 - std::atan(std::max(thickness, 0.0) / h.reach) * 180.0 / M_PI));
  h.length = std::max(0.5, std::round(2.0 * (2.0 / 3.0) * h.reach) / 2.0);
  return h;
}

namespace {

double percentile_90(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(0.9 * (values.size() - 1))];
}

}  // namespace

double shell_thickness(const ScalpChart& ch, const ThicknessField& field, int threads) {
  return percentile_90(vertex_thickness(ch, field, threads));
}

ShellHair shell_hair(const ScalpChart& ch, const ThicknessField& field, int threads) {
  const std::vector<double> thickness = vertex_thickness(ch, field, threads);
  const std::vector<double> distance = layer_end_distance(ch, thickness, field, kLayerEndProbe);
  double reach = 0.0;
  for (double d : distance)
    if (std::isfinite(d)) reach = std::max(reach, d);
  if (!(reach > 0.0)) return ShellHair{};
  return hair_for_shell(percentile_90(thickness), reach);
}

}  // namespace hairfit
