// A procedural bust to test `hairfit prepare` against known answers: a head (ellipsoid) on a neck,
// covered on a tilted cap by a hair layer that tapers to nothing at the hairline, with a bun and
// two plaited braids as bumps on the hair. Star-shaped about the origin (the head centre), so
// every quantity is a function of the direction u: the skull radius, the hair layer, the bumps.
// Units: cm. Up is +y, the face looks to +z (x is the person's left).
#pragma once
#include "core/mesh.h"

namespace hairfit {

struct BustShape {
  Vec3 head_axes{7.6, 9.0, 9.6};   // skull ellipsoid half-axes (x, y, z), cm
  double neck_radius = 5.5;        // cm, a vertical cylinder about the y axis
  double neck_bottom = -22.0;      // cm, where the bust is cut off (y)
  double hairline_angle = 78.0;    // degrees: the hair covers directions within this of cap_axis
  double cap_tilt = 25.0;          // degrees the cap axis leans back from +y
  double hair_thickness = 2.0;     // cm of hair over the skull on the crown
  double taper_angle = 20.0;       // degrees over which the layer grows from 0 at the hairline
  double bun_height = 4.5;         // cm
  double braid_height = 1.2;       // cm

  Vec3 cap_axis() const;
  // Angle (radians) between direction u and the cap axis.
  double cap_angle(const Vec3& u) const;
  bool in_hair(const Vec3& u) const { return cap_angle(u) <= hairline_angle * 3.14159265358979323846 / 180.0; }
  // Radius of the bare head and neck (the skull under the hair) along unit direction u.
  double skin_radius(const Vec3& u) const;
  // Hair on top of the skin: the tapered layer plus the bun and braids (0 outside the hair).
  double hair_layer(const Vec3& u) const;
  double bumps(const Vec3& u) const;  // bun and braids only
  // The scan's radius: skin + hair.
  double radius(const Vec3& u) const { return skin_radius(u) + hair_layer(u); }
};

struct BustScan {
  Mesh mesh;                  // the scan surface, closed, counter-clockwise seen from outside
  std::vector<Vec3> colors;   // per vertex: hair brown inside the cap, skin elsewhere
  std::vector<Vec3> directions;  // per vertex: its unit direction from the origin
};

constexpr double kHairColor[3] = {0.30, 0.18, 0.10};
constexpr double kSkinColor[3] = {0.92, 0.76, 0.66};

// The bust on an icosphere subdivided `levels` times (20·4^levels triangles).
BustScan make_bust(const BustShape& shape, int levels = 5);

}  // namespace hairfit
