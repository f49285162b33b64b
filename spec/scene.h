// The scene: everything a run needs, declared in one TOML file (spec/reference.md documents every
// key). parse_scene() turns the text into this immutable value; each table of the file is one
// section struct below, with the defaults written here once (the reference page is generated
// from them). Paths are absolute, resolved against the scene file's folder.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/types.h"

namespace hairfit {

inline constexpr const char* kSceneFormat = "hairfit-scene/1";

enum class DensityModel { none, binary, continuous };

// The keys whose absence (with no length or tilt map) makes the run derive the hair from the shell
// (SceneHair::from_shell); a resolved scene leaves them unset too, so that its run derives them again.
inline constexpr std::array<const char*, 2> kShellTriggerKeys{"hair.length", "hair.tilt"};

struct SceneUnits {
  std::string length = "cm";  // unit of the mesh coordinates: mm, cm, dm, m, in
  Vec3 down{0, -1, 0};        // world direction of gravity and of "down" on the head (unit)
  Vec3 front{0, 0, 1};        // world direction the face looks to; orients the chart and maps
  double to_cm() const;       // factor from the mesh unit to cm
};

struct SceneInputs {
  std::filesystem::path scalp;
  std::filesystem::path volume;
};

// Effects are off unless declared; what is off is never computed.
struct SceneEffects {
  bool gravity = false;
  bool contact = false;  // the scalp as a support ([contact])
  DensityModel density = DensityModel::none;
  std::vector<std::string> maps;  // which of "density", "tilt", "length" are used
  bool cutting = false;
  bool winding = false;
  bool uses_map(const std::string& name) const;
  std::vector<std::string> names() const;  // declared effects, for reports ("gravity", "density:continuous", ...)
};

struct SceneMaps {
  std::optional<std::filesystem::path> density, tilt, length;
};

struct SceneHair {
  double density = 200.0;                   // hairs per cm² of scalp (× density map)
  double length = 25.0;                     // cm, every hair, when the length map is not used
  std::array<double, 2> length_range{15.0, 35.0};  // cm, length map black → white
  double tilt = 0.0;                        // degrees from the normal toward tilt_toward, without tilt map
  std::array<double, 2> tilt_range{0.0, 90.0};     // degrees, tilt map black → white
  std::string tilt_toward = "down";         // down | thicker (up the hair layer's thickness gradient)
  // Set by the parser when the file leaves hair.length and hair.tilt unset (kShellTriggerKeys; and
  // no length or tilt map is used): the run derives both from the shell (scalp/shell_hair.h), and
  // the keys of the thin-shell machinery the file does not set take their shell defaults
  // (apply_shell_defaults).
  bool from_shell = false;
  std::string flow = "local";               // field (one smooth growth field) | relief (steered by the hull) | local
  double flow_smoothing = 6.0;              // cm: the growth field averages its guidance over this
  double relief_radius = 1.5;               // cm: with flow = relief, the reach of the hull's grain
  std::string relief_grain = "auto";        // auto (normals where combed from the crown, else edges) | edges (dihedral angles of the hull's edges) | normals (spread of its normals above the root)
  std::string comb = "auto";                // auto (hair that suits its shell: chosen from the hull, else into_layer) | into_layer (the paper: toward where the layer goes on) | from_crown (combed from the crown)
  std::string rest_shape = "straight";      // straight (the paper) | flow (styled along the growth field)
  double swirl = 0.0;                       // degrees: growth away from the layer's end turns clockwise
  double hang_margin = 0.0;                 // cm: with tilt_toward = hanging, hanging hair ends this far before its layer
  std::array<double, 2> whorl{0.0, 0.0};    // chart point of a crown whorl
  double whorl_radius = 0.0;                // cm (0: none)
  std::array<double, 2> parting{0.0, 1.0};  // chart point where a parting starts; it runs to the whorl
  double parting_radius = 0.0;              // cm (0: none)
  double youngs_modulus = 3.89e10;          // E, dyn/cm² (paper §3.1)
  double shear_modulus = 0.89e10;           // G, dyn/cm²
  double cross_section = 1.5e-5;            // A, cm² (circular: I = A²/4π, J = 2I)
  double mass_density = 1.32;               // g/cm³, for gravity
};

struct SceneFields {
  double voxel = 0.25;      // cm
  double band = 4.0;        // voxels: half-width of the band of exact distances
  double margin = 2.0;      // cm of grid beyond the mesh's bounding box
  double max_memory = 4.0;  // GiB for the grids of both fields together
  std::string skin_beyond_hairline = "floor";  // "floor" | "shell" | "auto" (field/skin_beyond_hairline.h)
};

struct SceneRoots {
  int guides = 3000;               // principal guides = clusters (paper: 3000)
  double preguide_spacing = 1.0;   // cm between pre-guide roots (paper: about 1 per cm)
  double cluster_overlap = 1.3;    // cluster circle radius / covering radius (≥ 1)
};

struct SceneRod {
  std::string integrator = "rk4";  // rk2 | rk4: Lie-group Runge–Kutta schemes
  int segments = 64;               // integration steps per rod
  double gravity = 981.0;          // cm/s², when effects.gravity
};

struct SceneContact {
  double stiffness = 5.0;  // dyn/cm²: force per length per cm into the contact layer
  double layer = 0.3;      // cm: how far above the scalp the support begins
};

struct ScenePreguides {
  std::array<double, 2> depth_range{0.15, 0.6};  // immersion depth / local thickness, top → bottom
  double max_load = 40.0;                         // dimensionless terminal-force cap (F L² / EI)
  std::string immersion = "tip";                  // tip (the paper) | layer (the whole rod in the layer)
};

struct SceneWeights {
  double direction = 0.4;   // w1, F1
  double similarity = 0.2;  // w2, F2
  double boundary = 0.4;    // w3, F3
  double density = 0.0;     // w4, F4 (needs effects.density)
};

struct SceneGuides {
  std::string start = "warm";      // warm (from neighbouring pre-guides) | straight (paper)
  int samples = 16;                // residual sample points per guide
  int neighbours = 3;              // pre-guides each guide follows (paper: 3)
  int max_iterations = 100;        // Levenberg–Marquardt iterations
  double tolerance = 1e-6;         // relative cost decrease at which a guide is converged
  std::string boundary = "smooth";  // smooth (C¹) | paper (eq. 9 exactly)
  double outside_penalty = 3.0;    // c_d, cm: extra cost outside the acceptable region (eq. 9)
  double boundary_width = 1.0;     // cm inside the surface over which the smooth form ramps c_d up
  int point_forces = 0;            // interior point forces per guide (0: the paper's terminal load)
  double point_force_weight = 1e-4;  // w5: weight of Σ|F_k|² on them
  SceneWeights weights;
};

struct SceneDensity {
  double voxel = 0.25;      // cm
  int batch = 64;           // guides optimised together against earlier batches
  double threshold = 0.5;   // BOM: occupancy above which the surcharge applies
  double surcharge = 10.0;  // c_BOM
  double strength = 1.0;    // c_ρ (CDM)
  int stall_iterations = 3;       // a guide's refinement with F4 stops after this many iterations …
  double stall_tolerance = 1e-4;  // … that together lowered its cost by less than this share
  int spread = 3;                 // passes spreading the fibres down their own density (0: off)
  std::string deposit = "tubes";  // CDM: what a guide's wisp deposits: tubes (lines over its cross-section) | fibres (the grown fibres)
};

struct SceneStrands {
  int points = 16;               // points per fibre
  double root_radius = 0.3;      // cm, radius of the wisp at the root
  double tip_radius = 0.6;       // cm, radius of the wisp at the tip
  double turns = 1.0;            // windings about the guide, when effects.winding
  double cut_threshold = 1.0;    // cm outside the volume before a fibre is cut, when effects.cutting
  bool cut_tips = false;         // with effects.cutting: a fibre ending outside is cut where it last left
  double contain = 0.0;          // cm: fibre points outside the volume by less than this move back in (0: none)
  std::string depth = "wisp";    // wisp (around the guide, the paper) | layer (spread through the layer's depth) | auto
};

struct SceneOutput {
  std::filesystem::path dir;                           // default: "out" beside the scene
  std::vector<std::string> strands{"hair", "obj"};     // hair | obj | usda | ply
  std::vector<std::string> renders{"front", "side"};   // views rendered after a full run
  std::array<double, 2> render_size{800, 800};         // pixels
  std::optional<std::filesystem::path> occluder;       // OBJ drawn opaque in 3D pictures (the scan, the head)
};

struct Scene {
  std::filesystem::path file;  // the scene file itself (absolute)
  std::string format = kSceneFormat;
  std::int64_t seed = 1;
  std::string preset = "default";  // accuracy preset (scene_presets): preview | default | final
  SceneUnits units;
  SceneInputs inputs;
  SceneEffects effects;
  SceneMaps maps;
  SceneHair hair;
  SceneFields fields;
  SceneRoots roots;
  SceneRod rod;
  SceneContact contact;
  ScenePreguides preguides;
  SceneGuides guides;
  SceneDensity density;
  SceneStrands strands;
  SceneOutput output;
  // Where each key given in the file was written, by dotted name ("guides.weights.boundary"),
  // so later stages can point at the line behind a problem.
  std::map<std::string, SourceLocation> locations;
  // The keys the file leaves unset that a rule set, with the rule: "preset \"final\"" or
  // "shell default" (apply_shell_defaults). The resolved scene names them (spec/resolved_scene.h).
  std::map<std::string, std::string> implied;
  // The vector3 keys given in the file, as written (before normalising): the resolved scene repeats
  // them, since normalising a unit vector again may move its last bit.
  std::map<std::string, Vec3> directions_as_written;

  // A diagnostic at a key's location (or at the file when the key took its default).
  Diagnostic at(const std::string& key, const std::string& message) const;
};

// An accuracy preset: values for the accuracy knobs that a scene naming it takes for every knob
// it does not set itself (docs/results/accuracy.md measures them).
struct ScenePreset {
  std::string name;
  std::string doc;
  std::vector<std::pair<std::string, double>> values;  // dotted key → value
};
const std::vector<ScenePreset>& scene_presets();

// Parses and validates a scene file. Throws InputError carrying every problem found (unknown keys
// with suggestions, wrong types, out-of-range values, missing files, weights not summing to 1).
Scene parse_scene(const std::filesystem::path& file);
Scene parse_scene_text(const std::string& text, const std::filesystem::path& file);

}  // namespace hairfit
