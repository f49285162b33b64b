// report.json: one shape from the first stage on (docs/design.md §8). Stages add their own figures.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "spec/resolved_scene.h"

namespace hairfit {

using Figure = std::variant<bool, std::int64_t, double, std::string>;

struct StageReport {
  std::string name;
  std::string status = "computed";  // computed | cached
  double seconds = 0.0;
  double cpu_seconds = 0.0;  // user + system time of all threads while the stage ran
  std::uint64_t peak_memory_bytes = 0;
  std::string digest;
  std::vector<std::pair<std::string, Figure>> figures;  // the stage's own counts and measures

  // Scene keys whose value the stage worked out at run time, for scene.resolved.toml; cached with
  // the figures, so a cached stage reports them too.
  std::vector<DerivedKey> derived;

  void add(const std::string& key, Figure value) { figures.emplace_back(key, std::move(value)); }
  // Records that scene key `key` (dotted, "hair.length") took `value` (TOML text, or a summary where
  // it varies per root) at run time, derived from `source` (what, with its figures). Throws
  // std::logic_error for a name that is no scene key.
  void derive(const std::string& key, const std::string& value, const std::string& source);
};

struct OutputFile {
  std::string path;  // relative to the output folder
  std::uint64_t bytes = 0;
};

struct RunReport {
  std::string scene;
  std::int64_t seed = 0;
  int threads = 1;
  std::vector<std::string> effects;
  std::vector<StageReport> stages;
  std::vector<OutputFile> outputs;
};

// The report as pretty-printed JSON with keys in a fixed order.
std::string report_json(const RunReport& report);

// Measures one stage: wall time, the CPU time of the whole process (cpu/wall tells how busy the
// cores were), and the peak resident memory while it ran (Linux: the high-water mark is reset
// through /proc/self/clear_refs; elsewhere the process peak is reported).
class StageMeter {
 public:
  StageMeter();
  double seconds() const;
  double cpu_seconds() const;
  std::uint64_t peak_memory_bytes() const;

 private:
  double start_;
  double cpu_start_;
};

}  // namespace hairfit
