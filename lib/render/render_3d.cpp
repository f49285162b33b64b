#include "render/render_3d.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/parallel.h"
#include "render/canvas.h"
#include "render/line_raster.h"

namespace hairfit {

namespace {

constexpr int kBandRows = 16;  // output rows per parallel work item
constexpr float kFar = std::numeric_limits<float>::infinity();

struct Buffers {
  int width = 0, height = 0;
  std::vector<float> rgb;    // supersampled colour
  std::vector<float> depth;  // supersampled depth along camera.forward (world units)
  std::size_t at(int x, int y) const { return static_cast<std::size_t>(y) * width + x; }
  void blend(std::size_t i, const Color& c, float alpha) {
    float* p = &rgb[i * 3];
    p[0] += (c.r - p[0]) * alpha;
    p[1] += (c.g - p[1]) * alpha;
    p[2] += (c.b - p[2]) * alpha;
  }
};

struct Lighting {
  Vec3 light;   // unit direction toward the key light
  Vec3 viewer;  // unit direction toward the camera
  Vec3 half;    // normalised light + viewer
};

Lighting make_lighting(const Camera& camera) {
  Lighting l;
  l.viewer = camera.to_viewer();
  l.light = (-0.45 * camera.right + 0.55 * camera.up + 0.70 * l.viewer).normalized();
  l.half = (l.light + l.viewer).normalized();
  return l;
}

// Two-sided Lambert with ambient and a soft Blinn highlight: the normal is turned toward the
// viewer so the inside of an open scalp is lit like its outside.
Color shade_surface(const Color& base, Vec3 n, const Lighting& l) {
  if (n.dot(l.viewer) < 0) n = -n;
  const double diffuse = std::max(0.0, n.dot(l.light));
  const double fill = 0.5 + 0.5 * n.dot(l.viewer);  // soft camera-side fill keeps shadows readable
  const double spec = 0.12 * std::pow(std::max(0.0, n.dot(l.half)), 24.0);
  const float k = static_cast<float>(0.18 + 0.62 * diffuse + 0.20 * fill);
  return {base.r * k + static_cast<float>(spec), base.g * k + static_cast<float>(spec), base.b * k + static_cast<float>(spec)};
}

// Kajiya–Kay hair shading from the unit tangent T: diffuse sin(T, L), a sharp white primary
// highlight and a broad secondary one tinted by the hair colour, both in sin(T, H).
Color shade_hair(const Color& base, const Vec3& t, const Lighting& l) {
  const double tl = t.dot(l.light), th = t.dot(l.half);
  const double sin_tl = std::sqrt(std::max(0.0, 1.0 - tl * tl));
  const double sin_th = std::sqrt(std::max(0.0, 1.0 - th * th));
  const float diffuse = static_cast<float>(0.25 + 0.75 * sin_tl);
  const float primary = static_cast<float>(0.30 * std::pow(sin_th, 80.0));
  const float secondary = static_cast<float>(0.25 * std::pow(sin_th, 10.0));
  return {base.r * (diffuse + secondary) + primary, base.g * (diffuse + secondary) + primary,
          base.b * (diffuse + secondary) + primary};
}

std::vector<Vec3> vertex_normals(const Mesh& mesh) {
  std::vector<Vec3> normals(mesh.positions.size(), Vec3::Zero());
  for (const Vec3i& t : mesh.triangles) {
    // The unnormalised cross product weights each face by its area.
    const Vec3 n = (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
    for (int k = 0; k < 3; ++k) normals[t[k]] += n;
  }
  for (Vec3& n : normals) {
    const double length = n.norm();
    n = length > 0 ? Vec3(n / length) : Vec3(0, 0, 0);
  }
  return normals;
}

void check_mesh(const MeshLayer& layer) {
  if (!layer.mesh) throw std::invalid_argument("render_3d: mesh layer without a mesh");
  const int n = static_cast<int>(layer.mesh->positions.size());
  for (const Vec3i& t : layer.mesh->triangles)
    if (t.minCoeff() < 0 || t.maxCoeff() >= n) throw std::invalid_argument("render_3d: triangle index out of range");
}

// A triangle in supersampled screen space, with what its fragments need.
struct ScreenTriangle {
  Vec3 p[3];  // x, y, depth
  Vec3 n[3];  // vertex normals (world)
  int layer;
};

// A fixed integer hash (lowbias32) mapped to [0, 1): stable per-curve variation, no RNG state.
float hash_unit(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return static_cast<float>(x >> 8) / 16777216.0f;
}

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// Visits the pixel centres inside a triangle within rows [row0, row1), with barycentric weights.
// Pixels on a shared edge may be visited by both triangles; the z-test makes that harmless.
template <class Fragment>
void rasterise(const Vec3 (&p)[3], int width, int row0, int row1, const Fragment& fragment) {
  const double area = (p[1].x() - p[0].x()) * (p[2].y() - p[0].y()) - (p[1].y() - p[0].y()) * (p[2].x() - p[0].x());
  if (!(std::abs(area) > 1e-12)) return;
  const double x_lo = std::min({p[0].x(), p[1].x(), p[2].x()}), x_hi = std::max({p[0].x(), p[1].x(), p[2].x()});
  const double y_lo = std::min({p[0].y(), p[1].y(), p[2].y()}), y_hi = std::max({p[0].y(), p[1].y(), p[2].y()});
  const int x0 = std::max(0, static_cast<int>(std::ceil(x_lo - 0.5))), x1 = std::min(width - 1, static_cast<int>(std::floor(x_hi - 0.5)));
  const int y0 = std::max(row0, static_cast<int>(std::ceil(y_lo - 0.5))), y1 = std::min(row1 - 1, static_cast<int>(std::floor(y_hi - 0.5)));
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5;
      double w[3];
      for (int k = 0; k < 3; ++k) {
        const Vec3& a = p[(k + 1) % 3];
        const Vec3& b = p[(k + 2) % 3];
        w[k] = ((b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x())) / area;
      }
      if (w[0] < 0 || w[1] < 0 || w[2] < 0) continue;
      fragment(x, y, w);
    }
  }
}

// Curve vertices in screen space with their shaded colours, flattened over all layers.
struct CurveVertices {
  std::vector<Vec3> screen;  // x, y (supersampled pixels), depth
  std::vector<Color> color;
};

struct Segment {
  int vertex;  // index of the first end in CurveVertices; the second is vertex + 1
  int layer;
};

void bin(std::vector<std::vector<int>>& bands, int item, double y_lo, double y_hi, int height) {
  const int b0 = std::max(0, static_cast<int>(std::floor(y_lo)) / kBandRows);
  const int b1 = std::min(static_cast<int>(bands.size()) - 1, std::max(0, static_cast<int>(std::ceil(y_hi))) / kBandRows);
  if (y_hi < 0 || y_lo >= height) return;
  for (int b = b0; b <= b1; ++b) bands[b].push_back(item);
}

}  // namespace

std::pair<Vec3, Vec3> drawing_bounds(const Drawing3D& drawing) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  auto add = [&](const Vec3& p) {
    if (!finite(p)) return;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (const MeshLayer& m : drawing.meshes)
    if (m.mesh)
      for (const Vec3i& t : m.mesh->triangles)
        for (int k = 0; k < 3; ++k)
          if (t[k] >= 0 && t[k] < static_cast<int>(m.mesh->positions.size())) add(m.mesh->positions[t[k]]);
  for (const CurveLayer& c : drawing.curves)
    if (c.curves)
      for (const Vec3& p : c.curves->points) add(p);
  for (const PointLayer& p : drawing.points)
    if (p.points)
      for (const Vec3& q : *p.points) add(q);
  if (!(lo.x() <= hi.x())) throw std::invalid_argument("drawing_bounds: the drawing has no finite position");
  return {lo, hi};
}

Image render_3d(const Drawing3D& drawing, const Camera& camera, const RenderOptions& options) {
  if (camera.width <= 0 || camera.height <= 0) throw std::invalid_argument("render_3d: camera has no size");
  for (const MeshLayer& m : drawing.meshes) check_mesh(m);
  for (const CurveLayer& c : drawing.curves) {
    if (!c.curves) throw std::invalid_argument("render_3d: curve layer without curves");
    if (!c.color_ids.empty() && c.color_ids.size() != c.curves->count())
      throw std::invalid_argument("render_3d: curve layer has " + std::to_string(c.color_ids.size()) +
                                  " colour ids for " + std::to_string(c.curves->count()) + " curves");
  }
  for (const PointLayer& p : drawing.points) {
    if (!p.points) throw std::invalid_argument("render_3d: point layer without points");
    if (!p.color_ids.empty() && p.color_ids.size() != p.points->size())
      throw std::invalid_argument("render_3d: point layer colour ids do not match its points");
  }
  const int ss = std::clamp(options.supersample, 1, 4);
  const int threads = std::max(1, options.threads);
  const Lighting lighting = make_lighting(camera);
  // Fragments within half an output pixel of depth of a surface still pass, so roots on the scalp
  // are not clipped by it.
  const float depth_bias = static_cast<float>(0.5 / camera.pixels_per_unit);

  // Surfaces are rendered supersampled (ss × ss samples per pixel) for smooth edges; curves and
  // points carry their own analytic anti-aliasing and are drawn at the output resolution, against
  // the surfaces' resolved depth, which keeps 100k+ strands fast.
  Camera sc = camera;
  sc.width = camera.width * ss;
  sc.height = camera.height * ss;
  sc.pixels_per_unit = camera.pixels_per_unit * ss;
  Buffers fine;  // supersampled surfaces
  fine.width = sc.width;
  fine.height = sc.height;
  fine.rgb.resize(static_cast<std::size_t>(fine.width) * fine.height * 3);
  fine.depth.assign(static_cast<std::size_t>(fine.width) * fine.height, kFar);
  Buffers out;  // output resolution
  out.width = camera.width;
  out.height = camera.height;
  out.rgb.resize(static_cast<std::size_t>(out.width) * out.height * 3);
  out.depth.assign(static_cast<std::size_t>(out.width) * out.height, kFar);
  const int out_bands = (out.height + kBandRows - 1) / kBandRows;
  const int fine_band_rows = kBandRows * ss;  // a fine band is exactly the samples of an output band

  // --- Triangles: shaded ones and silhouette coverage, binned by band. ---
  std::vector<ScreenTriangle> triangles;
  std::vector<int> silhouette_of_layer(drawing.meshes.size(), -1);
  int silhouettes = 0;
  for (std::size_t li = 0; li < drawing.meshes.size(); ++li) {
    const MeshLayer& layer = drawing.meshes[li];
    if (layer.style == MeshStyle::silhouette) silhouette_of_layer[li] = silhouettes++;
    const Mesh& mesh = *layer.mesh;
    const std::vector<Vec3> normals = layer.style == MeshStyle::shaded ? vertex_normals(mesh) : std::vector<Vec3>();
    for (const Vec3i& t : mesh.triangles) {
      ScreenTriangle st;
      st.layer = static_cast<int>(li);
      bool ok = true;
      for (int k = 0; k < 3; ++k) {
        st.p[k] = sc.project(mesh.positions[t[k]]);
        st.n[k] = normals.empty() ? Vec3::Zero() : normals[t[k]];
        ok = ok && finite(st.p[k]);
      }
      if (ok) triangles.push_back(st);
    }
  }
  std::vector<std::vector<int>> triangle_bands(out_bands);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const ScreenTriangle& t = triangles[i];
    bin(triangle_bands, static_cast<int>(i), (std::min({t.p[0].y(), t.p[1].y(), t.p[2].y()}) - 1) / ss,
        (std::max({t.p[0].y(), t.p[1].y(), t.p[2].y()}) + 1) / ss, out.height);
  }
  // Silhouette coverage (0/1 per sample) and its horizontal erosion by the outline radius.
  std::vector<std::vector<std::uint8_t>> coverage(silhouettes), eroded_h(silhouettes);
  for (int s = 0; s < silhouettes; ++s) {
    coverage[s].assign(static_cast<std::size_t>(fine.width) * fine.height, 0);
    eroded_h[s].assign(coverage[s].size(), 0);
  }
  auto outline_radius = [&](const MeshLayer& layer) {
    return std::max(1, static_cast<int>(std::lround(0.5 * layer.outline_width * ss)));
  };

  parallel_for(out_bands, threads, [&](int band) {
    const int row0 = band * fine_band_rows, row1 = std::min(fine.height, row0 + fine_band_rows);
    for (int y = row0; y < row1; ++y) {
      const Color c = mix(options.background_top, options.background_bottom, (y + 0.5f) / fine.height);
      for (int x = 0; x < fine.width; ++x) {
        float* p = &fine.rgb[fine.at(x, y) * 3];
        p[0] = c.r, p[1] = c.g, p[2] = c.b;
      }
    }
    for (int index : triangle_bands[band]) {
      const ScreenTriangle& t = triangles[index];
      const MeshLayer& layer = drawing.meshes[t.layer];
      if (layer.style == MeshStyle::silhouette) {
        std::vector<std::uint8_t>& mask = coverage[silhouette_of_layer[t.layer]];
        rasterise(t.p, fine.width, row0, row1, [&](int x, int y, const double*) { mask[fine.at(x, y)] = 1; });
        continue;
      }
      rasterise(t.p, fine.width, row0, row1, [&](int x, int y, const double* w) {
        const std::size_t i = fine.at(x, y);
        const float z = static_cast<float>(w[0] * t.p[0].z() + w[1] * t.p[1].z() + w[2] * t.p[2].z());
        if (!(z < fine.depth[i])) return;
        fine.depth[i] = z;
        Vec3 n = w[0] * t.n[0] + w[1] * t.n[1] + w[2] * t.n[2];
        if (n.norm() > 0) n.normalize();
        const Color c = shade_surface(layer.color, n, lighting);
        float* p = &fine.rgb[i * 3];
        p[0] = c.r, p[1] = c.g, p[2] = c.b;
      });
    }
    for (std::size_t li = 0; li < drawing.meshes.size(); ++li) {
      if (silhouette_of_layer[li] < 0) continue;
      const int s = silhouette_of_layer[li], k = outline_radius(drawing.meshes[li]);
      for (int y = row0; y < row1; ++y)
        for (int x = 0; x < fine.width; ++x) {
          std::uint8_t all = 1;
          for (int dx = -k; dx <= k && all; ++dx)
            all = (x + dx >= 0 && x + dx < fine.width) ? coverage[s][fine.at(x + dx, y)] : 0;
          eroded_h[s][fine.at(x, y)] = all;
        }
    }
  });

  // Resolve the samples to output pixels: mean colour, the depth of the nearest sample when at
  // least half the samples hit a surface (so strands pass in front of a surface's soft edge), and
  // per silhouette the covered and outlined fractions (the outline needs the full erosion, hence
  // a second pass).
  std::vector<std::vector<float>> tint(silhouettes), outline(silhouettes);
  for (int s = 0; s < silhouettes; ++s) {
    tint[s].assign(static_cast<std::size_t>(out.width) * out.height, 0.0f);
    outline[s].assign(tint[s].size(), 0.0f);
  }
  const float weight = 1.0f / (ss * ss);
  parallel_for(out_bands, threads, [&](int band) {
    const int row0 = band * kBandRows, row1 = std::min(out.height, row0 + kBandRows);
    for (int y = row0; y < row1; ++y)
      for (int x = 0; x < out.width; ++x) {
        float sum[3] = {0, 0, 0};
        float nearest = kFar;
        int hits = 0;
        for (int sy = 0; sy < ss; ++sy)
          for (int sx = 0; sx < ss; ++sx) {
            const std::size_t i = fine.at(x * ss + sx, y * ss + sy);
            sum[0] += fine.rgb[i * 3], sum[1] += fine.rgb[i * 3 + 1], sum[2] += fine.rgb[i * 3 + 2];
            if (fine.depth[i] < kFar) ++hits, nearest = std::min(nearest, fine.depth[i]);
          }
        const std::size_t o = out.at(x, y);
        out.rgb[o * 3] = sum[0] * weight, out.rgb[o * 3 + 1] = sum[1] * weight, out.rgb[o * 3 + 2] = sum[2] * weight;
        out.depth[o] = 2 * hits >= ss * ss ? nearest : kFar;
        for (std::size_t li = 0; li < drawing.meshes.size(); ++li) {
          const int s = silhouette_of_layer[li];
          if (s < 0) continue;
          const int k = outline_radius(drawing.meshes[li]);
          int covered = 0, edge = 0;
          for (int sy = 0; sy < ss; ++sy)
            for (int sx = 0; sx < ss; ++sx) {
              const int fx = x * ss + sx, fy = y * ss + sy;
              if (!coverage[s][fine.at(fx, fy)]) continue;
              ++covered;
              std::uint8_t inner = 1;
              for (int dy = -k; dy <= k && inner; ++dy)
                inner = (fy + dy >= 0 && fy + dy < fine.height) ? eroded_h[s][fine.at(fx, fy + dy)] : 0;
              edge += !inner;
            }
          tint[s][o] = covered * weight;
          outline[s][o] = edge * weight;
        }
      }
  });

  // --- Curves: screen positions and shaded colours per vertex (parallel over curves). ---
  std::vector<std::size_t> first_vertex;  // per (layer, curve), flattened
  std::vector<std::pair<int, int>> curve_ref;
  std::size_t vertex_total = 0;
  for (std::size_t li = 0; li < drawing.curves.size(); ++li)
    for (std::size_t c = 0; c < drawing.curves[li].curves->count(); ++c) {
      first_vertex.push_back(vertex_total);
      curve_ref.emplace_back(static_cast<int>(li), static_cast<int>(c));
      vertex_total += drawing.curves[li].curves->size(c);
    }
  // Depth range of all curve points, for depth cueing.
  float z_near = kFar, z_far = -kFar;
  for (const CurveLayer& layer : drawing.curves)
    for (const Vec3& p : layer.curves->points) {
      const float z = static_cast<float>((p - camera.centre).dot(camera.forward));
      if (std::isfinite(z)) z_near = std::min(z_near, z), z_far = std::max(z_far, z);
    }
  const float z_span = z_far > z_near ? z_far - z_near : 1.0f;
  CurveVertices cv;
  cv.screen.resize(vertex_total);
  cv.color.resize(vertex_total);
  parallel_for(static_cast<int>(curve_ref.size()), threads, [&](int item) {
    const CurveLayer& layer = drawing.curves[curve_ref[item].first];
    const int c = curve_ref[item].second;
    const Vec3* curve = layer.curves->points.data() + layer.curves->offsets[c];
    Color base = layer.color_ids.empty() ? layer.color : palette_color(layer.color_ids[c]);
    // Neighbouring fibres differ a little in tone, which is what makes a mass of lines read as hair.
    base = scale(base, 1.0f + layer.variation * (hash_unit(static_cast<std::uint32_t>(c)) - 0.5f));
    const int n = static_cast<int>(layer.curves->size(c));
    for (int k = 0; k < n; ++k) {
      const std::size_t v = first_vertex[item] + k;
      cv.screen[v] = camera.project(curve[k]);
      Vec3 tangent = curve[std::min(k + 1, n - 1)] - curve[std::max(k - 1, 0)];
      tangent = tangent.norm() > 0 ? Vec3(tangent.normalized()) : Vec3(camera.up);
      const Color color = layer.hair_shading ? shade_hair(base, tangent, lighting) : base;
      const float s = n > 1 ? static_cast<float>(k) / (n - 1) : 1.0f;
      float brightness = 1.0f - layer.root_darkening * (1.0f - s) * (1.0f - s);
      const float z = static_cast<float>(cv.screen[v].z());
      if (std::isfinite(z)) brightness *= 1.0f - layer.depth_cue * std::clamp((z - z_near) / z_span, 0.0f, 1.0f);
      cv.color[v] = scale(color, brightness);
    }
  });
  std::vector<Segment> segments;
  std::vector<std::vector<int>> segment_bands(out_bands);
  for (std::size_t item = 0; item < curve_ref.size(); ++item) {
    const CurveLayer& layer = drawing.curves[curve_ref[item].first];
    const double h = layer.width + 1.0;
    const int n = static_cast<int>(layer.curves->size(curve_ref[item].second));
    for (int k = 0; k + 1 < n; ++k) {
      const int v = static_cast<int>(first_vertex[item]) + k;
      const Vec3 &a = cv.screen[v], &b = cv.screen[v + 1];
      if (!finite(a) || !finite(b)) continue;
      bin(segment_bands, static_cast<int>(segments.size()), std::min(a.y(), b.y()) - h, std::max(a.y(), b.y()) + h,
          out.height);
      segments.push_back({v, curve_ref[item].first});
    }
  }
  // --- Points. ---
  struct ScreenPoint {
    Vec3 p;
    Color color;
    double radius;
    bool outlined;
  };
  std::vector<ScreenPoint> points;
  std::vector<std::vector<int>> point_bands(out_bands);
  for (const PointLayer& layer : drawing.points)
    for (std::size_t i = 0; i < layer.points->size(); ++i) {
      const Vec3 p = camera.project((*layer.points)[i]);
      if (!finite(p)) continue;
      const double r = std::max(0.5, layer.radius);
      bin(point_bands, static_cast<int>(points.size()), p.y() - r - 2, p.y() + r + 2, out.height);
      points.push_back({p, layer.color_ids.empty() ? layer.color : palette_color(layer.color_ids[i]), r, layer.outlined});
    }

  parallel_for(out_bands, threads, [&](int band) {
    const int row0 = band * kBandRows, row1 = std::min(out.height, row0 + kBandRows);
    for (std::size_t li = 0; li < drawing.meshes.size(); ++li) {
      if (silhouette_of_layer[li] < 0) continue;
      const MeshLayer& layer = drawing.meshes[li];
      const std::vector<float>& fraction = tint[silhouette_of_layer[li]];
      for (int y = row0; y < row1; ++y)
        for (int x = 0; x < out.width; ++x)
          if (fraction[out.at(x, y)] > 0) out.blend(out.at(x, y), layer.color, layer.opacity * fraction[out.at(x, y)]);
    }
    for (int index : segment_bands[band]) {
      const Segment& s = segments[index];
      const CurveLayer& layer = drawing.curves[s.layer];
      const Vec3 &a = cv.screen[s.vertex], &b = cv.screen[s.vertex + 1];
      const Color &ca = cv.color[s.vertex], &cb = cv.color[s.vertex + 1];
      const float za = static_cast<float>(a.z()), dz = static_cast<float>(b.z() - a.z());
      const Color dc{cb.r - ca.r, cb.g - ca.g, cb.b - ca.b};
      raster::line_coverage(static_cast<float>(a.x()), static_cast<float>(a.y()), static_cast<float>(b.x()),
                            static_cast<float>(b.y()), static_cast<float>(layer.width), out.width, row0, row1,
                            [&](int x, int y, float share, float t) {
                              const std::size_t i = out.at(x, y);
                              const float z = za + t * dz;
                              if (z > out.depth[i] + depth_bias) return;
                              const float cover = share * layer.opacity;
                              out.blend(i, {ca.r + t * dc.r, ca.g + t * dc.g, ca.b + t * dc.b}, cover);
                              // Only a mostly covered pixel occludes what comes later; fringes stay
                              // see-through.
                              if (cover >= 0.5f) out.depth[i] = std::min(out.depth[i], z);
                            });
    }
    for (int index : point_bands[band]) {
      const ScreenPoint& sp = points[index];
      const double ring = sp.outlined ? 1.0 : 0.0;
      const double reach = sp.radius + ring + 1;
      const int x0 = std::max(0, static_cast<int>(std::floor(sp.p.x() - reach)));
      const int x1 = std::min(out.width - 1, static_cast<int>(std::ceil(sp.p.x() + reach)));
      const int y0 = std::max(row0, static_cast<int>(std::floor(sp.p.y() - reach)));
      const int y1 = std::min(row1 - 1, static_cast<int>(std::ceil(sp.p.y() + reach)));
      const float z = static_cast<float>(sp.p.z());
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const double d = std::hypot(x + 0.5 - sp.p.x(), y + 0.5 - sp.p.y());
          const std::size_t i = out.at(x, y);
          if (z > out.depth[i] + depth_bias) continue;
          if (sp.outlined)
            out.blend(i, {0.05f, 0.05f, 0.06f}, static_cast<float>(std::clamp(sp.radius + ring + 0.5 - d, 0.0, 1.0)));
          const float cover = static_cast<float>(std::clamp(sp.radius + 0.5 - d, 0.0, 1.0));
          out.blend(i, sp.color, cover);
          if (cover >= 0.5f) out.depth[i] = std::min(out.depth[i], z);
        }
    }
    for (std::size_t li = 0; li < drawing.meshes.size(); ++li) {
      if (silhouette_of_layer[li] < 0 || drawing.meshes[li].outline_width <= 0) continue;
      const std::vector<float>& fraction = outline[silhouette_of_layer[li]];
      for (int y = row0; y < row1; ++y)
        for (int x = 0; x < out.width; ++x)
          if (fraction[out.at(x, y)] > 0)
            out.blend(out.at(x, y), drawing.meshes[li].outline, std::min(1.0f, 0.9f * fraction[out.at(x, y)] * 2.0f));
    }
  });

  Canvas canvas(camera.width, camera.height, options.background_bottom);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const float* p = &out.rgb[out.at(x, y) * 3];
      canvas.set(x, y, {p[0], p[1], p[2]});
    }
  if (!drawing.title.empty()) {
    const double margin = std::min(12.0, 0.02 * canvas.width());
    canvas.text(margin, 12, drawing.title, {0.92f, 0.92f, 0.92f},
                Canvas::fitting_scale(drawing.title, canvas.width() - 2 * margin, 2.0));
  }
  return canvas.image();
}

}  // namespace hairfit
