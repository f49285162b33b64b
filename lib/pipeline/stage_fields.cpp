// The fields stage: the scalp's and the volume's signed distance fields (docs/design.md §2).
#include "core/digest.h"
#include "field/field_nrrd.h"
#include "field/hair_region.h"
#include "field/skin_beyond_hairline.h"
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "pipeline/stage_options.h"

namespace hairfit {

namespace {

// fields.skin_beyond_hairline: "auto" takes the shell for an open hull, the floor for a closed one.
enum class SkinMode : std::uint8_t { floor, shell, automatic };

// The grids of the scalp's and the volume's fields, and where the skin lies past the hairline.
struct FieldsOptions {
  FieldSpec scalp, volume;
  SkinMode skin = SkinMode::floor;
};

void encode(ByteWriter& out, const FieldsOptions& o) {
  encode(out, o.scalp);
  encode(out, o.volume);
  out.put<std::uint8_t>(static_cast<std::uint8_t>(o.skin));
}

void compute(StageRun& run, const FieldsOptions& o, StageReport& stage) {
  const Inputs& inputs = run.inputs;
  const int threads = run.options.threads;
  StageValues& v = run.values;
  auto grid = [](const DistanceField& f) {
    return std::to_string(f.dims().x()) + "x" + std::to_string(f.dims().y()) + "x" + std::to_string(f.dims().z());
  };
  // The scalp's field: the distance to the head closed under the scalp by a floor across the
  // hairline, negative inside it.
  const Mesh head = closed_head(inputs.scalp.mesh);
  const FastWindingNumber head_winding(head, HairRegion::kFirstBeta, threads);
  const RobustInside inside_head{{winding_soup(head, head_winding)}};
  v.scalp_distance = std::make_shared<const DistanceField>(make_distance_field(head, o.scalp, threads, inside_head));
  v.scalp_field = v.scalp_distance;
  // The volume's inside is the region's (HairRegion) together with the head, so that its field
  // keeps its sign across the scalp, as a prepared volume's floor under the scalp makes it: the
  // acceptable region, inside the volume and not behind the scalp, is the region's shell.
  const HairRegion region(inputs.volume.mesh, inputs.scalp.mesh, inputs.volume_report.closed(), threads);
  const RobustInside inside_volume{{region.soup(inputs.volume.mesh, inputs.scalp.mesh)}, v.scalp_distance.get()};
  v.volume_field = std::make_shared<const DistanceField>(
      make_distance_field(inputs.volume.mesh, o.volume, threads, inside_volume));
  std::vector<NrrdVolume> volumes{field_to_nrrd(*v.scalp_distance, threads), field_to_nrrd(*v.volume_field, threads)};
  const bool skin_under_shell =
      o.skin == SkinMode::shell || (o.skin == SkinMode::automatic && !inputs.volume_report.closed());
  if (o.skin == SkinMode::automatic)
    stage.derive("fields.skin_beyond_hairline", skin_under_shell ? "\"shell\"" : "\"floor\"",
                 std::string("auto, the hull being ") + (skin_under_shell ? "open" : "closed"));
  if (skin_under_shell) {
    const SkinBeyondHairline skin = skin_beyond_hairline(inputs.scalp.mesh, *v.scalp_distance, *v.volume_field, threads);
    v.scalp_field = std::make_shared<const DistanceField>(skin.field);
    volumes.push_back(field_to_nrrd(*v.scalp_field, threads));
    stage.add("skin_beyond_hairline", std::string("shell"));
    stage.add("skin_grid", grid(*v.scalp_field));
    stage.add("hairline_thickness_cm", skin.hairline_thickness);
  }
  Digest d;
  for (const NrrdVolume& volume : volumes) d.add_bytes(volume.data.data(), volume.data.size() * sizeof(float));
  if (run.options.write_outputs) run.field_volumes = std::move(volumes);  // the files hold the same samples
  stage.digest = d.hex();
  stage.add("voxel_cm", o.volume.voxel);
  stage.add("scalp_grid", grid(*v.scalp_distance));
  stage.add("volume_grid", grid(*v.volume_field));
  stage.add("band_voxels", static_cast<std::int64_t>(v.scalp_distance->band_voxels() + v.volume_field->band_voxels()));
  const std::int64_t skin_bytes = skin_under_shell ? v.scalp_field->memory_bytes() : 0;
  stage.add("memory_bytes",
            static_cast<std::int64_t>(v.scalp_distance->memory_bytes() + v.volume_field->memory_bytes()) + skin_bytes);
  // What the inputs were found to be, and how much of the scalp the region covers.
  const MeshReport& hull = inputs.volume_report;
  stage.add("volume_closed", hull.closed());
  stage.add("volume_parts", static_cast<std::int64_t>(hull.parts));
  stage.add("volume_boundary_loops", static_cast<std::int64_t>(hull.boundary_loops));
  stage.add("volume_nonmanifold_edges", static_cast<std::int64_t>(hull.nonmanifold_edges));
  stage.add("volume_flipped_patches", static_cast<std::int64_t>(hull.flipped_patches));
  stage.add("volume_reversed", inputs.volume_reversed);
  stage.add("scalp_inside_share", inputs.scalp_inside_share);
  stage.add("scalp_outside_share", 1.0 - inputs.scalp_inside_share);
}

void encode_value(ByteWriter& out, const StageValues& v) {
  encode(out, *v.scalp_distance);
  encode(out, *v.volume_field);
  out.put<std::uint8_t>(v.scalp_field != v.scalp_distance);
  if (v.scalp_field != v.scalp_distance) encode(out, *v.scalp_field);
}

void decode_value(ByteReader& in, StageValues& v) {
  v.scalp_distance = std::make_shared<const DistanceField>(decode_distance_field(in));
  v.volume_field = std::make_shared<const DistanceField>(decode_distance_field(in));
  v.scalp_field = in.get<std::uint8_t>() ? std::make_shared<const DistanceField>(decode_distance_field(in)) : v.scalp_distance;
}

ConfiguredStage configure(const Scene& scene) {
  const std::string& skin = scene.fields.skin_beyond_hairline;
  const SkinMode mode = skin == "shell" ? SkinMode::shell : skin == "auto" ? SkinMode::automatic : SkinMode::floor;
  ConfiguredStage c = configured(FieldsOptions{field_spec(scene, scene.inputs.scalp.string()),
                                               field_spec(scene, scene.inputs.volume.string()), mode},
                                 compute);
  c.files = {"scalp", "volume"};
  return c;
}

void write(StageRun& run, const Scene&) {
  const StageValues& v = run.values;
  const int threads = run.options.threads;
  if (!run.field_volumes) {  // a cached stage: converted again rather than stored
    run.field_volumes = std::vector<NrrdVolume>{field_to_nrrd(*v.scalp_distance, threads), field_to_nrrd(*v.volume_field, threads)};
    if (v.scalp_field != v.scalp_distance) run.field_volumes->push_back(field_to_nrrd(*v.scalp_field, threads));
  }
  const std::vector<NrrdVolume>& volumes = *run.field_volumes;
  run.output("fields/scalp.nrrd", [&](const std::filesystem::path& p) { write_nrrd(p, run.in_scene_frame(volumes[0])); });
  run.output("fields/volume.nrrd", [&](const std::filesystem::path& p) { write_nrrd(p, run.in_scene_frame(volumes[1])); });
  if (volumes.size() > 2)
    run.output("fields/skin.nrrd", [&](const std::filesystem::path& p) { write_nrrd(p, run.in_scene_frame(volumes[2])); });
  run.field_volumes.reset();
}

}  // namespace

const StageDescriptor& fields_stage() {
  static const StageDescriptor d{"fields", 1, nullptr, configure, nullptr, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
