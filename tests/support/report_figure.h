// A stage's figure from a run's report, for tests.
#pragma once
#include <cmath>
#include <string>
#include <type_traits>
#include <variant>

#include "pipeline/report.h"

namespace hairfit::testing {

// The figure `name` of stage `stage` as a number (a count or a flag too), NaN when the report has
// none or it is text.
inline double figure(const RunReport& report, const std::string& stage, const std::string& name) {
  for (const StageReport& s : report.stages)
    if (s.name == stage)
      for (const auto& [key, value] : s.figures)
        if (key == name)
          return std::visit(
              [](const auto& v) -> double {
                if constexpr (std::is_arithmetic_v<std::decay_t<decltype(v)>>) return static_cast<double>(v);
                else return std::nan("");
              },
              value);
  return std::nan("");
}

}  // namespace hairfit::testing
