#include "pipeline/stage_plan.h"

#include <stdexcept>

#include "core/digest.h"
#include "pipeline/build_id.h"
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "spec/scene_keys.h"

namespace hairfit {

namespace {

bool names_part(const std::string& key, const std::string& part) {
  return key == part || (key.size() > part.size() && key.compare(0, part.size(), part) == 0 && key[part.size()] == '.');
}

}  // namespace

std::vector<StageDeclaration> stage_declarations(const Scene& scene) {
  std::vector<StageDeclaration> stages;
  for (const StageDescriptor* stage : stage_table())
    if (!stage->present || stage->present(scene)) {
      stages.push_back(stage->declare(scene));
      stages.back().name = stage->name;
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
  auto map = [&d, &file](const std::shared_ptr<const GreyMap>& m) {
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
