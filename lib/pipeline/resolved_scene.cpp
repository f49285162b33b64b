#include "pipeline/resolved_scene.h"

#include <string>

#include "io/number_text.h"
#include "spec/scene_keys.h"

namespace hairfit {

namespace {

// A figure in a comment, to 4 significant digits.
std::string figure(double x) {
  char text[48];
  return std::string(text, format_general(text, x, 4));
}

}  // namespace

void derive_shell_keys(StageReport& stage, const ShellHair& shell, double length, double tilt) {
  if (!shell.layer_ends) {
    const std::string source = "the shell derives nothing (its layer does not end on the scalp), so the default holds";
    stage.derive("hair.length", number_text(length), source);
    stage.derive("hair.tilt", number_text(tilt), source);
    return;
  }
  const std::string reach = figure(shell.reach) + " cm along the scalp from where the layer ends";
  stage.derive("hair.length", number_text(length),
               "the shell, ⅔ of its reach " + reach + ", to 0.5 cm (scalp/shell_hair.h)");
  stage.derive("hair.tilt", number_text(tilt),
               "the shell, 90° − atan(T / reach), at most " + figure(kMaxShellTilt) + "°, for its thickness T " +
                   figure(shell.thickness) + " cm (90th percentile over the scalp) and reach " + reach);
}

void derive_hull_keys(StageReport& stage, const std::vector<HullHairRegion>& regions, double lying_length,
                      double tilt) {
  std::string quarters;
  for (const HullHairRegion& g : regions)
    quarters += (quarters.empty() ? "" : "; ") + g.name + " " + figure(g.median_length) + " cm, " +
                figure(100.0 * g.hanging_share) + " % hanging, falling " + figure(g.median_below_rim) + " cm below the rim";
  stage.derive("hair.length", "per root",
               "the hull: as long as the hair's fall where it hangs, " + figure(lying_length) +
                   " cm where it lies; medians by quarter: " + quarters + " (scalp/hull_hair.h)");
  stage.derive("hair.tilt", number_text(tilt), "the shell's tilt where the hair lies (scalp/shell_hair.h)");
  stage.derive("hair.tilt_toward", "\"hanging\"", "the hull: its layer carries hair on below the scalp's rim");
}

void derive_comb_keys(StageReport& stage, const CombChoice& choice, bool grain_follows_comb) {
  const bool combed = choice.comb == Comb::from_crown;
  const std::string figures = "the layer thickens toward the crown under " + figure(100.0 * choice.thickening_up) +
                              " % of the scalp's area and its hair hangs from " + figure(100.0 * choice.hanging) +
                              " %: " + (combed ? "a carved cap" : "not a carved cap") + " (at least " +
                              figure(100.0 * kCombedThickeningShare) + " % and under " +
                              figure(100.0 * kCombedHangingShare) + " %)";
  stage.derive("hair.comb", combed ? "\"from_crown\"" : "\"into_layer\"", "the hull: " + figures + " (scalp/hull_hair.h)");
  if (grain_follows_comb)
    stage.derive("hair.relief_grain", combed ? "\"normals\"" : "\"edges\"",
                 combed ? "combed from the crown, the grain of the hull's normals" : "the grain of the hull's edges");
}

std::vector<DerivedKey> derived_keys(const RunReport& report) {
  std::vector<DerivedKey> out;
  for (const StageReport& stage : report.stages) out.insert(out.end(), stage.derived.begin(), stage.derived.end());
  return out;
}

void encode(ByteWriter& out, const std::vector<DerivedKey>& derived) {
  out.put<std::uint64_t>(derived.size());
  for (const DerivedKey& d : derived) {
    out.put(d.key);
    out.put(d.value);
    out.put(d.source);
  }
}

std::vector<DerivedKey> decode_derived_keys(ByteReader& in) {
  const auto count = in.get<std::uint64_t>();
  if (count > in.remaining() / (3 * sizeof(std::uint64_t))) throw CodecError("impossible derived key count");
  std::vector<DerivedKey> derived(count);
  for (DerivedKey& d : derived) {
    in.get(d.key);
    in.get(d.value);
    in.get(d.source);
    if (!find_scene_key(d.key)) throw CodecError("derived key \"" + d.key + "\" is no scene key");
  }
  return derived;
}

}  // namespace hairfit
