#include "pipeline/stage_plan.h"

#include <stdexcept>

#include "core/digest.h"
#include "pipeline/build_id.h"
#include "pipeline/stage_codec.h"
#include "spec/scene_keys.h"

namespace hairfit {

namespace {

bool names_part(const std::string& key, const std::string& part) {
  return key == part || (key.size() > part.size() && key.compare(0, part.size(), part) == 0 && key[part.size()] == '.');
}

StageDeclaration named(const char* name) {
  StageDeclaration d;
  d.name = name;
  return d;
}

void append(std::vector<std::string>& to, std::initializer_list<const char*> items) {
  to.insert(to.end(), items.begin(), items.end());
}

// The rod's material and discretisation (stage_options.cpp hair_material, rod_discretisation);
// weight only with gravity, the support only with contact.
void read_rod(const Scene& scene, StageDeclaration& d) {
  append(d.reads, {"hair.youngs_modulus", "hair.shear_modulus", "hair.cross_section", "rod.integrator", "rod.segments",
                   "effects.gravity", "effects.contact", "units.down", "units.front"});
  if (scene.effects.gravity) append(d.reads, {"hair.mass_density", "rod.gravity"});
  if (scene.effects.contact) append(d.reads, {"contact.stiffness", "contact.layer"});
}

// strand_options(): winding and cutting parameters only when those effects are on.
void read_strands(const Scene& scene, StageDeclaration& d) {
  append(d.reads, {"strands.points", "strands.root_radius", "strands.tip_radius", "effects.winding", "effects.cutting"});
  if (scene.effects.winding) append(d.reads, {"strands.turns"});
  if (scene.effects.cutting) append(d.reads, {"strands.cut_threshold", "strands.cut_tips"});
}

}  // namespace

std::vector<StageDeclaration> stage_declarations(const Scene& scene) {
  const bool density = scene.effects.density != DensityModel::none;
  std::vector<StageDeclaration> stages;

  StageDeclaration fields = named("fields");
  append(fields.reads, {"fields"});
  append(fields.files, {"scalp", "volume"});
  stages.push_back(fields);

  StageDeclaration chart = named("chart");
  append(chart.reads, {"units.front", "units.down"});
  append(chart.files, {"scalp"});
  stages.push_back(chart);

  StageDeclaration roots = named("roots");
  append(roots.reads, {"seed", "hair.density", "hair.length", "hair.tilt", "roots", "effects.maps"});
  if (scene.effects.uses_map("density")) roots.files.push_back("density map");
  if (scene.effects.uses_map("tilt")) {
    roots.files.push_back("tilt map");
    roots.reads.push_back("hair.tilt_range");
  }
  if (scene.effects.uses_map("length")) {
    roots.files.push_back("length map");
    roots.reads.push_back("hair.length_range");
  }
  append(roots.consumes, {"chart"});
  roots.reads.push_back("hair.flow");
  if (scene.hair.flow != "local")
    append(roots.reads, {"hair.flow_smoothing", "hair.swirl", "hair.whorl", "hair.whorl_radius", "hair.parting",
                         "hair.parting_radius"});
  if (scene.hair.flow == "relief") {  // the hull's grain
    roots.reads.push_back("hair.relief_radius");
    roots.files.push_back("volume");
  }
  // Tilting toward the thicker layer reads the volume's distance field at each root.
  if (scene.hair.tilt_toward == "thicker") {
    roots.reads.push_back("hair.tilt_toward");
    roots.consumes.push_back("fields");
  }
  stages.push_back(roots);

  StageDeclaration preguides = named("preguides");
  read_rod(scene, preguides);
  append(preguides.reads, {"preguides"});
  append(preguides.consumes, {"fields", "roots"});
  if (scene.preguides.immersion == "layer" && scene.hair.flow != "local") {  // they follow the growth field
    append(preguides.reads, {"hair", "roots"});
    preguides.consumes.push_back("chart");
    if (scene.hair.flow == "relief") preguides.files.push_back("volume");
  }
  stages.push_back(preguides);

  StageDeclaration guides = named("guides");
  read_rod(scene, guides);
  append(guides.reads, {"guides", "effects.density"});
  append(guides.consumes, {"fields", "roots", "preguides"});
  if (density) {  // batches against the density of the earlier ones (stage_options.cpp guide_density_options)
    append(guides.reads, {"density", "fields.max_memory"});
    read_strands(scene, guides);
    guides.files.push_back("volume");
  }
  stages.push_back(guides);

  StageDeclaration strands = named("strands");
  read_strands(scene, strands);
  append(strands.reads, {"hair.cross_section"});  // fibre widths
  if (scene.strands.contain > 0.0) append(strands.reads, {"strands.contain"});  // the deposit's fibres do not
  append(strands.consumes, {"roots", "guides"});
  if (scene.effects.cutting || scene.strands.contain > 0.0)
    strands.consumes.push_back("fields");  // cut where the fibres leave the volume, or held in it
  // Not stored: the strands (and the density of the final fibres) are hit only when nothing
  // before them changed, while every new weight or strand setting would add the largest entry of
  // all (31 MB for the spheroid's 68 000 fibres, against 15 MB for its guides); rebuilding them
  // from the cached guides takes about a second.
  strands.cached = false;
  stages.push_back(strands);

  if (density) {
    StageDeclaration d = named("density");
    append(d.reads, {"effects.density", "density.voxel", "fields.max_memory", "units.down", "units.front"});
    append(d.files, {"volume"});
    append(d.consumes, {"fields", "strands"});
    d.cached = false;  // as the strands it is made from
    stages.push_back(d);
  }

  for (const StageDeclaration& s : stages)
    for (const std::string& part : s.reads) {
      bool known = false;
      for (const SceneKey& k : scene_keys()) known = known || names_part(k.name, part);
      if (!known) throw std::logic_error("stage " + s.name + " declares it reads \"" + part + "\", which is no scene key");
    }
  return stages;
}

std::string canonical_scene_parts(const Scene& scene, const std::vector<std::string>& reads) {
  std::string text;
  for (const SceneKey& k : scene_keys()) {
    bool read = false;
    for (const std::string& part : reads) read = read || names_part(k.name, part);
    // Paths are read through their content (input_digest), never by name.
    if (read && k.kind != KeyKind::path) text += k.name + " = " + k.show(scene) + "\n";
  }
  return text;
}

std::string input_digest(const Inputs& inputs, const std::string& file) {
  Digest d;
  auto mesh = [&d](const Mesh& m) {
    d.add(m.positions);
    d.add(static_cast<std::int64_t>(m.triangles.size()));
    d.add_bytes(m.triangles.data(), m.triangles.size() * sizeof(Vec3i));
  };
  auto map = [&d, &file](const std::optional<GreyMap>& m) {
    if (!m) throw std::logic_error("the " + file + " is read but was not loaded");
    d.add(static_cast<std::int64_t>(m->width)).add(static_cast<std::int64_t>(m->height)).add(static_cast<std::int64_t>(m->bits));
    d.add_bytes(m->values.data(), m->values.size() * sizeof(float));
  };
  if (file == "scalp") mesh(inputs.scalp.mesh);
  else if (file == "volume") mesh(inputs.volume.mesh);
  else if (file == "density map") map(inputs.density_map);
  else if (file == "tilt map") map(inputs.tilt_map);
  else if (file == "length map") map(inputs.length_map);
  else throw std::logic_error("no input file named " + file);
  return d.hex();
}

std::map<std::string, std::string> stage_keys(const Scene& scene, const Inputs& inputs) {
  std::map<std::string, std::string> keys;
  for (const StageDeclaration& s : stage_declarations(scene)) {
    // Two independently salted 64-bit digests: a 128-bit key, so unrelated entries never collide.
    std::string key;
    for (const char* salt : {"hairfit-stage-key/1 a", "hairfit-stage-key/1 b"}) {
      Digest d;
      d.add(salt).add(s.name).add(static_cast<std::int64_t>(s.version)).add(static_cast<std::int64_t>(kStageCodecVersion));
      d.add(build_id()).add(source_fingerprint());
      d.add(canonical_scene_parts(scene, s.reads));
      for (const std::string& f : s.files) d.add(f).add(input_digest(inputs, f));
      for (const std::string& c : s.consumes) d.add(c).add(keys.at(c));
      key += d.hex();
    }
    keys[s.name] = key;
  }
  return keys;
}

}  // namespace hairfit
