// libFuzzer target: the OBJ loader and what the scalp checks do with its mesh (topology, the disk
// requirement, the chart's orientation checks and the Floater chart itself on small meshes).
#include <cstddef>
#include <cstdint>

#include "core/error.h"
#include "fuzz_input_file.h"
#include "io/obj_mesh.h"
#include "scalp/chart.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path path = hairfit::fuzz::write_input(data, size, ".obj");
  try {
    const hairfit::LoadedMesh loaded = hairfit::load_obj_mesh(path, 1.0);
    hairfit::winding_number(loaded.mesh, hairfit::Vec3(0.1, 0.2, 0.3));
    if (loaded.mesh.triangles.size() <= 2000)
      hairfit::make_scalp_chart(loaded.mesh, hairfit::Vec3(0, 0, 1), hairfit::Vec3(0, -1, 0), path.string());
  } catch (const hairfit::InputError&) {
  }
  return 0;
}
