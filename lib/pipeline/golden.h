// Golden results of a scene for `hairfit check` (spec/reference.md, "Regression checks"): per stage
// its digest and report figures, plus a compact table of the guides (tip, loads, convergence),
// stored in a folder as golden.json and guides.csv. Between runs of the same build (build_id())
// the digests must match exactly; between different builds each figure and the guide tips are
// compared with the documented tolerances, since another compiler or machine may round
// differently.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/pipeline.h"

namespace hairfit {

struct GoldenGuide {
  bool converged = false;
  int iterations = 0;
  Vec3 tip = Vec3::Zero();          // cm
  Vec3 force = Vec3::Zero();        // f_L, dimensionless
  Vec3 root_moment = Vec3::Zero();  // m(0), dimensionless
};

struct GoldenStage {
  std::string name;
  std::string digest;
  std::vector<std::pair<std::string, Figure>> figures;
};

struct Golden {
  std::string build;  // build_id() of the program that made it
  std::vector<GoldenStage> stages;
  std::vector<GoldenGuide> guides;
};

Golden make_golden(const PipelineResult& result);

// Writes golden.json and guides.csv into `folder` (atomically, creating it).
void write_golden(const std::filesystem::path& folder, const Golden& golden);
// Reads them back; InputError naming the file for a missing or malformed one.
Golden read_golden(const std::filesystem::path& folder);

struct FigureTolerance {
  double absolute = 0.0;  // |now − golden| ≤ absolute + relative·|golden|
  double relative = 0.0;
};
// The tolerance of one figure of one stage across builds (exact for counts and texts unless listed).
FigureTolerance figure_tolerance(const std::string& stage, const std::string& figure);

// Guide tips across builds: at least kGuideTipShare of the guides within kGuideTipTolerance cm.
inline constexpr double kGuideTipTolerance = 0.01;
inline constexpr double kGuideTipShare = 0.98;

struct StageComparison {
  std::string name;
  bool differs = false;
  std::vector<std::string> details;  // what differs and by how much
};

struct GoldenComparison {
  bool same_build = false;
  std::vector<StageComparison> stages;  // in stage order
  const StageComparison* first_difference() const;
};

// Compares a run against golden results: exact digests when the builds are the same, tolerances
// otherwise. Every stage is compared; the details say by how much each figure moved.
GoldenComparison compare_golden(const Golden& golden, const Golden& now);

}  // namespace hairfit
