#include <cstdio>

#include "args.h"
#include "commands.h"
#include "core/interrupt.h"
#include "core/parallel.h"
#include "pipeline/stage_pictures.h"

namespace hairfit::cli {

int command_run(const Arguments& argv) {
  const Args args(argv, {"out", "until", "threads", "cache"}, {"no-cache", "quiet"});
  if (args.positionals().size() != 1) throw UsageError{"expected exactly one SCENE file"};
  const int threads = args.integer("threads", 0);
  if (threads < 0) throw UsageError{"--threads must be ≥ 0 (0 = all cores)"};

  install_interrupt_handlers();  // Ctrl-C stops at the next safe point (core/interrupt.h)
  const Scene scene = parse_scene(args.positionals()[0]);
  const Inputs inputs = load_inputs(scene, resolve_thread_count(threads));  // all input is checked before anything is written
  RunOptions options;
  options.out_dir = args.text("out") ? std::filesystem::path(*args.text("out")) : scene.output.dir;
  options.until = args.text("until").value_or("");
  options.threads = resolve_thread_count(threads);
  check_stage_name(options.until);
  if (args.has("no-cache") && args.has("cache")) throw UsageError{"--cache and --no-cache contradict each other"};
  if (!args.has("no-cache"))
    options.cache_dir = args.text("cache") ? std::filesystem::path(*args.text("cache")) : default_cache_dir(scene);
  ProgressReporter progress(progress_style_for(stderr, args.has("quiet")));
  options.progress = &progress;
  const PipelineResult result = run_pipeline(scene, inputs, options);
  const RunReport& report = result.report;
  std::printf("wrote %s\n", (options.out_dir / "report.json").string().c_str());
  for (const OutputFile& o : report.outputs) std::printf("wrote %s (%llu bytes)\n", (options.out_dir / o.path).string().c_str(),
                                                         static_cast<unsigned long long>(o.bytes));
  // After a full run, the pictures the scene asks for: the strands from each view, and a contact
  // sheet of every stage from the first view.
  if (options.until.empty() && !scene.output.renders.empty()) {
    const int width = static_cast<int>(scene.output.render_size[0]), height = static_cast<int>(scene.output.render_size[1]);
    for (const std::string& view : scene.output.renders) {
      const std::filesystem::path path = options.out_dir / "renders" / ("strands-" + view + ".png");
      write_png(path, render_stage("strands", scene, inputs, result.values, parse_view(view), width, height, options.threads));
      std::printf("wrote %s\n", path.string().c_str());
    }
    const std::filesystem::path sheet = options.out_dir / "renders" / "stages.png";
    write_png(sheet, render_stage("all", scene, inputs, result.values, parse_view(scene.output.renders.front()), width,
                                  height, options.threads));
    std::printf("wrote %s\n", sheet.string().c_str());
  }
  return 0;
}

}  // namespace hairfit::cli
