// Same scene and seed: byte-identical outputs for any thread count (docs/design.md §8), end to end
// through the command line.
#include <doctest/doctest.h>

#include <regex>

#include "../support/run_hairfit.h"
#include "../support/scratch.h"

using hairfit::testing::read_all;
using hairfit::testing::run_hairfit;
using hairfit::testing::source_path;

TEST_CASE("hairfit run gives byte-identical files and digests for 1, 2, 3 and 4 threads") {
  const std::string base = hairfit::testing::scratch_path("determinism").string();
  for (int threads : {1, 2, 3, 4}) {
    // --no-cache: every run computes (the cache would hand the later runs the first one's values).
    const auto r = run_hairfit("run " + source_path("fixtures/smoke/scene.toml") + " --no-cache --out " + base + "-" +
                               std::to_string(threads) + " --threads " + std::to_string(threads));
    REQUIRE(r.exit_code == 0);
  }
  // Digests of every stage (report.json also holds times and the thread count, which differ).
  auto digests = [&](int threads) {
    const std::string report = read_all(base + "-" + std::to_string(threads) + "/report.json");
    std::string all;
    const std::regex digest("\"digest\": \"([0-9a-f]{16})\"");
    for (auto it = std::sregex_iterator(report.begin(), report.end(), digest); it != std::sregex_iterator(); ++it)
      all += (*it)[1].str() + " ";
    return all;
  };
  CHECK(digests(1).size() == 6 * 17);  // fields, chart, roots, preguides, guides, strands
  for (int threads : {2, 3, 4}) {
    CHECK(digests(threads) == digests(1));
    for (const char* file : {"strands.hair", "strands.obj", "guides.csv", "preguides.obj", "roots.ply", "chart.obj",
                             "fields/volume.nrrd", "renders/strands-front.png", "renders/stages.png"}) {
      INFO(file << " with " << threads << " threads");
      const std::string one = read_all(base + "-1/" + file);
      CHECK(!one.empty());
      CHECK(read_all(base + "-" + std::to_string(threads) + "/" + file) == one);
    }
  }
}
