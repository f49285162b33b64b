#include <cstdio>

#include "args.h"
#include "commands.h"
#include "spec/scene_keys.h"

namespace hairfit::cli {

int command_scene_keys(const Arguments& argv) {
  const Args args(argv, {}, {"presets"});
  if (!args.positionals().empty()) throw UsageError{"takes no arguments"};
  std::fputs((args.has("presets") ? scene_presets_markdown() : scene_keys_markdown()).c_str(), stdout);
  return 0;
}

}  // namespace hairfit::cli
