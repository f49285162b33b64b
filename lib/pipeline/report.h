// report.json: one shape from the first stage on (docs/design.md §8). Stages add their own figures.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

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

  void add(const std::string& key, Figure value) { figures.emplace_back(key, std::move(value)); }
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
