#include "pipeline/stage_plan.h"

#include <stdexcept>

#include "core/digest.h"
#include "pipeline/build_id.h"
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"

namespace hairfit {

std::vector<ConfiguredStage> configure_stages(const Scene& scene) {
  std::vector<ConfiguredStage> stages;
  for (const StageDescriptor* stage : stage_table())
    if (!stage->present || stage->present(scene)) {
      stages.push_back(stage->configure(scene));
      stages.back().name = stage->name;
      stages.back().version = stage->version;
    }
  return stages;
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

std::map<std::string, std::string> stage_keys(const std::vector<ConfiguredStage>& stages, const Inputs& inputs) {
  std::map<std::string, std::string> keys;
  for (const ConfiguredStage& s : stages) {
    // Two independently salted 64-bit digests: a 128-bit key, so unrelated entries never collide.
    std::string key;
    for (const char* salt : {"hairfit-stage-key/1 a", "hairfit-stage-key/1 b"}) {
      Digest d;
      d.add(salt).add(s.name).add(static_cast<std::int64_t>(s.version)).add(static_cast<std::int64_t>(kStageCodecVersion));
      d.add(build_id()).add(source_fingerprint());
      d.add(s.options);
      for (const std::string& f : s.files) d.add(f).add(input_digest(inputs, f));
      for (const std::string& c : s.consumes) d.add(c).add(keys.at(c));
      key += d.hex();
    }
    keys[s.name] = key;
  }
  return keys;
}

std::map<std::string, std::string> stage_keys(const Scene& scene, const Inputs& inputs) {
  return stage_keys(configure_stages(scene), inputs);
}

}  // namespace hairfit
