// Editing scene text in tests: keys added to a scene a command wrote.
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace hairfit::testing {

// The scene text with `keys` (table, lines) added: into the table where the text has it, else as
// a new table at the end (TOML allows each table header once).
inline std::string with_keys(std::string scene, const std::vector<std::pair<std::string, std::string>>& keys) {
  for (const auto& [table, lines] : keys) {
    const std::string header = "\n[" + table + "]\n";
    const std::size_t at = scene.find(header);
    if (at == std::string::npos) scene += header + lines + "\n";
    else scene.insert(at + header.size(), lines + "\n");
  }
  return scene;
}

// The keys that make a prepared scene test-sized: few guides and hairs, a coarse field, short rods.
inline const std::vector<std::pair<std::string, std::string>>& small_run_keys() {
  static const std::vector<std::pair<std::string, std::string>> keys{
      {"hair", "density = 3"},          {"fields", "voxel = 0.3"},
      {"roots", "guides = 60\npreguide_spacing = 2.0"}, {"rod", "segments = 24"},
      {"guides", "samples = 8"},        {"strands", "points = 12"},
      {"output", "strands = []\nrenders = []"}};
  return keys;
}

}  // namespace hairfit::testing
