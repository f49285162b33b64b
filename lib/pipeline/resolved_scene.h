// The run's side of scene.resolved.toml (spec/resolved_scene.h): stages report the scene keys they
// work out at run time with StageReport::derive(key, value, source), in compute, so that the
// entries are cached with the stage's figures; the runner collects them from every stage's report
// in stage order and writes the file beside report.json.
#pragma once
#include <filesystem>
#include <vector>

#include "pipeline/byte_stream.h"
#include "pipeline/report.h"
#include "scalp/hull_hair.h"
#include "scalp/shell_hair.h"

namespace hairfit {

// hair.length and hair.tilt as the roots stage derived them from the shell (scalp/shell_hair.h):
// `length` cm and `tilt` degrees are the values used, with the shell's thickness and reach as
// their source (or, where the layer does not end, the defaults that held).
void derive_shell_keys(StageReport& stage, const ShellHair& shell, double length, double tilt);

// hair.length, hair.tilt and hair.tilt_toward where the hull gives hanging hair
// (scalp/hull_hair.h): the length per root, with each quarter's median length, hanging share and
// fall below the rim as its source; `lying_length` and `tilt` (degrees) as used where it does not
// hang.
void derive_hull_keys(StageReport& stage, const std::vector<HullHairRegion>& regions, double lying_length,
                      double tilt);

// hair.comb = "auto" as the hull chose it (scalp/hull_hair.h comb_from_hull), with its two shares
// as the source; and hair.relief_grain = "auto" where `grain_follows_comb`.
void derive_comb_keys(StageReport& stage, const CombChoice& choice, bool grain_follows_comb);

// Every stage's derived keys, in stage order.
std::vector<DerivedKey> derived_keys(const RunReport& report);

// The entries in and out of a stage's cache entry.
void encode(ByteWriter& out, const std::vector<DerivedKey>& derived);
std::vector<DerivedKey> decode_derived_keys(ByteReader& in);

}  // namespace hairfit
