// A scene run in the test's own process, on 2 threads, writing nothing: for tests that look at
// the stage values themselves.
#pragma once
#include "pipeline/inputs.h"
#include "pipeline/pipeline.h"

namespace hairfit::testing {

inline PipelineResult run_in_process(const Scene& scene, const Inputs& inputs) {
  RunOptions options;
  options.threads = 2;
  options.write_outputs = false;
  return run_pipeline(scene, inputs, options);
}

}  // namespace hairfit::testing
