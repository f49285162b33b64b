#include "pipeline/pipeline.h"

#include <algorithm>

#include "io/atomic_file.h"

namespace hairfit {

const std::vector<std::string>& stage_names() {
  static const std::vector<std::string> names{};
  return names;
}

RunReport run_pipeline(const Scene& scene, const Inputs& inputs, const RunOptions& options) {
  const std::vector<std::string>& names = stage_names();
  if (!options.until.empty() && std::find(names.begin(), names.end(), options.until) == names.end()) {
    std::string valid;
    for (const std::string& n : names) valid += (valid.empty() ? "" : ", ") + n;
    throw InputError("--until", "no stage named \"" + options.until + "\"; this build has: " +
                                    (valid.empty() ? std::string("(no stages yet)") : valid));
  }
  (void)inputs;
  RunReport report;
  report.scene = scene.file.string();
  report.seed = scene.seed;
  report.threads = options.threads;
  report.effects = scene.effects.names();
  write_text_file_atomically(options.out_dir / "report.json", report_json(report));
  return report;
}

}  // namespace hairfit
