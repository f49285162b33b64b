// hairfit: strand hair from a scalp mesh and the boundary of the hair volume
// (Sobottka, Kusak and Weber, "Hairstyle Construction from Raw Surface Data").
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

#include "args.h"
#include "commands.h"
#include "core/error.h"
#include "core/interrupt.h"

namespace {

struct Command {
  const char* name;
  const char* usage;
  int (*run)(const hairfit::cli::Arguments&);
};

const Command kCommands[] = {
    {"validate", "validate SCENE [--resolved]   check a scene and its inputs; nothing is computed (--resolved: print the scene as a run resolves it, scene.resolved.toml)",
     hairfit::cli::command_validate},
    {"run", "run SCENE [--out DIR] [--until STAGE] [--threads N] [--cache DIR | --no-cache] [--quiet]   run the pipeline, write outputs and report.json",
     hairfit::cli::command_run},
    {"check", "check SCENE [--golden DIR] [--update] [--threads N] [--quiet]   compare every stage with golden results (exit 1 if one differs)",
     hairfit::cli::command_check},
    {"render", "render SCENE [--stage STAGE] [--view VIEW] [--size WxH] [--out PNG|DIR] [--threads N]   picture of a stage",
     hairfit::cli::command_render},
    {"scene-keys", "scene-keys [--presets]    print the table of scene keys, or of accuracy presets (spec/reference.md embeds both)",
     hairfit::cli::command_scene_keys},
    {"rod", "rod [--length L] [--force x,y,z] [--torque x,y,z] [--solver ...] [--segments N]   solve one rod, print JSON (--help)",
     hairfit::cli::command_rod},
    {"field", "field MESH --voxel H --band B [--margin M] [--max-memory GIB] --out F.nrrd [--threads N]   one distance field, timed", hairfit::cli::command_field},
    {"prepare", "prepare SCAN.obj --out DIR (--plane P,N | --cap C,A,DEG | --mask R,G,B [--mask-tolerance D] [--mask-smoothing N]) [--units U | --head-height H] [--up x,y,z] [--front x,y,z] [--crown-thickness T] [--ramp R] [--max-hole F] [--weld D] [--scalp auto|radial|level-set] [--scalp-voxel H] [--threads N]   hull, scalp and scene from one scan", hairfit::cli::command_prepare},
};

void print_help() {
  std::printf("hairfit %s — strand hair from raw surface data\n\nusage: hairfit COMMAND [ARGS]\n\ncommands:\n",
              HAIRFIT_VERSION);
  for (const Command& c : kCommands) std::printf("  hairfit %s\n", c.usage);
  std::printf("\n  hairfit --help | --version\n\nexit codes: 0 success, 2 bad input, 1 internal error\n");
}

}  // namespace

int main(int argc, char** argv) {
  const std::string first = argc > 1 ? argv[1] : "";
  if (first.empty() || first == "--help" || first == "-h" || first == "help") {
    print_help();
    return first.empty() ? 2 : 0;
  }
  if (first == "--version") {
    std::printf("hairfit %s\n", HAIRFIT_VERSION);
    return 0;
  }
  for (const Command& c : kCommands) {
    if (first != c.name) continue;
    const hairfit::cli::Arguments args(argv + 2, argv + argc);
    try {
      return c.run(args);
    } catch (const hairfit::Interrupted& e) {
      std::fprintf(stderr, "hairfit %s: %s; the files written before it are complete and intact, nothing "
                           "half-written was left\n", c.name, e.what());
      return e.exit_code();
    } catch (const hairfit::InputError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return 2;
    } catch (const hairfit::cli::UsageError& e) {
      std::fprintf(stderr, "hairfit %s: %s\nusage: hairfit %s\n", c.name, e.message.c_str(), c.usage);
      return 2;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "hairfit %s: internal error: %s\n", c.name, e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "hairfit: unknown command \"%s\"; see hairfit --help\n", first.c_str());
  return 2;
}
