// hairfit check SCENE [--golden DIR] [--update] [--threads N] [--quiet]: runs the scene cold (never
// from the cache: a check tests the code, not the cache) and compares every stage with the golden
// results in DIR (default: `golden` beside the scene). Exit 0 when all agree, 1 when a stage
// differs (the first one is named, with by how much), 2 for bad input. --update rewrites them.
#include <cstdio>

#include "args.h"
#include "commands.h"
#include "core/parallel.h"
#include "pipeline/golden.h"

namespace hairfit::cli {

int command_check(const Arguments& argv) {
  const Args args(argv, {"golden", "threads"}, {"update", "quiet"});
  if (args.positionals().size() != 1) throw UsageError{"expected exactly one SCENE file"};
  const int threads = args.integer("threads", 0);
  if (threads < 0) throw UsageError{"--threads must be ≥ 0 (0 = all cores)"};

  const Scene scene = parse_scene(args.positionals()[0]);
  const Inputs inputs = load_inputs(scene);
  const std::filesystem::path folder =
      args.text("golden") ? std::filesystem::path(*args.text("golden")) : scene.file.parent_path() / "golden";
  const bool update = args.has("update");
  const Golden golden = update ? Golden{} : read_golden(folder);  // bad golden files fail before the run

  RunOptions options;
  options.threads = resolve_thread_count(threads);
  options.write_outputs = false;
  ProgressReporter progress(progress_style_for(stderr, args.has("quiet")));
  options.progress = &progress;
  const Golden now = make_golden(run_pipeline(scene, inputs, options));

  if (update) {
    write_golden(folder, now);
    std::printf("wrote %s and %s (%zu stages, %zu guides; build %s)\n", (folder / "golden.json").string().c_str(),
                (folder / "guides.csv").string().c_str(), now.stages.size(), now.guides.size(), now.build.c_str());
    return 0;
  }
  const GoldenComparison c = compare_golden(golden, now);
  if (c.same_build)
    std::printf("same build as the golden results (%s): digests must match exactly\n", now.build.c_str());
  else
    std::printf("another build than the golden results: comparing with tolerances (spec/reference.md)\n  golden: %s\n"
                "  this:   %s\n", golden.build.c_str(), now.build.c_str());
  for (const StageComparison& s : c.stages) {
    std::printf("  %-10s %s\n", s.name.c_str(), s.differs ? "DIFFERS" : "agrees");
    for (const std::string& d : s.details) std::printf("             %s\n", d.c_str());
  }
  const StageComparison* first = c.first_difference();
  if (!first) {
    std::printf("check passed: %s agrees with %s\n", scene.file.string().c_str(), folder.string().c_str());
    return 0;
  }
  std::printf("check failed: the first stage that differs is %s\n", first->name.c_str());
  return 1;
}

}  // namespace hairfit::cli
