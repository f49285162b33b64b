// A stage's figure from a run's report, for tests.
#pragma once
#include <cmath>
#include <string>
#include <variant>

#include "pipeline/report.h"

namespace hairfit::testing {

// The figure `name` of stage `stage` as a number, NaN when the report has none.
inline double figure(const RunReport& report, const std::string& stage, const std::string& name) {
  for (const StageReport& s : report.stages)
    if (s.name == stage)
      for (const auto& [key, value] : s.figures)
        if (key == name) return std::get<double>(value);
  return std::nan("");
}

}  // namespace hairfit::testing
