#include "pipeline/pipeline.h"

#include <algorithm>
#include <map>
#include <optional>
#include <variant>

#include "core/error.h"
#include "io/atomic_file.h"
#include "pipeline/resolved_scene.h"
#include "pipeline/stage.h"
#include "pipeline/stage_cache.h"
#include "pipeline/stage_options.h"
#include "pipeline/stage_plan.h"

namespace hairfit {

const std::vector<std::string>& stage_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const StageDescriptor* stage : stage_table()) n.push_back(stage->name);
    return n;
  }();
  return names;
}

void check_stage_name(const std::string& stage, const std::string& option) {
  const std::vector<std::string>& names = stage_names();
  if (stage.empty() || std::find(names.begin(), names.end(), stage) != names.end()) return;
  std::string valid;
  for (const std::string& n : names) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError(option, "no stage named \"" + stage + "\"; the stages are: " + valid);
}

namespace {

// Runs the stage table in order: each stage loaded from the cache where its entry is valid, else
// computed (and stored), then its files written.
class Runner {
 public:
  Runner(const Scene& scene, const Inputs& inputs, const RunOptions& options)
      : scene_(scene), options_(options), run_(inputs, options, result_.values, result_.report.outputs) {
    result_.report.scene = scene.file.string();
    result_.report.seed = scene.seed;
    result_.report.threads = options.threads;
    result_.report.effects = scene.effects.names();
    const std::vector<ConfiguredStage> stages = configure_stages(scene);
    if (!options.cache_dir.empty()) {
      cache_.emplace(options.cache_dir);
      keys_ = stage_keys(stages, inputs);
    }
    for (const ConfiguredStage& c : stages) configured_.emplace(c.name, c);
  }

  PipelineResult run() {
    for (const StageDescriptor* stage : stage_table()) {
      if (configured_.count(stage->name)) run_stage(*stage);  // no trace of a stage the scene lacks
      if (stage->name == options_.until) break;
    }
    if (options_.write_outputs) {
      run_.output(kResolvedSceneFile, [&](const std::filesystem::path& path) {
        write_text_file_atomically(path, resolved_scene_text(scene_, derived_keys(result_.report), options_.out_dir));
      });
      write_text_file_atomically(options_.out_dir / "report.json", report_json(result_.report));
    }
    return std::move(result_);
  }

 private:
  void run_stage(const StageDescriptor& descriptor) {
    StageReport stage;
    stage.name = descriptor.name;
    const StageMeter meter;
    const ConfiguredStage& configured = configured_.at(stage.name);
    const bool cacheable = cache_ && configured.cached;
    if (!(cacheable && load_cached(descriptor, stage))) {
      if (progress())
        progress()->stage_begins(stage.name, descriptor.loop_items ? descriptor.loop_items(result_.values) : 0);
      configured.compute(run_, stage);
      if (cacheable) {
        await_digest(stage);
        store(descriptor, stage);
      }
    }
    if (options_.write_outputs) descriptor.write(run_, scene_);
    await_digest(stage);
    stage.seconds = meter.seconds();
    stage.cpu_seconds = meter.cpu_seconds();
    stage.peak_memory_bytes = meter.peak_memory_bytes();
    if (progress()) progress()->stage_ends(stage.name, stage.status, stage.seconds);
    result_.report.stages.push_back(std::move(stage));
  }

  // A stage may hash its value on a thread of its own while it writes its files (StageRun::digest).
  void await_digest(StageReport& stage) {
    if (run_.digest.valid()) stage.digest = run_.digest.get();
  }

  ProgressReporter* progress() const { return options_.progress; }

  // A cache entry's payload: the stage's digest, figures and derived keys, then its values.
  void store(const StageDescriptor& descriptor, const StageReport& stage) {
    ByteWriter out;
    out.put(stage.digest);
    out.put<std::uint64_t>(stage.figures.size());
    for (const auto& [key, value] : stage.figures) {
      out.put(key);
      out.put<std::uint8_t>(static_cast<std::uint8_t>(value.index()));
      std::visit([&out](const auto& x) { out.put(x); }, value);
    }
    encode(out, stage.derived);
    descriptor.encode(out, result_.values);
    try {
      cache_->store(stage.name, keys_.at(stage.name), out.take());
    } catch (const std::exception& e) {  // a cache that cannot be written costs speed, not the run
      if (progress()) progress()->note(std::string("warning: could not cache ") + stage.name + ": " + e.what());
    }
  }

  // Loads the stage's value, digest, figures and derived keys from its cache entry. Nothing is
  // changed unless the whole entry decodes; a rejected entry is reported and the stage recomputed.
  bool load_cached(const StageDescriptor& descriptor, StageReport& stage) {
    const std::string& name = stage.name;
    std::string problem;
    const std::optional<std::string> payload = cache_->load(name, keys_.at(name), problem);
    if (!payload) {
      if (!problem.empty() && progress()) progress()->note("cache: " + problem + "; recomputing " + name);
      return false;
    }
    try {
      ByteReader in(*payload);
      StageReport loaded = stage;
      in.get(loaded.digest);
      const auto figures = in.get<std::uint64_t>();
      if (figures > 1000) throw CodecError("impossible figure count");
      for (std::uint64_t i = 0; i < figures; ++i) {
        std::string key;
        in.get(key);
        switch (in.get<std::uint8_t>()) {
          case 0: loaded.add(key, in.get<bool>()); break;
          case 1: loaded.add(key, in.get<std::int64_t>()); break;
          case 2: loaded.add(key, in.get<double>()); break;
          case 3: {
            std::string text;
            in.get(text);
            loaded.add(key, text);
            break;
          }
          default: throw CodecError("unknown figure type");
        }
      }
      loaded.derived = decode_derived_keys(in);
      StageValues v = result_.values;
      descriptor.decode(in, v);
      in.expect_end();
      loaded.status = "cached";
      stage = std::move(loaded);
      result_.values = std::move(v);
      return true;
    } catch (const CodecError& e) {
      if (progress())
        progress()->note("cache: " + cache_->entry_path(name, keys_.at(name)).string() + ": " + e.what() +
                         "; recomputing " + name);
      return false;
    }
  }

  const Scene& scene_;
  const RunOptions& options_;
  PipelineResult result_;
  StageRun run_;  // after result_: it holds references into it
  std::optional<StageCache> cache_;
  std::map<std::string, std::string> keys_;
  std::map<std::string, ConfiguredStage> configured_;  // each present stage, configured from the scene
};

}  // namespace

PipelineResult run_pipeline(const Scene& scene, const Inputs& inputs, const RunOptions& options) {
  check_stage_name(options.until);
  if (options.until == "density" && !density_declared(scene))
    throw InputError(scene.file.string(), "declares no density model (effects.density = \"none\"), so there is no "
                                          "density stage to stop after; declare one or stop after strands");
  return Runner(scene, inputs, options).run();
}

std::filesystem::path default_cache_dir(const Scene& scene) { return scene.file.parent_path() / ".hairfit-cache"; }

}  // namespace hairfit
