#include "spec/scene_keys.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace hairfit {

// `show` gives the value itself (the stage cache keys on it) and the documented defaults stay short.
std::string number_text(double x) {
  char buffer[64];
  if (x == std::floor(x) && std::fabs(x) < 1e16) {
    std::snprintf(buffer, sizeof buffer, "%.0f", x);
    return buffer;
  }
  for (int digits = 10; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
    if (std::strtod(buffer, nullptr) == x) break;
  }
  return buffer;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
};
Range closed(double lo, double hi) { return {lo, hi, false, false}; }
Range above(double lo, double hi = kInf) { return {lo, hi, true, false}; }  // (lo, hi]
Range any() { return {}; }

std::string toml_string(const std::string& s) { return '"' + s + '"'; }

std::string list_text(const std::vector<std::string>& items) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + toml_string(items[i]);
  return out + "]";
}

SceneKey make(std::string name, KeyKind kind, std::string unit, Range range, std::string feeds, std::string doc) {
  SceneKey k;
  k.name = std::move(name);
  k.kind = kind;
  k.unit = std::move(unit);
  k.lo = range.lo;
  k.hi = range.hi;
  k.lo_open = range.lo_open;
  k.hi_open = range.hi_open;
  k.feeds = std::move(feeds);
  k.doc = std::move(doc);
  return k;
}

// `ref` is a captureless lambda Scene& → member&, so one table row names its member once.
template <class Ref>
SceneKey number(std::string name, Ref ref, std::string unit, Range range, std::string feeds, std::string doc) {
  SceneKey k = make(std::move(name), KeyKind::number, std::move(unit), range, std::move(feeds), std::move(doc));
  k.store = [ref](Scene& s, const std::vector<double>& x, const std::vector<std::string>&) { ref(s) = x[0]; };
  k.show = [ref](const Scene& s) { Scene c = s; return number_text(ref(c)); };
  return k;
}

template <class Ref>
SceneKey integer(std::string name, Ref ref, std::string unit, Range range, std::string feeds, std::string doc) {
  SceneKey k = make(std::move(name), KeyKind::integer, std::move(unit), range, std::move(feeds), std::move(doc));
  k.store = [ref](Scene& s, const std::vector<double>& x, const std::vector<std::string>&) {
    ref(s) = static_cast<std::decay_t<decltype(ref(s))>>(x[0]);
  };
  k.show = [ref](const Scene& s) { Scene c = s; return number_text(static_cast<double>(ref(c))); };
  return k;
}

template <class Ref>
SceneKey boolean(std::string name, Ref ref, std::string feeds, std::string doc) {
  SceneKey k = make(std::move(name), KeyKind::boolean, "", any(), std::move(feeds), std::move(doc));
  k.store = [ref](Scene& s, const std::vector<double>& x, const std::vector<std::string>&) { ref(s) = x[0] != 0.0; };
  k.show = [ref](const Scene& s) { Scene c = s; return std::string(ref(c) ? "true" : "false"); };
  return k;
}

template <class Ref>
SceneKey text(std::string name, Ref ref, std::vector<std::string> choices, std::string feeds, std::string doc) {
  SceneKey k = make(std::move(name), KeyKind::text, "", any(), std::move(feeds), std::move(doc));
  k.choices = std::move(choices);
  k.store = [ref](Scene& s, const std::vector<double>&, const std::vector<std::string>& t) { ref(s) = t[0]; };
  k.show = [ref](const Scene& s) { Scene c = s; return toml_string(ref(c)); };
  return k;
}

template <class Ref>
SceneKey pair(std::string name, Ref ref, std::string unit, Range range, std::string feeds, std::string doc) {
  SceneKey k = make(std::move(name), KeyKind::pair, std::move(unit), range, std::move(feeds), std::move(doc));
  k.store = [ref](Scene& s, const std::vector<double>& x, const std::vector<std::string>&) { ref(s) = {x[0], x[1]}; };
  k.show = [ref](const Scene& s) {
    Scene c = s;
    return "[" + number_text(ref(c)[0]) + ", " + number_text(ref(c)[1]) + "]";
  };
  return k;
}

// A chart point [x, y] in the closed unit disk: stored and shown as a pair.
template <class Ref>
SceneKey point2(std::string name, Ref ref, std::string feeds, std::string doc) {
  SceneKey k = pair(std::move(name), ref, "", closed(-1, 1), std::move(feeds), std::move(doc));
  k.kind = KeyKind::point2;
  return k;
}

template <class Ref>
SceneKey vector3(std::string name, Ref ref, std::string feeds, std::string doc) {
  SceneKey k = make(std::move(name), KeyKind::vector3, "", any(), std::move(feeds), std::move(doc));
  k.store = [ref](Scene& s, const std::vector<double>& x, const std::vector<std::string>&) {
    ref(s) = Vec3(x[0], x[1], x[2]).normalized();
  };
  k.show = [ref](const Scene& s) {
    Scene c = s;
    const Vec3 v = ref(c);
    return "[" + number_text(v.x()) + ", " + number_text(v.y()) + ", " + number_text(v.z()) + "]";
  };
  return k;
}

template <class Ref>
SceneKey text_list(std::string name, Ref ref, std::vector<std::string> choices, std::string feeds, std::string doc) {
  SceneKey k = make(std::move(name), KeyKind::text_list, "", any(), std::move(feeds), std::move(doc));
  k.choices = std::move(choices);
  k.store = [ref](Scene& s, const std::vector<double>&, const std::vector<std::string>& t) { ref(s) = t; };
  k.show = [ref](const Scene& s) { Scene c = s; return list_text(ref(c)); };
  return k;
}

SceneKey path(std::string name, std::filesystem::path& (*ref)(Scene&), bool required, std::string feeds, std::string doc) {
  SceneKey k = make(std::move(name), KeyKind::path, "", any(), std::move(feeds), std::move(doc));
  k.required = required;
  k.store = [ref](Scene& s, const std::vector<double>&, const std::vector<std::string>& t) { ref(s) = t[0]; };
  k.show = [](const Scene&) { return std::string("(required)"); };
  return k;
}

SceneKey optional_path(std::string name, std::optional<std::filesystem::path>& (*ref)(Scene&), std::string feeds,
                       std::string doc) {
  SceneKey k = make(std::move(name), KeyKind::path, "", any(), std::move(feeds), std::move(doc));
  k.store = [ref](Scene& s, const std::vector<double>&, const std::vector<std::string>& t) { ref(s) = t[0]; };
  k.show = [](const Scene&) { return std::string("(none)"); };
  return k;
}

#define REF(member) [](Scene& s) -> auto& { return s.member; }
#define PATH_REF(member) [](Scene& s) -> std::filesystem::path& { return s.member; }
#define OPT_REF(member) [](Scene& s) -> std::optional<std::filesystem::path>& { return s.member; }

std::vector<SceneKey> build_keys() {
  std::vector<SceneKey> keys;
  {
    SceneKey k = text("format", REF(format), {kSceneFormat}, "scene",
                      "Version of the scene format; required, so old scenes can be migrated.");
    k.required = true;
    k.show = [](const Scene&) { return toml_string(kSceneFormat) + " (required)"; };
    keys.push_back(k);
  }
  keys.push_back(integer("seed", REF(seed), "", closed(0, 9007199254740991.0), "roots, clusters, strands",
                         "Seed of every random choice; same scene and seed give byte-identical results."));
  keys.push_back(text("preset", REF(preset), {"preview", "default", "final"}, "rod, fields, guides, density",
                      "Accuracy preset: values for the accuracy knobs the scene does not set itself (table below)."));

  keys.push_back(text("units.length", REF(units.length), {"mm", "cm", "dm", "m", "in"}, "inputs",
                      "Length unit of the mesh coordinates; everything is converted to cm on loading."));
  keys.push_back(vector3("units.down", REF(units.down), "roots, gravity",
                         "World direction of down: hair tilts toward it, gravity pulls along it."));
  keys.push_back(vector3("units.front", REF(units.front), "chart, maps",
                         "World direction the face looks to; puts the forehead at the top of every map."));

  keys.push_back(path("inputs.scalp", PATH_REF(inputs.scalp), true, "fields, chart, roots",
                      "Scalp mesh (OBJ): an open topological disk, outward normals, hair grows from it."));
  keys.push_back(path("inputs.volume", PATH_REF(inputs.volume), true, "fields",
                      "Outer boundary of the hair volume (OBJ): closed, or open and raw (in parts, with holes, non-manifold); with the scalp reversed it encloses the hair."));

  keys.push_back(boolean("effects.gravity", REF(effects.gravity), "preguides, guides",
                         "Load every rod by its weight per length ρ·A·g along units.down."));
  keys.push_back(boolean("effects.contact", REF(effects.contact), "preguides, guides",
                         "The scalp as a support: a unilateral force per length from the scalp's distance field holds "
                         "hair out of the head and lets long hair lie on it ([contact])."));
  {
    SceneKey k = make("effects.density", KeyKind::text, "", any(), "guides, density",
                      "Density model against hair–hair crowding (paper §3.5): none, binary (BOM) or continuous (CDM).");
    k.choices = {"none", "binary", "continuous"};
    k.store = [](Scene& s, const std::vector<double>&, const std::vector<std::string>& t) {
      s.effects.density = t[0] == "binary" ? DensityModel::binary
                          : t[0] == "continuous" ? DensityModel::continuous : DensityModel::none;
    };
    k.show = [](const Scene& s) {
      return toml_string(s.effects.density == DensityModel::binary ? "binary"
                    : s.effects.density == DensityModel::continuous ? "continuous" : "none");
    };
    keys.push_back(k);
  }
  keys.push_back(text_list("effects.maps", REF(effects.maps), {"density", "tilt", "length"}, "roots",
                           "Which grey maps of [maps] are used; each listed map must have a path."));
  keys.push_back(boolean("effects.cutting", REF(effects.cutting), "strands",
                         "Cut fibres that leave the volume for longer than strands.cut_threshold (§3.6)."));
  keys.push_back(boolean("effects.winding", REF(effects.winding), "strands",
                         "Wind the fibres of a wisp about their guide by strands.turns turns (§3.6)."));

  keys.push_back(optional_path("maps.density", OPT_REF(maps.density), "roots",
                               "Grey PNG: hair density factor, black = no hair, white = hair.density."));
  keys.push_back(optional_path("maps.tilt", OPT_REF(maps.tilt), "roots",
                               "Grey PNG: tilt of the growth direction from the normal (toward hair.tilt_toward), over hair.tilt_range."));
  keys.push_back(optional_path("maps.length", OPT_REF(maps.length), "roots, strands",
                               "Grey PNG: hair length, over hair.length_range."));

  keys.push_back(number("hair.density", REF(hair.density), "1/cm²", above(0, 2000), "roots",
                        "Hairs per cm² of scalp surface (paper: 200), times the density map when used."));
  keys.push_back(number("hair.length", REF(hair.length), "cm", above(0, 500), "roots, guides, strands",
                        "Length of every hair when the length map is not used."));
  keys.push_back(pair("hair.length_range", REF(hair.length_range), "cm", above(0, 500), "roots",
                      "Lengths for black and white of the length map."));
  keys.push_back(number("hair.tilt", REF(hair.tilt), "degrees", closed(0, 90), "roots",
                        "Tilt of the growth direction from the normal (toward hair.tilt_toward) when the tilt map is not used."));
  keys.push_back(pair("hair.tilt_range", REF(hair.tilt_range), "degrees", closed(0, 90), "roots",
                      "Tilts for black and white of the tilt map."));
  keys.push_back(text("hair.tilt_toward", REF(hair.tilt_toward), {"down", "thicker", "hanging"}, "roots",
                      "Where the normal tilts: toward down; up the surface gradient of the hair layer's thickness "
                      "(depth below the volume boundary), blended with down where the layer is flat; or hanging: as "
                      "thicker, but toward down where the layer below a root holds a hanging hair (a bob's curtain), "
                      "whose pre-guide is then the paper's and which ends where that layer ends."));
  keys.push_back(text("hair.flow", REF(hair.flow), {"local", "field", "relief"}, "roots",
                      "Where each root's tilt points: local, its own tilt_toward direction (the paper); field, one smooth "
                      "growth field over the scalp aligned with it (Knöppel et al. 2013), so neighbouring roots grow alike; "
                      "relief, that field steered by the hull's carved grooves and ridges (its grain, hair.relief_radius)."));
  keys.push_back(text("hair.rest_shape", REF(hair.rest_shape), {"straight", "flow"}, "preguides, guides",
                      "A fibre's shape at rest: straight (the paper); or flow, styled along the growth field: the path "
                      "from its root along the field at its immersion depth in the layer, so that the unloaded rod "
                      "follows the flow and the loads only correct it (needs hair.flow = \"field\" or \"relief\")."));
  keys.push_back(number("hair.flow_smoothing", REF(hair.flow_smoothing), "cm", above(0, 100), "roots",
                        "With hair.flow = \"field\" or \"relief\": the distance over which the growth field averages its guidance."));
  keys.push_back(number("hair.swirl", REF(hair.swirl), "degrees", closed(-90, 90), "roots",
                        "With a growth field and tilt_toward = \"thicker\" or \"hanging\": hair that grows away from where the layer "
                        "ends turns clockwise (seen from outside) by this, so on a cap it spirals to the crown like a whorl "
                        "instead of meeting there head on."));
  keys.push_back(number("hair.hang_margin", REF(hair.hang_margin), "cm", closed(0, 100), "roots",
                        "With tilt_toward = \"hanging\": the layer below a root counts as ending this much sooner, so a "
                        "hanging hair ends this far before the hull's lower edge instead of at it (a heavy rod sags and a "
                        "wisp spreads past the probe's path)."));
  keys.push_back(point2("hair.whorl", REF(hair.whorl), "roots",
                      "With a growth field: the chart point (x to the person's right, y to the front) of a crown whorl, "
                      "from which hair grows, turned clockwise by hair.swirl."));
  keys.push_back(number("hair.whorl_radius", REF(hair.whorl_radius), "cm", closed(0, 100), "roots",
                        "How far the whorl steers the growth field (its weight falls as exp(−d²/r²)); 0 declares no whorl."));
  keys.push_back(point2("hair.parting", REF(hair.parting), "roots",
                      "With a growth field: the chart point where a parting starts; it runs straight (in the chart) to hair.whorl, "
                      "and hair grows away from it on either side."));
  keys.push_back(number("hair.parting_radius", REF(hair.parting_radius), "cm", closed(0, 100), "roots",
                        "How far the parting steers the growth field; 0 declares no parting."));
  keys.push_back(number("hair.relief_radius", REF(hair.relief_radius), "cm", above(0, 100), "roots",
                        "With hair.flow = \"relief\": how far around a scalp point the hull's ridges and grooves are read."));
  keys.push_back(text("hair.relief_grain", REF(hair.relief_grain), {"auto", "edges", "normals"}, "roots",
                      "With hair.flow = \"relief\", how the hull's grain is read: edges, from the dihedral angles of the "
                      "hull's edges within hair.relief_radius of the root; or normals, from the spread of the hull's face "
                      "normals over the hull above the root, at ½, 1 and 2 × hair.relief_radius, whichever is most "
                      "anisotropic (scan noise and a coarse triangulation bias it less); auto, normals where the hair is "
                      "combed from the crown, else edges."));
  keys.push_back(text("hair.comb", REF(hair.comb), {"auto", "into_layer", "from_crown"}, "roots",
                      "With a growth field, which way along its lines hair grows: into_layer, toward where the layer "
                      "goes on (the paper's thicker layer, away from where it ends); or from_crown, as carved hair is "
                      "combed: away from the crown and down (the hull's grain signed so), each hair as long as the layer "
                      "ahead of it, less 2 cm (nearer the end, a third of the way there), where it lies (a declared "
                      "hair.length is the most it gets). auto: for hair that suits its shell, from_crown where the layer "
                      "thickens toward the crown under at least 80 % of the scalp's area and hangs from under 25 % of it "
                      "(a carved cap), else into_layer; the run reports the choice and its shares."));
  keys.push_back(number("hair.youngs_modulus", REF(hair.youngs_modulus), "dyn/cm²", above(0, 1e15), "rod",
                        "Young's modulus E of a fibre (paper: 3.89e10)."));
  keys.push_back(number("hair.shear_modulus", REF(hair.shear_modulus), "dyn/cm²", above(0, 1e15), "rod",
                        "Shear modulus G of a fibre (paper: 0.89e10)."));
  keys.push_back(number("hair.cross_section", REF(hair.cross_section), "cm²", above(0, 1), "rod",
                        "Cross-section area A of a circular fibre (paper: 1.5e-5); I = A²/4π, J = 2I."));
  keys.push_back(number("hair.mass_density", REF(hair.mass_density), "g/cm³", above(0, 100), "gravity",
                        "Mass density ρ of a fibre; weight per length is ρ·A·g."));

  keys.push_back(number("fields.voxel", REF(fields.voxel), "cm", above(0, 100), "fields",
                        "Edge length of a distance-field voxel."));
  keys.push_back(number("fields.band", REF(fields.band), "voxels", closed(1, 64), "fields",
                        "Half-width of the band where distances are exact; beyond it the field is an estimate."));
  keys.push_back(number("fields.margin", REF(fields.margin), "cm", closed(0, 1000), "fields",
                        "Grid extent beyond the mesh's bounding box."));
  keys.push_back(number("fields.max_memory", REF(fields.max_memory), "GiB", above(0, 1024), "fields",
                        "Refuse field grids larger than this, naming a voxel size that fits."));
  keys.push_back(text("fields.skin_beyond_hairline", REF(fields.skin_beyond_hairline), {"floor", "shell", "auto"}, "fields",
                      "Where the head's skin lies past the scalp's hairline, where the hull may go on (the sides and "
                      "nape of short hair, a bob's curtain): floor, nowhere (the head is the scalp closed by a floor "
                      "across its hairline, so the hull's region there, ears and neck included, is all hair layer); "
                      "shell, the hairline's layer thickness under the hull (a hair shell follows the skin at about "
                      "its offset at the hairline), so that hair hangs in the layer there instead of sinking into "
                      "the neck; auto, shell for an open hull (a raw shell) and floor for a closed one (which "
                      "encloses what it overhangs past the hairline, as prepare's volumes do)."));

  keys.push_back(integer("roots.guides", REF(roots.guides), "", closed(1, 1000000), "roots, guides",
                         "Number of clusters, each with one principal guide (paper: 3000)."));
  keys.push_back(number("roots.preguide_spacing", REF(roots.preguide_spacing), "cm", above(0, 100), "roots, preguides",
                        "Spacing of the sparse pre-guide roots (paper: about 1 per cm)."));
  keys.push_back(number("roots.cluster_overlap", REF(roots.cluster_overlap), "", closed(1, 4), "roots",
                        "Cluster circle radius relative to the covering radius; pores in overlaps are shared at random."));

  keys.push_back(text("rod.integrator", REF(rod.integrator), {"rk2", "rk4"}, "rod",
                      "Lie-group Runge–Kutta scheme for the Kirchhoff equations: 2nd or 4th order."));
  keys.push_back(integer("rod.segments", REF(rod.segments), "", closed(2, 4096), "rod",
                         "Integration steps per rod (and nodes − 1 of every guide)."));
  keys.push_back(number("rod.gravity", REF(rod.gravity), "cm/s²", closed(0, 1e5), "gravity",
                        "Gravitational acceleration g, when effects.gravity."));

  keys.push_back(number("contact.stiffness", REF(contact.stiffness), "dyn/cm²", above(0, 1e9), "contact",
                        "Force per length per cm into the contact layer, k: the support is k·g(φ) along the scalp's "
                        "normal, g = (δ − φ)²/(2δ) within the layer δ above the scalp and δ/2 − φ below it (C¹). "
                        "The default carries a hair's weight (0.019 dyn/cm for the default material) 2.5 mm above "
                        "the scalp and forty times that at the scalp itself."));
  keys.push_back(number("contact.layer", REF(contact.layer), "cm", above(0, 100), "contact",
                        "δ: how far above the scalp the support begins."));

  keys.push_back(pair("preguides.depth_range", REF(preguides.depth_range), "", closed(0, 1), "preguides",
                      "Target immersion depth of a pre-guide's tip as a share of the local thickness, from the top of the head to its lowest roots."));
  keys.push_back(number("preguides.max_load", REF(preguides.max_load), "", above(0, 1e6), "preguides",
                        "Largest dimensionless terminal force F·L²/EI the continuation tries. Beyond ≈40 the tip is already within a few degrees of the pull and more load only tightens the bend at the root, while the guides that start from these loads become exponentially sensitive (like exp(√load)) and cost several times more to optimise."));

  keys.push_back(text("preguides.immersion", REF(preguides.immersion), {"tip", "layer"}, "preguides",
                      "How a pre-guide is bent into the hair: tip, a terminal force normal to its initial axis grown until "
                      "the tip reaches its depth (the paper); layer, a terminal force and a root couple in that plane "
                      "fitted so that the whole rod runs at its depth in the layer (thin shells; weightless rods)."));
  keys.push_back(text("guides.start", REF(guides.start), {"warm", "straight"}, "guides",
                      "Start each optimisation from the neighbouring pre-guides' loads (warm) or from a straight rod (straight, the paper)."));
  keys.push_back(integer("guides.samples", REF(guides.samples), "", closed(2, 1024), "guides",
                         "Sample points per guide at which the objective's residuals are evaluated."));
  keys.push_back(integer("guides.neighbours", REF(guides.neighbours), "", closed(1, 16), "guides",
                         "Pre-guides each principal guide follows, weighted by distance on the scalp (paper: 3)."));
  keys.push_back(integer("guides.max_iterations", REF(guides.max_iterations), "", closed(1, 10000), "guides",
                         "Levenberg–Marquardt iteration cap per guide; a guide stopped by it is flagged."));
  keys.push_back(number("guides.tolerance", REF(guides.tolerance), "", above(0, 1), "guides",
                        "Relative decrease of the cost below which a guide counts as converged."));
  keys.push_back(text("guides.boundary", REF(guides.boundary), {"smooth", "paper", "layer"}, "guides",
                      "Boundary penalty F3: the C¹ form (smooth), the paper's eq. 9 exactly (paper), or the C¹ form "
                      "with its ramp narrowed to a quarter of the local layer thickness (layer: thin shells)."));
  keys.push_back(number("guides.outside_penalty", REF(guides.outside_penalty), "cm", closed(0, 1e6), "guides",
                        "c_d of eq. 9: extra cost of a sample outside the acceptable region."));
  keys.push_back(number("guides.boundary_width", REF(guides.boundary_width), "cm", above(0, 100), "guides",
                        "Depth inside each surface over which the smooth boundary penalty ramps c_d up."));
  keys.push_back(integer("guides.point_forces", REF(guides.point_forces), "", closed(0, 3), "guides",
                         "Interior point forces per guide, evenly spaced along it, optimised with the terminal "
                         "load: the layer holding the hair along its length (thin shells). 0: the paper's six "
                         "terminal-load parameters alone. Weightless hair only."));
  keys.push_back(number("guides.point_force_weight", REF(guides.point_force_weight), "", closed(0, 1), "guides",
                        "w5: weight of Σ|F_k|² over the point forces (dimensionless, F·L²/EI), so that the layer "
                        "pushes no harder than the shape needs."));
  keys.push_back(number("guides.weights.direction", REF(guides.weights.direction), "", closed(0, 1), "guides",
                        "w1: follow the pre-guides' directions (F1, eq. 7). The four weights sum to 1 (eq. 6)."));
  keys.push_back(number("guides.weights.similarity", REF(guides.weights.similarity), "", closed(0, 1), "guides",
                        "w2: match the pre-guides' curvature and twist (F2², eq. 8 squared)."));
  keys.push_back(number("guides.weights.boundary", REF(guides.weights.boundary), "", closed(0, 1), "guides",
                        "w3: stay between the scalp and the volume boundary (F3, eq. 9)."));
  keys.push_back(number("guides.weights.density", REF(guides.weights.density), "", closed(0, 1), "guides, density",
                        "w4: avoid crowding (F4, eq. 10/11); non-zero only with a density model."));

  keys.push_back(number("density.voxel", REF(density.voxel), "cm", above(0, 100), "density",
                        "Edge length of a density-grid voxel."));
  keys.push_back(integer("density.batch", REF(density.batch), "", closed(1, 100000), "density",
                         "Guides optimised in parallel against the density of all earlier batches."));
  keys.push_back(number("density.threshold", REF(density.threshold), "", closed(0, 1), "density",
                        "BOM: occupancy above which a guide's sample pays the surcharge."));
  keys.push_back(number("density.surcharge", REF(density.surcharge), "", closed(0, 1e6), "density",
                        "c_BOM of eq. 10."));
  keys.push_back(number("density.strength", REF(density.strength), "", closed(0, 1e6), "density",
                        "c_ρ of eq. 11."));
  keys.push_back(integer("density.stall_iterations", REF(density.stall_iterations), "", closed(0, 100000), "density",
                         "A guide's second solve, with F4, stops once this many iterations in a row (accepted or "
                         "not) lowered its cost by less than density.stall_tolerance of it; 0: never."));
  keys.push_back(number("density.stall_tolerance", REF(density.stall_tolerance), "", closed(0, 1), "density",
                        "Share of the cost that density.stall_iterations iterations must lower it by to go on."));
  keys.push_back(text("density.deposit", REF(density.deposit), {"tubes", "fibres"}, "density",
                      "CDM: what a solved guide's wisp adds to the density the later guides' F4 reads: tubes, 16 lines "
                      "spread evenly over the wisp's cross-section (the paper's cylindrical region around the guide), "
                      "each carrying an equal share of its pores' fibre length; or fibres, the fibres the strands "
                      "stage grows from its pores, grown in the guides stage and handed on."));
  keys.push_back(integer("density.spread", REF(density.spread), "", closed(0, 100), "density",
                         "The models' fibre part: passes that move the grown fibres down their own density gradient "
                         "(density.voxel apart; the density per unit of the hair's region, so a thin layer's faces "
                         "do not push fibres out) before the keep-out pass and the cut; 0: the guides alone."));

  keys.push_back(integer("strands.points", REF(strands.points), "", closed(2, 65536), "strands",
                         "Points per fibre, root to tip."));
  keys.push_back(number("strands.root_radius", REF(strands.root_radius), "cm", closed(0, 100), "strands",
                        "Radius of a wisp's generalised cylinder at the root."));
  keys.push_back(number("strands.tip_radius", REF(strands.tip_radius), "cm", closed(0, 100), "strands",
                        "Radius of a wisp's generalised cylinder at the tip."));
  keys.push_back(number("strands.turns", REF(strands.turns), "", closed(-1000, 1000), "winding",
                        "Turns of every fibre about its guide, root to tip, when effects.winding."));
  keys.push_back(number("strands.cut_threshold", REF(strands.cut_threshold), "cm", closed(0, 1000), "cutting",
                        "Length a fibre may run outside the volume before it is cut there, when effects.cutting."));
  keys.push_back(boolean("strands.cut_tips", REF(strands.cut_tips), "cutting",
                         "A fibre whose tip lies outside the volume is cut where it last left it, however short that "
                         "last stretch, when effects.cutting (it never re-enters; strands.cut_threshold still spares "
                         "excursions that do)."));
  keys.push_back(number("strands.contain", REF(strands.contain), "cm", closed(0, 100), "strands",
                        "Fibre points outside the volume by less than this move back in, 0.5 mm inside it (the fibre "
                        "keeps its length; the head still comes first); 0 leaves them."));
  keys.push_back(text("strands.depth", REF(strands.depth), {"wisp", "layer", "auto"}, "strands",
                      "Where a fibre lies across the hair layer: wisp, at its place in the wisp around its guide (the "
                      "paper); layer, the wisp's fibres spread evenly through the layer's depth between the scalp and the "
                      "hull (a tenth of it kept clear at either side), or through its top 2·strands.tip_radius where it is "
                      "deeper (a bun), the fibre rooted furthest upstream on top; auto, "
                      "layer where the layer over the scalp (the 90th percentile of its thickness) is deeper than a wisp "
                      "is wide at its tip (2·strands.tip_radius), else wisp."));

  {
    SceneKey k = make("output.dir", KeyKind::folder, "", any(), "outputs",
                      "Folder for every output, relative to the scene; `hairfit run --out` overrides it.");
    k.store = [](Scene& s, const std::vector<double>&, const std::vector<std::string>& t) { s.output.dir = t[0]; };
    k.show = [](const Scene&) { return std::string("\"out\""); };
    keys.push_back(k);
  }
  keys.push_back(text_list("output.strands", REF(output.strands), {"hair", "obj", "usda", "ply"}, "outputs",
                           "Strand file formats to write: cyHair .hair, OBJ lines, USD BasisCurves, PLY edges."));
  keys.push_back(text_list("output.renders", REF(output.renders), {"front", "side", "back", "top", "three-quarter"},
                           "render", "Views of the final strands rendered to PNG after a full run."));
  keys.push_back(pair("output.render_size", REF(output.render_size), "pixels", closed(16, 8192), "render",
                      "Width and height of rendered pictures."));
  keys.push_back(optional_path("output.occluder", OPT_REF(output.occluder), "render",
                               "OBJ mesh in units.length (the scan, or the head) drawn opaque in every 3D picture, so hair "
                               "behind it is hidden; without it, the scalp closed by a floor across its hairline."));
  return keys;
}

}  // namespace

bool SceneKey::in_range(double x) const {
  if (!std::isfinite(x)) return false;
  if (lo_open ? !(x > lo) : !(x >= lo)) return false;
  if (hi_open ? !(x < hi) : !(x <= hi)) return false;
  return true;
}

std::string SceneKey::range_text() const {
  if (lo == -kInf && hi == kInf) return "";
  return std::string(lo_open ? "(" : "[") + number_text(lo) + ", " + (hi == kInf ? "∞" : number_text(hi)) +
         (hi_open || hi == kInf ? ")" : "]");
}

const std::vector<ScenePreset>& scene_presets() {
  static const std::vector<ScenePreset> presets{
      // Values from bench_accuracy (docs/results/accuracy.md): the field voxels stay at their
      // default in both, since a coarser field doubles the guide error for tenths of a second.
      {"preview", "a quick look while iterating on a scene",
       {{"rod.segments", 32}, {"guides.samples", 8}, {"guides.tolerance", 1e-3}, {"guides.max_iterations", 30}}},
      {"default", "the documented defaults", {}},
      {"final", "the hair to keep",
       {{"guides.samples", 64}, {"guides.tolerance", 1e-8}, {"guides.max_iterations", 200}}},
  };
  return presets;
}

std::string scene_presets_markdown() {
  std::ostringstream out;
  out << "| preset | for | values |\n| --- | --- | --- |\n";
  for (const ScenePreset& p : scene_presets()) {
    std::string values;
    for (const auto& [key, value] : p.values) values += (values.empty() ? "" : ", ") + ("`" + key + " = " + number_text(value) + "`");
    out << "| `" << p.name << "` | " << p.doc << " | " << (values.empty() ? "the defaults above" : values) << " |\n";
  }
  return out.str();
}

const std::vector<SceneKey>& scene_keys() {
  static const std::vector<SceneKey> keys = build_keys();
  return keys;
}

const SceneKey* find_scene_key(const std::string& name) {
  for (const SceneKey& k : scene_keys())
    if (k.name == name) return &k;
  return nullptr;
}

std::string scene_keys_markdown() {
  static const char* kind_names[] = {"integer", "number", "boolean", "string", "path", "folder",
                                     "[x, y, z]", "[lo, hi]", "list of strings", "[x, y]"};
  std::ostringstream out;
  out << "| key | type | unit | default | allowed | feeds | meaning |\n";
  out << "| --- | --- | --- | --- | --- | --- | --- |\n";
  const Scene defaults;
  for (const SceneKey& k : scene_keys()) {
    std::string allowed = k.range_text();
    if (!k.choices.empty()) {
      allowed.clear();
      for (const std::string& c : k.choices) allowed += (allowed.empty() ? "" : ", ") + ("`" + c + "`");
    }
    if (k.kind == KeyKind::vector3) allowed = "non-zero";
    if (k.kind == KeyKind::point2) allowed = "in the unit disk";
    out << "| `" << k.name << "` | " << kind_names[static_cast<int>(k.kind)] << " | " << k.unit << " | `"
        << k.show(defaults) << "` | " << allowed << " | " << k.feeds << " | " << k.doc << " |\n";
  }
  return out.str();
}

}  // namespace hairfit
