// `hairfit prepare`: from one raw scan of a bust or head to the two meshes and the scene a run
// needs. Cut the hair hull (hair_region.h), derive the scalp and the closed hair volume
// (scalp_offset.h), check both, and write DIR/volume.obj, DIR/scalp.obj, DIR/scene.toml and
// DIR/prepare.json (what was done, for `hairfit render SCENE --stage cut` and for the user).
#pragma once
#include <filesystem>
#include <optional>
#include <string>

#include "prepare/hair_region.h"
#include "prepare/scalp_offset.h"
#include "prepare/untangle.h"

namespace hairfit {

struct PrepareOptions {
  HairSelection selection;          // in the scan's own coordinates and units
  std::string units = "cm";         // the scan's unit: mm, cm, dm, m or in
  double head_height = 0.0;         // cm; when > 0, scales the scan so its extent along up is this
  std::optional<Vec3> up, front;    // declared directions; detected when absent
  double weld_tolerance = -1.0;     // scan units; < 0: 1e-6 × the scan's bounding-box diagonal
  HullOptions hull;
  ScalpOptions scalp;               // cm
  // How the scalp is made: "radial" (scalp_offset.h: moved toward the head centre under a robust
  // envelope; only for hulls star-shaped about it), "level-set" (scalp_level_set.h: any hull), or
  // "auto": radial where the hull is star-shaped and the result passes every check, else the
  // level set.
  std::string scalp_method = "auto";
  int threads = 0;                  // 0: all; the result is the same for any count
};

struct PrepareChecks {
  bool hull_disk = false, scalp_disk = false;
  int scalp_inward_triangles = 0;   // triangles whose outer side is not in the layer (must be 0)
  int intersections = 0;            // among hull, floor and scalp, triangles sharing no vertex
  double deepest_winding = 0.0;     // winding number in the volume of the scalp vertex farthest in
  bool hairline_shared = false;     // scalp and hull hairline vertices identical
  Vec3 first_inward = Vec3::Zero(), first_intersection = Vec3::Zero();  // where, for the message
  // How smooth the scalp is where the layer is at least half its crown thickness: the 95th
  // percentile and the largest of the vertices' mean curvature |H| (1/cm; a 9 cm skull has 0.11).
  double curvature_p95 = 0.0, curvature_max = 0.0;
};

struct Prepared {
  Hull hull;                 // cm
  ScalpResult scalp;         // cm
  double scale_to_cm = 1.0;
  Vec3 up = Vec3::UnitY(), front = Vec3::UnitZ();
  std::string up_how, front_how;  // "declared", or how they were detected
  int welded_vertices = 0;
  int refine_splits = 0;  // rounds a coarse scan's triangles were split into four (refine.h)
  double median_edge_before = 0.0, median_edge_after = 0.0;  // scan units
  Untangled untangled;    // the hull's self-intersections smoothed away (untangle.h; cm, places in the centred frame)
  // What prepare repaired, one sentence each, for stdout and prepare.json ("repaired"): empty
  // when the scan and the surfaces made from it needed nothing.
  std::vector<std::string> repairs;
  std::string scalp_how;  // which method made the scalp, and why
  PrepareChecks checks;
  // The meshes are in the scan's own frame (scaled to cm); they were computed about this point
  // (cm), near the data (core/mesh.h, frame_origin), where doubles resolve a head's details whatever its
  // distance from the origin. The checks' positions (first_inward, …) are in that centred frame.
  Vec3 origin = Vec3::Zero();
};


// Everything but the writing. Throws InputError naming `file` for bad options, a selection that
// catches nothing or no one connected region, a mask without colours, a hull the scalp cannot be
// built under, or a failed check.
Prepared prepare_scan(const Mesh& scan, const std::vector<Vec3>& colors, const PrepareOptions& options,
                      const std::string& file);

// The scene text: relative paths, cm, down = −up, front, cutting on, hair length and tilt left
// for the run to derive from the layer (with the thin-shell defaults), everything else default.
std::string prepared_scene_text(const Prepared& prepared, const std::string& scan_name, const PrepareOptions& options);

// Writes the four files into `dir` (each atomically, all computed first).
void write_prepared(const Prepared& prepared, const std::filesystem::path& scan, const PrepareOptions& options,
                    const std::filesystem::path& dir);

}  // namespace hairfit
