// scene.resolved.toml: the scene as a run resolved it, written beside the run's outputs
// (spec/reference.md, "The resolved scene"). It lists every scene key with the value used and, as a
// TOML comment, where that value came from: the scene file at its line, the accuracy preset, the
// shell defaults, the documented default, or derived at run time with the figure it came from.
//
// It parses as a scene, and running it gives the same outputs byte for byte. So a value derived at
// run time stays a comment: the key is left unset, as are the keys whose absence makes the run
// derive it (kShellTriggerKeys), and the rerun derives it again from the same hull. Every other key
// is written with the exact value used (numbers read back to the same bits; directions as the file
// wrote them, since normalising again may move a bit).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "spec/scene.h"

namespace hairfit {

inline constexpr const char* kResolvedSceneFile = "scene.resolved.toml";

// A scene key's value worked out at run time, as a stage reports it (StageReport::derive).
struct DerivedKey {
  std::string key;     // dotted scene key, e.g. "hair.length"
  std::string value;   // the value used as TOML text ("9"), or a summary where it varies per root
  std::string source;  // what it was derived from, with the figures ("the shell: reach 13.1 cm")
};

// The text of scene.resolved.toml for a run of `scene` whose outputs go to `folder`: paths are
// written relative to that folder (the file's own, so the rerun finds the same files) and
// output.dir as "."; `derived` are the run's derived keys in the order its stages derived them.
std::string resolved_scene_text(const Scene& scene, const std::vector<DerivedKey>& derived,
                                const std::filesystem::path& folder);

}  // namespace hairfit
