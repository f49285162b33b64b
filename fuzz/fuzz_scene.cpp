// libFuzzer target: the scene parser (TOML text → Scene), every key's type, range and path checks.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "spec/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // Relative paths in the text resolve against the fixtures' scene folder, so a fuzzed scene can
    // name real meshes and maps (the seed corpus does).
    hairfit::parse_scene_text(text, HAIRFIT_SOURCE_DIR "/fixtures/smoke/scene.toml");
  } catch (const hairfit::InputError&) {
  }
  return 0;
}
