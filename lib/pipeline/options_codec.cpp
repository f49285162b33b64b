#include "pipeline/options_codec.h"

#include <stdexcept>

namespace hairfit {

// A new member in one of these types must be written below (a member that never reaches a stage's
// value is said so here instead); these sizes make the compiler ask, so that no option can change
// a stage's value without changing its cache key. Update the number once the member is handled.
// The sizes are those of the toolchain the project builds with (GCC's library on a 64-bit
// target); elsewhere tests/pipeline/cache_test.cpp alone guards the codec (every scene key a
// stage reads must change a stage's key).
#if defined(__GLIBCXX__) && defined(__LP64__)
static_assert(sizeof(FieldSpec) == 64, "FieldSpec changed: update options_codec.cpp");
static_assert(sizeof(RootOptions) == 192, "RootOptions changed: update options_codec.cpp");
static_assert(sizeof(HairMaterial) == 72, "HairMaterial changed: update options_codec.cpp");
static_assert(sizeof(RodDiscretisation) == 8, "RodDiscretisation changed: update options_codec.cpp");
static_assert(sizeof(PreguideOptions) == 184, "PreguideOptions changed: update options_codec.cpp");
static_assert(sizeof(GuideOptions) == 264, "GuideOptions changed: update options_codec.cpp");
static_assert(sizeof(DensityTermOptions) == 40, "DensityTermOptions changed: update options_codec.cpp");
static_assert(sizeof(WispShape) == 32, "WispShape changed: update options_codec.cpp");
static_assert(sizeof(DensitySpread) == 32, "DensitySpread changed: update options_codec.cpp");
static_assert(sizeof(StrandOptions) == 88, "StrandOptions changed: update options_codec.cpp");
#endif

void encode(ByteWriter& out, const FieldSpec& spec) {
  out.put(spec.voxel);
  out.put(spec.band);
  out.put(spec.margin);
  out.put(spec.max_memory_gib);  // a larger budget may admit a grid a smaller one refuses
  // spec.name labels messages only.
}

void encode(ByteWriter& out, const RootOptions& o) {
  out.put(o.density);
  out.put(o.tilt);
  out.put(o.tilt_toward);
  out.put(o.flow);
  out.put(o.comb);
  out.put(o.flow_smoothing);
  out.put(o.swirl);
  out.put(o.whorl);
  out.put(o.whorl_radius);
  out.put(o.parting);
  out.put(o.parting_radius);
  out.put(o.tilt_range);
  out.put(o.length);
  out.put(o.length_range);
  out.put(o.hang_margin);
  out.put<std::uint8_t>(o.hang_falls_free);
  out.put(o.guides);
  out.put(o.preguide_spacing);
  out.put(o.cluster_overlap);
  out.put(o.seed);
  out.put(o.oversampling);
}

void encode(ByteWriter& out, const RootSettings& s) {
  encode(out, s.options);
  out.put(s.maps);
  out.put<std::uint8_t>(s.from_shell);
  out.put(s.relief_radius);
  out.put<std::uint8_t>(s.grain_of_normals);
  out.put<std::uint8_t>(s.comb_from_hull);
  out.put<std::uint8_t>(s.grain_follows_comb);
  out.put(s.fall_depth_range);
}

void encode(ByteWriter& out, const HairMaterial& m) {
  out.put(m.youngs_modulus);
  out.put(m.shear_modulus);
  out.put(m.cross_section);
  out.put(m.mass_density);
  out.put(m.gravity);
  out.put(m.contact.stiffness);
  out.put(m.contact.layer);
}

void encode(ByteWriter& out, const RodDiscretisation& rod) {
  out.put(rod.integrator);
  out.put(rod.segments);
}

void encode(ByteWriter& out, const PreguideOptions& o) {
  encode(out, o.material);
  encode(out, o.rod);
  out.put(o.depth_range);
  out.put(o.max_load);
  out.put(o.immersion);
  // o.flow is made in the stage from its root settings (PreguidesOptions::growth), which the key holds.
  if (o.flow) throw std::logic_error("pre-guide options: the growth field is keyed through its root settings");
  out.put<std::uint8_t>(o.styled);
  out.put(o.down);
  out.put(o.front);
}

void encode(ByteWriter& out, const GuideOptions& o) {
  encode(out, o.material);
  encode(out, o.rod);
  out.put(o.samples);
  out.put(o.neighbours);
  out.put(o.max_iterations);
  out.put(o.tolerance);
  out.put(o.boundary);
  out.put(o.outside_penalty);
  out.put(o.boundary_width);
  out.put(o.point_forces);
  out.put(o.point_force_weight);
  out.put(o.weights.direction);
  out.put(o.weights.similarity);
  out.put(o.weights.boundary);
  out.put(o.weights.density);
  out.put<std::uint8_t>(o.warm_start);
  // o.styled is made in the stage from its root settings (GuidesOptions::growth), which the key holds.
  if (o.styled) throw std::logic_error("guide options: the growth field is keyed through its root settings");
  out.put(o.depth_range);
  out.put(o.down);
  out.put(o.front);
}

void encode(ByteWriter& out, const DensityGridSpec& grid) {
  out.put(grid.voxel);
  out.put(grid.max_memory);
}

void encode(ByteWriter& out, const GuideDensitySettings& s) {
  out.put(s.term.model);
  out.put(s.term.strength);
  out.put(s.term.threshold);
  out.put(s.term.surcharge);
  out.put(s.term.surcharge_width);
  encode(out, s.grid);
  out.put(s.batch);
  out.put(s.stall.iterations);
  out.put(s.stall.tolerance);
  encode(out, s.wisp);
  out.put(s.deposit);
}

void encode(ByteWriter& out, const WispShape& w) {
  out.put(w.points);
  out.put(w.root_radius);
  out.put(w.tip_radius);
  out.put(w.turns);
}

void encode(ByteWriter& out, const StrandOptions& o) {
  encode(out, o.wisp);
  out.put<std::uint8_t>(o.cutting);
  out.put(o.cut_threshold);
  out.put<std::uint8_t>(o.cut_tips);
  out.put<std::uint8_t>(o.layer_depth);
  out.put<std::int32_t>(o.spread.passes);
  out.put(o.spread.voxel);
  out.put(o.spread.step);
  out.put(o.spread.settle);
}

}  // namespace hairfit
