#include "pipeline/report.h"

#include <sys/resource.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "spec/scene_keys.h"

namespace hairfit {

void StageReport::derive(const std::string& key, const std::string& value, const std::string& source) {
  if (!find_scene_key(key)) throw std::logic_error("StageReport::derive: \"" + key + "\" is no scene key");
  derived.push_back({key, value, source});
}

std::string report_json(const RunReport& report) {
  using Json = nlohmann::ordered_json;
  Json root;
  root["format"] = "hairfit-report/1";
  root["scene"] = report.scene;
  root["seed"] = report.seed;
  root["threads"] = report.threads;
  root["effects"] = report.effects;
  Json stages = Json::object();
  for (const StageReport& s : report.stages) {
    Json stage;
    stage["status"] = s.status;
    stage["seconds"] = s.seconds;
    stage["cpu_seconds"] = s.cpu_seconds;
    stage["peak_memory_bytes"] = s.peak_memory_bytes;
    stage["digest"] = s.digest;
    for (const auto& [key, value] : s.figures) std::visit([&, k = key](const auto& v) { stage[k] = v; }, value);
    stages[s.name] = stage;
  }
  root["stages"] = stages;
  Json outputs = Json::array();
  for (const OutputFile& o : report.outputs) outputs.push_back({{"path", o.path}, {"bytes", o.bytes}});
  root["outputs"] = outputs;
  return root.dump(2) + "\n";
}

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

std::uint64_t peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  return 0;
}

}  // namespace

StageMeter::StageMeter() : start_(now()), cpu_start_(process_cpu_seconds()) {
  std::ofstream clear("/proc/self/clear_refs");
  if (clear) clear << "5";
}

double StageMeter::seconds() const { return now() - start_; }

double StageMeter::cpu_seconds() const { return process_cpu_seconds() - cpu_start_; }

std::uint64_t StageMeter::peak_memory_bytes() const { return peak_resident_bytes(); }

}  // namespace hairfit
