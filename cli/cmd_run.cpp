#include <cstdio>

#include "args.h"
#include "commands.h"
#include "core/parallel.h"
#include "pipeline/pipeline.h"

namespace hairfit::cli {

int command_run(const Arguments& argv) {
  const Args args(argv, {"out", "until", "threads"}, {});
  if (args.positionals().size() != 1) throw UsageError{"expected exactly one SCENE file"};
  const int threads = args.integer("threads", 0);
  if (threads < 0) throw UsageError{"--threads must be ≥ 0 (0 = all cores)"};

  const Scene scene = parse_scene(args.positionals()[0]);
  const Inputs inputs = load_inputs(scene);  // all input is checked before anything is written
  RunOptions options;
  options.out_dir = args.text("out") ? std::filesystem::path(*args.text("out")) : scene.output.dir;
  options.until = args.text("until").value_or("");
  options.threads = resolve_thread_count(threads);
  check_stage_name(options.until);
  const RunReport report = run_pipeline(scene, inputs, options).report;
  std::printf("wrote %s\n", (options.out_dir / "report.json").string().c_str());
  for (const OutputFile& o : report.outputs) std::printf("wrote %s (%llu bytes)\n", (options.out_dir / o.path).string().c_str(),
                                                         static_cast<unsigned long long>(o.bytes));
  return 0;
}

}  // namespace hairfit::cli
