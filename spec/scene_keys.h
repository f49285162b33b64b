// The scene format's single source of truth: every key with its type, unit, allowed range, the
// stage or effect it feeds and its documentation. The parser checks against this table and the
// reference page's key table (spec/reference.md) is generated from it.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "spec/scene.h"

namespace hairfit {

enum class KeyKind {
  integer,    // TOML integer
  number,     // TOML float or integer
  boolean,
  text,       // string, one of `choices` when that is non-empty
  path,       // string naming an existing file, relative to the scene's folder
  folder,     // string naming an output folder, relative to the scene's folder
  vector3,    // [x, y, z], non-zero (normalised)
  pair,       // [lo, hi] with lo ≤ hi, each within the key's range
  text_list,  // [string, ...], each one of `choices`, no repeats
  point2,     // [x, y], a chart point: in the closed unit disk
};

struct SceneKey {
  std::string name;  // dotted, e.g. "guides.weights.boundary"
  KeyKind kind;
  std::string unit;  // "" when dimensionless
  double lo = -1e300, hi = 1e300;  // allowed range of numbers (and of pair components)
  bool lo_open = false, hi_open = false;
  std::vector<std::string> choices;
  bool required = false;
  std::string feeds;  // the stage or effect that reads it
  std::string doc;
  // Stores a checked value into the scene; numbers arrive as doubles, vectors and pairs as
  // their components, texts and lists as strings.
  std::function<void(Scene&, const std::vector<double>&, const std::vector<std::string>&)> store;
  // The key's value in a scene, as TOML text (a default scene gives the documented defaults).
  std::function<std::string(const Scene&)> show;

  bool in_range(double x) const;
  std::string range_text() const;  // e.g. "(0, 10]"
};

const std::vector<SceneKey>& scene_keys();

// The key named `name`, or null.
const SceneKey* find_scene_key(const std::string& name);

// x as TOML text: the shortest text of at least 10 significant digits that reads back as exactly x
// (an integer's digits when x is whole).
std::string number_text(double x);

// The Markdown table of all keys (name, type, unit, default, range, feeds, meaning).
std::string scene_keys_markdown();

// The Markdown table of the accuracy presets and the values each sets.
std::string scene_presets_markdown();

}  // namespace hairfit
