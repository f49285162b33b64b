// hairfit check: the shipped fixtures agree with their golden results, a changed weight is caught
// and named at the guides, and across builds the documented tolerances decide.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "pipeline/build_id.h"
#include "pipeline/golden.h"
#include "../support/run_hairfit.h"
#include "../support/scratch.h"

using namespace hairfit;
using hairfit::testing::read_all;
using hairfit::testing::run_hairfit;
using hairfit::testing::source_path;
namespace fs = std::filesystem;

namespace {

std::string fresh_folder(const std::string& name) {
  return hairfit::testing::fresh_scratch_folder("check-" + name).string();
}

// A copy of the smoke scene in `folder` (input paths made absolute), with `extra` replacing the
// [guides] table.
std::string smoke_copy(const std::string& folder, const std::string& guides_table) {
  std::string text = read_all(source_path("fixtures/smoke/scene.toml"));
  for (const char* path : {"../meshes/", "../maps/"})
    text = std::regex_replace(text, std::regex(path), source_path("fixtures/") + (path + 3));
  text = std::regex_replace(text, std::regex("\\[guides\\]\nsamples = 8\n"), guides_table);
  const std::string file = folder + "/scene.toml";
  std::ofstream(file) << text;
  return file;
}

const char* kOtherWeights = "[guides]\nsamples = 8\n[guides.weights]\ndirection = 0.5\nsimilarity = 0.2\nboundary = 0.3\n";

// The golden results of the smoke fixture as if another build had written them.
std::string foreign_golden(const std::string& folder) {
  fs::copy(source_path("fixtures/smoke/golden"), folder, fs::copy_options::recursive);
  const std::string file = folder + "/golden.json";
  const std::string text = std::regex_replace(read_all(file), std::regex("\"build\": \"[^\"]*\""), "\"build\": \"another compiler\"");
  std::ofstream(file) << text;
  return folder;
}

}  // namespace

TEST_CASE("the smoke fixture agrees with its golden results") {
  const auto r = run_hairfit("check " + source_path("fixtures/smoke/scene.toml") + " --quiet");
  INFO(r.out << r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("check passed") != std::string::npos);
  // Digests are compared exactly only by the build that wrote the golden results (a Release build);
  // any other (the sanitizer build, tests/sanitize.sh) compares with the tolerances.
  std::smatch golden_build;
  const std::string golden = read_all(source_path("fixtures/smoke/golden/golden.json"));
  REQUIRE(std::regex_search(golden, golden_build, std::regex("\"build\": \"([^\"]*)\"")));
  const bool same_build = golden_build[1] == build_id();
  CHECK(r.out.find(same_build ? "digests must match exactly" : "comparing with tolerances") != std::string::npos);
}

TEST_CASE("a changed guide weight fails the check, naming the guides as the first stage that differs") {
  const std::string folder = fresh_folder("weights");
  const auto r = run_hairfit("check " + smoke_copy(folder, kOtherWeights) + " --golden " +
                             source_path("fixtures/smoke/golden") + " --quiet");
  INFO(r.out << r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.out.find("the first stage that differs is guides") != std::string::npos);
  for (const char* stage : {"fields", "chart", "roots", "preguides"})
    CHECK(r.out.find(std::string("  ") + stage + std::string(10 - std::string(stage).size(), ' ') + " agrees") != std::string::npos);
  CHECK(r.out.find("guide tips: ") != std::string::npos);  // by how much
  fs::remove_all(folder);
}

TEST_CASE("across builds the tolerances decide: the same values pass, a changed weight still fails at the guides") {
  const std::string folder = fresh_folder("foreign");
  const std::string golden = foreign_golden(folder + "/golden");
  auto r = run_hairfit("check " + source_path("fixtures/smoke/scene.toml") + " --golden " + golden + " --quiet");
  INFO(r.out << r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("comparing with tolerances") != std::string::npos);
  r = run_hairfit("check " + smoke_copy(folder, kOtherWeights) + " --golden " + golden + " --quiet");
  CHECK(r.exit_code == 1);
  CHECK(r.out.find("the first stage that differs is guides") != std::string::npos);
  fs::remove_all(folder);
}

TEST_CASE("--update writes golden results the same run then agrees with; unusable ones are bad input") {
  const std::string folder = fresh_folder("update");
  const std::string scene = smoke_copy(folder, kOtherWeights);
  auto r = run_hairfit("check " + scene + " --golden " + folder + "/golden --quiet");
  CHECK(r.exit_code == 2);  // none yet
  CHECK(r.err.find("--update") != std::string::npos);
  r = run_hairfit("check " + scene + " --golden " + folder + "/golden --update --quiet");
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("40 guides") != std::string::npos);
  CHECK(run_hairfit("check " + scene + " --golden " + folder + "/golden --quiet").exit_code == 0);
  std::ofstream(folder + "/golden/guides.csv", std::ios::app) << "41,1,2,x\n";
  r = run_hairfit("check " + scene + " --golden " + folder + "/golden --quiet");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("guides.csv:42") != std::string::npos);
  fs::remove_all(folder);
}

TEST_CASE("compare_golden: same build compares digests, another build each figure against its tolerance") {
  Golden golden;
  golden.build = "a";
  golden.stages = {GoldenStage{"guides", "0123", {{"failures", std::int64_t(10)}, {"mean_iterations", 30.0}}}};
  Golden now = golden;
  CHECK(compare_golden(golden, now).first_difference() == nullptr);
  now.stages[0].digest = "4567";
  CHECK(compare_golden(golden, now).first_difference()->name == "guides");  // same build: the digest decides
  now.build = "b";
  CHECK(compare_golden(golden, now).first_difference() == nullptr);  // other build: digests are not compared
  now.stages[0].figures[1].second = 31.4;                             // +4.7 %: within 5 %
  CHECK(compare_golden(golden, now).first_difference() == nullptr);
  now.stages[0].figures[1].second = 31.6;  // +5.3 %
  const GoldenComparison c = compare_golden(golden, now);
  REQUIRE(c.first_difference());
  CHECK(c.first_difference()->details.back().find("mean_iterations: 30 → 31.6") == 0);
  // Failures may move by 1 + 2 % of 10 = 1.2 across builds.
  now.stages[0].figures[1].second = 30.0;
  now.stages[0].figures[0].second = std::int64_t(11);
  CHECK(compare_golden(golden, now).first_difference() == nullptr);
  now.stages[0].figures[0].second = std::int64_t(12);
  CHECK(compare_golden(golden, now).first_difference() != nullptr);
  // Guide tips: 98 % within 0.01 cm.
  golden.guides.assign(100, GoldenGuide{});
  now.guides = golden.guides;
  now.stages[0].figures[0].second = std::int64_t(10);
  now.guides[3].tip.x() = 0.5;
  now.guides[4].tip.x() = 0.02;
  CHECK(compare_golden(golden, now).first_difference() == nullptr);  // 2 of 100 beyond
  now.guides[5].tip.y() = 0.011;
  CHECK(compare_golden(golden, now).first_difference() != nullptr);  // 3 of 100
  // A stage missing on one side always differs.
  now.stages.clear();
  CHECK(compare_golden(golden, now).first_difference()->name == "guides");
}
