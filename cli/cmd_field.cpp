// hairfit field MESH.obj --voxel H --band B [--margin M] [--max-memory GIB] --out F.nrrd [--threads N]
// One distance field (docs/design.md §2), timed: the time printed is make_distance_field alone (no file
// reading or writing).
#include <chrono>
#include <cstdio>

#include "args.h"
#include "commands.h"
#include "core/parallel.h"
#include "field/distance_field.h"
#include "field/field_nrrd.h"
#include "io/obj_mesh.h"

namespace hairfit::cli {

int command_field(const Arguments& argv) {
  const Args args(argv, {"voxel", "band", "margin", "max-memory", "out", "threads"}, {});
  if (args.positionals().size() != 1) throw UsageError{"expected exactly one MESH file"};
  if (!args.has("voxel")) throw UsageError{"--voxel H (cm) is required"};
  if (!args.has("band")) throw UsageError{"--band B (voxels) is required"};
  if (!args.has("out")) throw UsageError{"--out F.nrrd is required"};
  FieldSpec spec;
  spec.voxel = args.number("voxel", spec.voxel);
  spec.band = args.number("band", spec.band);
  spec.margin = args.number("margin", spec.margin);
  spec.max_memory_gib = args.number("max-memory", spec.max_memory_gib);
  spec.name = args.positionals()[0];
  const int threads = resolve_thread_count(args.integer("threads", 0));
  if (threads < 1) throw UsageError{"--threads must be ≥ 0 (0 = all cores)"};

  const LoadedMesh loaded = load_obj_mesh(args.positionals()[0]);
  const auto start = std::chrono::steady_clock::now();
  const DistanceField field = make_distance_field(loaded.mesh, spec, threads);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  write_nrrd(*args.text("out"), field_to_nrrd(field));

  std::printf("%s: %zu triangles\n", spec.name.c_str(), loaded.mesh.triangles.size());
  std::printf("  grid     %d×%d×%d voxels of %g cm, origin (%g, %g, %g) cm\n", field.dims().x(), field.dims().y(),
              field.dims().z(), field.voxel(), field.origin().x(), field.origin().y(), field.origin().z());
  std::printf("  band     %g voxels = %g cm, %lld voxels exact\n", spec.band, field.band_width(),
              static_cast<long long>(field.band_voxels()));
  std::printf("  time     %.3f s on %d thread(s) (distance field only)\n", seconds, threads);
  std::printf("  wrote    %s\n", args.text("out")->c_str());
  return 0;
}

}  // namespace hairfit::cli
