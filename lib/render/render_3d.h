// The deterministic software renderer for 3D stages: shaded meshes with a z-buffer, the hair volume
// as a tinted, outlined silhouette, curves (pre-guides, guides, strands) as depth-tested
// anti-aliased lines with Kajiya–Kay hair shading, and points (roots, guide bases) as discs.
// A Drawing3D holds non-owning pointers to the caller's data, valid for the render_3d call only.
// Output depends only on the drawing, the camera and the options, never on the thread count.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/curves.h"
#include "core/mesh.h"
#include "io/png_image.h"
#include "render/camera.h"
#include "render/color.h"

namespace hairfit {

enum class MeshStyle {
  shaded,      // opaque, smooth two-sided Lambert shading, z-buffered (the scalp)
  silhouette,  // depth-independent coverage: tinted over the picture and outlined (the hair volume)
};

struct MeshLayer {
  const Mesh* mesh = nullptr;
  MeshStyle style = MeshStyle::shaded;
  Color color{0.82f, 0.69f, 0.60f};  // surface colour (shaded) or tint (silhouette)
  float opacity = 0.16f;             // silhouette only: tint weight in [0, 1]
  Color outline{0.55f, 0.75f, 0.95f};  // silhouette only: outline colour
  double outline_width = 1.5;        // silhouette only: output pixels (0 = no outline)
};

struct CurveLayer {
  const Curves* curves = nullptr;     // world positions; curves with < 2 points are skipped
  std::vector<int> color_ids;         // one palette id per curve (guide or cluster), or empty
  Color color{0.50f, 0.33f, 0.19f};   // base colour when color_ids is empty (a mid brown)
  double width = 1.0;                 // output pixels
  float opacity = 1.0f;
  bool hair_shading = true;    // Kajiya–Kay diffuse sin(T, L) + two specular lobes; false: flat colour
  float root_darkening = 0.4f;  // brightness lost at the root, fading quadratically to 0 at the tip
  float depth_cue = 0.35f;      // brightness lost by the farthest curve point relative to the nearest
  float variation = 0.3f;       // per-curve brightness spread (a hash of the curve index, not random)
};

struct PointLayer {
  const std::vector<Vec3>* points = nullptr;
  std::vector<int> color_ids;  // one palette id per point, or empty
  Color color{0.95f, 0.95f, 0.95f};
  double radius = 2.0;  // output pixels
  bool outlined = true;  // a dark ring keeps points visible on any background
};

struct Drawing3D {
  std::vector<MeshLayer> meshes;
  std::vector<CurveLayer> curves;
  std::vector<PointLayer> points;
  std::string title;  // drawn in the top-left corner when not empty
};

struct RenderOptions {
  int supersample = 2;  // samples per output pixel along each axis (1–4); box-filtered down
  int threads = 1;      // rows are split into bands; the result does not depend on this
  Color background_top{0.17f, 0.18f, 0.21f};  // a vertical gradient behind everything
  Color background_bottom{0.05f, 0.05f, 0.07f};
};

// Renders in this order: shaded meshes (z-buffer), silhouette tints, curves and points (depth-tested
// against meshes and each other), silhouette outlines, title. Light: a key light from the camera's
// upper left, fixed relative to the camera so every view is lit alike. Throws std::invalid_argument
// for a null layer pointer, a triangle index out of range or a colour-id list of the wrong length.
Image render_3d(const Drawing3D& drawing, const Camera& camera, const RenderOptions& options = {});

// Axis-aligned bounds {lo, hi} of every finite position the drawing references (world units), to
// fit a camera with fit_camera; throws std::invalid_argument when there is none.
std::pair<Vec3, Vec3> drawing_bounds(const Drawing3D& drawing);

}  // namespace hairfit
