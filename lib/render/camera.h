// Orthographic cameras for the five named views, placed relative to the scene's `down` and `front`
// directions (world unit vectors), and fitted to a bounding box. No perspective: sizes in a picture
// are comparable everywhere, which is what judging a hairstyle's silhouette needs.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/types.h"

namespace hairfit {

// The views, seen from the person whose head the scene holds:
//   front          camera on the face side (+front), looking back at the face; the person's left
//                  appears on the image's right, as in a photograph;
//   side           camera on the person's right, so the face points to the image's right;
//   back           camera behind the head (−front), the person's left on the image's left;
//   top            camera above (−down) looking down, the face toward the image's top;
//   three-quarter  halfway between front and side (45° about the vertical), 20° above.
// In every view but top, image up is −down.
enum class ViewName { front, side, back, top, three_quarter };

// All view names in order, as written on the command line ("front", "side", "back", "top",
// "three-quarter").
const std::vector<std::string>& view_names();
std::string view_name(ViewName view);
// Throws InputError ("unknown view "x"; valid views: front, side, back, top, three-quarter") for
// any other name.
ViewName parse_view(const std::string& name);
// Parses "WxH" (e.g. "1200x900", both 16–16384 pixels); throws InputError with the expected form.
std::pair<int, int> parse_size(const std::string& text);

struct Camera {
  int width = 0;   // pixels
  int height = 0;  // pixels
  Vec3 right{1, 0, 0};    // world direction of the image's +x
  Vec3 up{0, 1, 0};       // world direction of the image's −y (image up)
  Vec3 forward{0, 0, -1}; // viewing direction, from the camera into the scene; right = forward × up
  Vec3 centre{0, 0, 0};   // world point drawn at the image centre
  double pixels_per_unit = 1.0;  // image pixels per world length unit (cm)

  // Image coordinates (x right, y down, pixel (i, j) centred at (i+½, j+½)) and depth along
  // `forward` relative to `centre` (world units; larger is farther from the camera).
  Vec3 project(const Vec3& world) const;
  // Direction toward the camera (−forward).
  Vec3 to_viewer() const { return -forward; }
};

// Camera orientation of a view: {right, up, forward}. `down` and `front` must be non-parallel;
// they are orthonormalised (front loses its component along down). Throws InputError otherwise.
Camera orient_camera(ViewName view, const Vec3& down, const Vec3& front);

// Fits an oriented camera to the box [lo, hi] (world units): the projections of its 8 corners fill
// the image less a margin of `margin` × the smaller image side on every edge; aspect kept.
Camera fit_camera(ViewName view, const Vec3& down, const Vec3& front, const Vec3& lo, const Vec3& hi, int width,
                  int height, double margin = 0.06);

}  // namespace hairfit
