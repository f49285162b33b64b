#include <cstdio>
#include <filesystem>

#include "args.h"
#include "commands.h"
#include "core/interrupt.h"
#include "core/parallel.h"
#include "pipeline/stage_pictures.h"
#include "pipeline/cut_picture.h"

namespace hairfit::cli {

namespace {

// Where the picture goes: --out as given, or `name` in the folder --out names, or `name` here.
std::string picture_path(const Args& args, const std::string& name) {
  const std::optional<std::string> out = args.text("out");
  if (!out) return name;
  std::error_code ec;
  return std::filesystem::is_directory(*out, ec) ? (std::filesystem::path(*out) / name).string() : *out;
}

}  // namespace

int command_render(const Arguments& argv) {
  const Args args(argv, {"stage", "view", "size", "out", "threads"}, {});
  if (args.positionals().size() != 1) throw UsageError{"expected exactly one SCENE file"};
  const std::string stage = args.text("stage").value_or("strands");
  if (stage != "cut") check_picture_stage(stage);  // before any work
  const ViewName view = parse_view(args.text("view").value_or("front"));
  const auto [width, height] = parse_size(args.text("size").value_or("800x800"));
  const int threads = resolve_thread_count(args.integer("threads", 0));
  if (stage == "cut") {  // what `hairfit prepare` cut from the scan: no pipeline stage needed
    const std::string out = picture_path(args, "cut-" + view_name(view) + ".png");
    const Image image = render_cut(args.positionals()[0], view, width, height, threads);
    write_png(out, image);
    std::printf("wrote %s (%d×%d)\n", out.c_str(), image.width, image.height);
    return 0;
  }
  install_interrupt_handlers();  // Ctrl-C stops at the next safe point (core/interrupt.h)
  const Scene scene = parse_scene(args.positionals()[0]);
  const Inputs inputs = load_inputs(scene);
  RunOptions options;
  options.until = stage_needed_for_picture(stage);
  options.threads = threads;
  options.write_outputs = false;
  const PipelineResult result = run_pipeline(scene, inputs, options);
  const Image image = render_stage(stage, scene, inputs, result.values, view, width, height, threads);
  const std::string out = picture_path(args, stage + "-" + view_name(view) + ".png");
  write_png(out, image);
  std::printf("wrote %s (%d×%d)\n", out.c_str(), width, height);
  return 0;
}

}  // namespace hairfit::cli
