// One stage of the pipeline as a descriptor: its options, built from the scene in one function
// (and so what invalidates its cache entry: the key hashes those options, encoded), how it
// computes its value from them and the earlier stages' values, how that value is stored in the
// cache, and which files it writes. Each stage's descriptor lives in its own file
// (stage_fields.cpp … stage_density.cpp); the pipeline is the table of them (stage_table).
#pragma once
#include <array>
#include <cstddef>
#include <filesystem>
#include <future>
#include <optional>
#include <string>
#include <vector>

#include "density/statistics.h"
#include "guides/boundary.h"
#include "io/nrrd.h"
#include "scalp/flow_lookup.h"
#include "pipeline/byte_stream.h"
#include "pipeline/pipeline.h"
#include "pipeline/stage_options.h"
#include "pipeline/stage_plan.h"
#include "pipeline/options_codec.h"
#include "scalp/hull_hair.h"
#include "scalp/shell_hair.h"

namespace hairfit {

// What a stage sees while it computes: the inputs, the run's options, the values of the stages
// before it (its own goes in `values` too), and what stages hand on within one run. Not the
// scene: a stage reads that only through its options (ConfiguredStage).
class StageRun {
 public:
  StageRun(const Inputs& run_inputs, const RunOptions& run_options, StageValues& run_values,
           std::vector<OutputFile>& outputs)
      : inputs(run_inputs), options(run_options), values(run_values), outputs_(outputs) {}

  const Inputs& inputs;
  const RunOptions& options;
  StageValues& values;

  // How the stage's loops run: the run's threads, and its progress bar (empty when it reports
  // nothing).
  Exec exec() const;
  // Curves moved from the run's frame into the scene's (by inputs.origin, pipeline/inputs.h), for
  // the writers: every position a run writes is in the scene's frame.
  Curves in_scene_frame(Curves curves) const {
    if (inputs.origin != Vec3::Zero())
      for (Vec3& x : curves.points) x += inputs.origin;
    return curves;
  }
  NrrdVolume in_scene_frame(NrrdVolume volume) const {
    volume.origin += inputs.origin;
    return volume;
  }
  // Writes out_dir/relative by `write(path)` and lists it among the run's outputs.
  template <class Write>
  void output(const std::string& relative, Write write) {
    const std::filesystem::path path = options.out_dir / relative;
    write(path);
    outputs_.push_back({relative, static_cast<std::uint64_t>(std::filesystem::file_size(path))});
  }

  // Shared views of the earlier values.
  Boundary boundary() const;  // the acceptable region: the fields
  Pores pores() const;        // one fibre per pore, grown along its cluster's guide (roots, chart)
  // The roots' options and inputs with what they read from the fields and the hull: the grey
  // maps, the layer's thickness, the hull's grain, and the length and tilt of hair that suits its
  // shell. Worked out once a run (the roots and the pre-guides that follow the growth field hand
  // in the same settings, both built by root_settings from the run's scene).
  struct ResolvedRoots {
    RootOptions options;
    RootInputs inputs;
    ShellHair shell;
    std::vector<Fall> falls;  // hair from the hull: the fall from every scalp vertex
    HullHair hull;
    std::optional<CombChoice> comb;  // hair.comb = "auto": what the hull chose
  };
  const ResolvedRoots& resolved_roots(const RootSettings& settings);
  // The growth field the roots grew along (one solve on the scalp, once a run), read anywhere near
  // the scalp: for pre-guides that follow it and hair styled along it.
  std::shared_ptr<const FlowLookup> growth_lookup(const RootSettings& settings);

  // Handed on within one run, never cached; results do not depend on them.
  // The stage's digest when it is hashed on a thread of its own beside its files.
  std::future<std::string> digest;
  // The fields stage's samples (scalp, volume, and the skin where it differs), for its files.
  std::optional<std::vector<NrrdVolume>> field_volumes;
  // The fibres the guides stage's CDM deposit grew (DensityGuides::fibres), as the strands stage
  // grows them before the head exit and the cut, so that it need not grow them again.
  std::vector<Vec3> deposited_fibres;
  std::optional<SegmentHistogram> histogram;  // the density stage's, for its file

 private:
  std::vector<OutputFile>& outputs_;
  std::optional<ResolvedRoots> resolved_;
  std::shared_ptr<const FlowLookup> growth_lookup_;
};

struct StageDescriptor {
  const char* name;
  // Bump when the stage's values change for the same options and inputs (a new algorithm, a
  // fixed bug), so caches made by earlier code miss. (The cache also keys on the source
  // fingerprint; this is the stated reason.)
  int version;
  // Whether the scene has the stage at all (null: always).
  bool (*present)(const Scene& scene);
  // The stage's options from the scene, with what it reads beside them and its compute bound to
  // them (configured()).
  ConfiguredStage (*configure)(const Scene& scene);
  // Its loop's length for the progress bar (null: none worth showing).
  std::size_t (*loop_items)(const StageValues& values);
  // The value in and out of a cache entry.
  void (*encode)(ByteWriter& out, const StageValues& values);
  void (*decode)(ByteReader& in, StageValues& values);
  // The stage's files, from run.values (computed or cached) and the scene's output keys. Files are
  // written on every run, so they may read the scene beyond the options.
  void (*write)(StageRun& run, const Scene& scene);
};

// A stage configured with `options`: the key hashes their encoding (options_codec.h) and the
// stage computes with exactly that value, `compute(run, options, report)`.
template <class Options>
ConfiguredStage configured(Options options, void (*compute)(StageRun&, const Options&, StageReport&)) {
  ConfiguredStage c;
  ByteWriter bytes;
  encode(bytes, options);
  c.options = bytes.take();
  c.compute = [o = std::move(options), compute](StageRun& run, StageReport& report) { compute(run, o, report); };
  return c;
}

// The stages in order.
const std::vector<const StageDescriptor*>& stage_table();

const StageDescriptor& fields_stage();
const StageDescriptor& chart_stage();
const StageDescriptor& roots_stage();
const StageDescriptor& preguides_stage();
const StageDescriptor& guides_stage();
const StageDescriptor& strands_stage();
const StageDescriptor& density_stage();

// Diameters along a fibre: a hair of section A at the root, tapering to half at the tip.
void add_fibre_widths(Curves& curves, double cross_section, int threads);

}  // namespace hairfit
