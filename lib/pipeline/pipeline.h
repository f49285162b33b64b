// The stages in order, run as pure functions of the scene and the earlier stages' values.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/inputs.h"
#include "pipeline/report.h"
#include "spec/scene.h"

namespace hairfit {

struct RunOptions {
  std::filesystem::path out_dir;  // where outputs and report.json go
  std::string until;              // last stage to run ("" = all)
  int threads = 1;                // already resolved (≥ 1)
};

// The stages this build runs, in order.
const std::vector<std::string>& stage_names();

// Runs the stages up to options.until, writes their outputs and report.json into out_dir, and
// returns the report. Throws InputError when options.until names no stage.
RunReport run_pipeline(const Scene& scene, const Inputs& inputs, const RunOptions& options);

}  // namespace hairfit
