// The stages a scene configures, in order, each with its options encoded, the loaded input files
// and earlier stages it reads beside them, and its compute bound to those options (each stage's
// own file builds them, stage.h). The stage cache keys on exactly this, so a change costs only the
// stages whose options or inputs it changes, and those after them.
#pragma once
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "pipeline/inputs.h"
#include "pipeline/pipeline.h"
#include "spec/scene.h"

namespace hairfit {

class StageRun;

struct ConfiguredStage {
  std::string name;
  int version = 1;                    // StageDescriptor::version
  std::string options;                // the stage's options, encoded (options_codec.h)
  std::vector<std::string> files;     // loaded inputs: scalp, volume, density map, tilt map, length map
  std::vector<std::string> consumes;  // earlier stages
  bool cached = true;                 // whether its value is worth storing (the stage says why not)
  // Computes the value into run.values, with its digest and figures, from those options.
  std::function<void(StageRun& run, StageReport& report)> compute;
};

// The scene's stages in order. Effects that are off are not read (their options keep the
// library's defaults), and the density stage is absent without a density model.
std::vector<ConfiguredStage> configure_stages(const Scene& scene);

// The digest of a loaded input's content ("scalp", "volume", "density map", ...): what was read,
// not the file's path or time.
std::string input_digest(const Inputs& inputs, const std::string& file);

// Every stage's cache key (32 hex digits): a hash of its name, version, the codec version, the
// build and source fingerprint, its encoded options, its input files' contents and the keys of
// the stages it consumes.
std::map<std::string, std::string> stage_keys(const std::vector<ConfiguredStage>& stages, const Inputs& inputs);
std::map<std::string, std::string> stage_keys(const Scene& scene, const Inputs& inputs);

}  // namespace hairfit
