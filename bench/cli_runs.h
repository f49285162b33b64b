// What the end-to-end benchmarks (paper_scale, scaling) share: they time the real `hairfit run`
// in a child process, so the kernel measures each run on its own (wall time, user and system CPU
// time, peak resident memory from wait4), read the stages' own figures back from report.json,
// and write scene variants (some keys overridden, every path absolute) into a scratch folder.
#pragma once
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#ifndef HAIRFIT_BINARY
#define HAIRFIT_BINARY "hairfit"
#endif

namespace hairfit::bench {

namespace fs = std::filesystem;

struct ProcessUsage {
  int exit_code = -1;
  double wall = 0.0, user = 0.0, system = 0.0;  // seconds
  std::uint64_t max_rss_bytes = 0;
  double cpu() const { return user + system; }
};

// Runs argv (argv[0] a path) with stdout and stderr sent to `log`, and waits for it.
inline ProcessUsage run_process(const std::vector<std::string>& argv, const fs::path& log) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::fflush(nullptr);  // else the child's freopen writes our buffered output a second time
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    if (!std::freopen(log.c_str(), "w", stdout) || !std::freopen(log.c_str(), "a", stderr)) _exit(127);
    execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) throw std::runtime_error("wait4 failed");
  ProcessUsage u;
  u.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  u.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  u.user = usage.ru_utime.tv_sec + 1e-6 * usage.ru_utime.tv_usec;
  u.system = usage.ru_stime.tv_sec + 1e-6 * usage.ru_stime.tv_usec;
  u.max_rss_bytes = static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux: kilobytes
  return u;
}

struct StageRun {
  std::string name;
  double seconds = 0.0;
  double cpu_seconds = 0.0;
  std::uint64_t peak_memory_bytes = 0;
  nlohmann::ordered_json figures;  // the stage's object in report.json: its figures beside seconds, digest, …
};

struct RunRecord {
  ProcessUsage usage;
  std::vector<StageRun> stages;
  const StageRun* stage(const std::string& name) const {
    for (const StageRun& s : stages)
      if (s.name == name) return &s;
    return nullptr;
  }
  double figure(const std::string& stage_name, const std::string& key) const {
    const StageRun* s = stage(stage_name);
    return s && s->figures.contains(key) && s->figures.at(key).is_number() ? s->figures.at(key).get<double>() : 0.0;
  }
};

inline std::vector<StageRun> read_report(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  const nlohmann::ordered_json root = nlohmann::ordered_json::parse(in);  // stages in run order
  std::vector<StageRun> out;
  for (const auto& [name, s] : root.at("stages").items())
    out.push_back({name, s.at("seconds").get<double>(), s.value("cpu_seconds", 0.0),
                   s.at("peak_memory_bytes").get<std::uint64_t>(), s});
  return out;
}

// One cold, quiet `hairfit run` of `scene` into `out`; throws with the log's path when it fails.
inline RunRecord run_hairfit(const std::string& hairfit, const fs::path& scene, const fs::path& out, int threads) {
  fs::remove_all(out);
  fs::create_directories(out);
  const fs::path log = out / "run.log";
  RunRecord r;
  r.usage = run_process({hairfit, "run", scene.string(), "--out", out.string(), "--no-cache", "--quiet", "--threads",
                         std::to_string(threads)},
                        log);
  if (r.usage.exit_code != 0)
    throw std::runtime_error("hairfit run " + scene.string() + " exited " + std::to_string(r.usage.exit_code) +
                             "; see " + log.string());
  r.stages = read_report(out / "report.json");
  return r;
}

using KeyValue = std::variant<std::int64_t, double, std::string>;
using Overrides = std::vector<std::pair<std::string, KeyValue>>;  // dotted key → value

// Writes `base` with `overrides` applied and its paths made absolute (so the copy may live
// anywhere) to `out`.
inline void write_scene_variant(const fs::path& base, const Overrides& overrides, const fs::path& out) {
  toml::table scene = toml::parse_file(base.string());
  const fs::path folder = fs::absolute(base).parent_path();
  auto absolute = [&](toml::node* node) {
    if (node && node->is_string()) {
      const fs::path p(node->as_string()->get());
      if (p.is_relative()) *node->as_string() = (folder / p).lexically_normal().string();
    }
  };
  absolute(scene.at_path("inputs.scalp").node());
  absolute(scene.at_path("inputs.volume").node());
  if (toml::table* maps = scene["maps"].as_table())
    for (auto&& [key, node] : *maps) absolute(&node);
  absolute(scene.at_path("output.dir").node());
  absolute(scene.at_path("output.occluder").node());
  for (const auto& [key, value] : overrides) {
    toml::table* table = &scene;
    std::string rest = key;
    for (std::size_t dot; (dot = rest.find('.')) != std::string::npos; rest = rest.substr(dot + 1)) {
      const std::string part = rest.substr(0, dot);
      if (!table->contains(part)) table->insert(part, toml::table{});
      table = (*table)[part].as_table();
      if (!table) throw std::runtime_error("write_scene_variant: " + key + " crosses a non-table");
    }
    std::visit([&](const auto& v) { table->insert_or_assign(rest, v); }, value);
  }
  fs::create_directories(out.parent_path());
  std::ofstream file(out);
  file << scene << "\n";
  if (!file) throw std::runtime_error("cannot write " + out.string());
}

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

inline double mib(std::uint64_t bytes) { return bytes / (1024.0 * 1024.0); }

// The 1-, 5- and 15-minute load averages, to print beside every timing on the shared machine.
inline std::string load_average() {
  double l[3] = {0, 0, 0};
  if (getloadavg(l, 3) != 3) return "unknown";
  char text[64];
  std::snprintf(text, sizeof text, "%.2f %.2f %.2f", l[0], l[1], l[2]);
  return text;
}

// The options bench_paper_scale and bench_scaling share: --runs N --threads T --hairfit PATH
// --scratch DIR. Takes argv[i] (and its value) when it is one of them.
struct RunSettings {
  int runs = 1, threads = 2;
  std::string hairfit = HAIRFIT_BINARY;
  fs::path scratch;  // scene variants and run outputs
};
inline bool parse_run_option(int argc, char** argv, int& i, RunSettings& s) {
  const std::string a = argv[i];
  if (i + 1 >= argc) return false;
  if (a == "--runs") s.runs = std::atoi(argv[++i]);
  else if (a == "--threads") s.threads = std::atoi(argv[++i]);
  else if (a == "--hairfit") s.hairfit = argv[++i];
  else if (a == "--scratch") s.scratch = argv[++i];
  else return false;
  return true;
}

// The rows of a CSV file without quoting (what the benchmarks write), header skipped; each row
// must have at least `columns` cells.
inline std::vector<std::vector<std::string>> read_csv(const fs::path& file, std::size_t columns) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream text(line);
    for (std::string cell; std::getline(text, cell, ',');) cells.push_back(cell);
    if (cells.size() < columns) throw std::runtime_error(file.string() + ": short line: " + line);
    rows.push_back(std::move(cells));
  }
  return rows;
}

// The commit the source tree is at (the figures of a run belong to it; the build may hold
// uncommitted changes of the shared tree too).
inline std::string source_commit() {
  std::string out;
  if (FILE* p = popen("git -C '" HAIRFIT_SOURCE_DIR "' log -1 --date=format:%Y-%m-%dT%H:%M --format='%h (%cd)' 2>/dev/null", "r")) {
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, p)) out += buffer;
    pclose(p);
  }
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out.empty() ? "unknown" : out;
}

}  // namespace hairfit::bench
