// What each stage reads: the scene keys (or whole sections), the loaded input files, and the
// earlier stages whose values it consumes, declared in the stage's own file (stage.h, beside where
// it builds its options). The stage cache keys on exactly this, so a change costs only the stages
// that read it and those after them.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "pipeline/inputs.h"
#include "spec/scene.h"

namespace hairfit {

struct StageDeclaration {
  std::string name;
  // Bump when the stage's values change for the same inputs (a new algorithm, a fixed bug), so
  // caches made by earlier code miss. (The cache also keys on the source fingerprint; this is the
  // stated reason.)
  int version = 1;
  std::vector<std::string> reads;     // scene key names or section prefixes (spec/scene_keys.h)
  std::vector<std::string> files;     // loaded inputs: scalp, volume, density map, tilt map, length map
  std::vector<std::string> consumes;  // earlier stages
  bool cached = true;                 // whether its value is worth storing (the stage says why not)
};

// The scene's stages in order, each with what it reads. Effects that are off are not read (their
// keys are absent, and the density stage is absent without a density model). Throws
// std::logic_error if a declaration names a key that the key table does not have.
std::vector<StageDeclaration> stage_declarations(const Scene& scene);

// The scene parts a stage reads as text, one "key = value" line per key in key-table order, with
// values after defaults and exact (so reformatting, reordering or commenting the scene file, or
// writing a default out, changes nothing).
std::string canonical_scene_parts(const Scene& scene, const std::vector<std::string>& reads);

// The digest of a loaded input's content ("scalp", "volume", "density map", ...): what was read,
// not the file's path or time.
std::string input_digest(const Inputs& inputs, const std::string& file);

// Every stage's cache key (32 hex digits): a hash of its name, version, the codec version, the
// build and source fingerprint, its canonical scene parts, its input files' contents and the keys
// of the stages it consumes.
std::map<std::string, std::string> stage_keys(const Scene& scene, const Inputs& inputs);

}  // namespace hairfit
