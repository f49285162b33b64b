#include "io/curve_files.h"

#include "core/mesh.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "io/atomic_file.h"
#include "io/number_text.h"

namespace hairfit {

namespace {

static_assert(sizeof(float) == 4, "hairfit writes IEEE-754 single precision");

// Text built in memory and written once. Numbers go through format_general, which writes exactly
// what printf's %.Ng writes, at a fraction of snprintf's (or std::to_chars') cost: writing
// guides.obj at paper scale took as long as computing every strand.
class Text {
 public:
  Text& operator<<(const char* s) {
    const std::size_t n = std::strlen(s);
    std::memcpy(room(n), s, n);
    size_ += n;
    return *this;
  }
  Text& number(double value, int precision) {
    char* end = room(48);
    size_ += format_general(end, value, precision) - end;
    return *this;
  }
  Text& integer(std::uint64_t value) {
    char* end = room(24);
    size_ += std::to_chars(end, end + 24, value).ptr - end;
    return *this;
  }
  // x, y and z at %.7g (or `digits`), separated by `separator`.
  Text& point(const Vec3& p, const char* separator, int digits = 7) {
    number(p.x(), digits) << separator;
    number(p.y(), digits) << separator;
    return number(p.z(), digits);
  }
  void write_to(std::ostream& out) const { out.write(text_.data(), static_cast<std::streamsize>(size_)); }

 private:
  // The end of the text, with room for n more characters (the buffer grows by doubling; only
  // size_ characters of it are text).
  char* room(std::size_t n) {
    if (size_ + n > text_.size()) text_.resize(std::max(2 * text_.size(), size_ + n + 4096));
    return text_.data() + size_;
  }

  std::string text_;
  std::size_t size_ = 0;
};

// All formats here are little-endian; x86 and ARM Linux are too, so raw copies are exact.
template <class T>
void put(std::ostream& out, T value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof value);
}

// 7 digits for curves about the origin, more for curves far from it (the same step relative to
// their size).
int point_digits(const Curves& curves) {
  if (curves.points.empty()) return 7;
  Vec3 lo = curves.points.front(), hi = lo;
  for (const Vec3& p : curves.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return digits_for_far_data(7, lo.cwiseAbs().cwiseMax(hi.cwiseAbs()).maxCoeff(), (hi - lo).maxCoeff());
}

void require_finite(const Curves& curves, const std::filesystem::path& path) {
  for (std::size_t i = 0; i < curves.points.size(); ++i)
    if (!curves.points[i].allFinite())
      throw std::logic_error("refusing to write a non-finite point (index " + std::to_string(i) + ") to " + path.string());
}

}  // namespace

void write_hair_file(const std::filesystem::path& path, const Curves& curves, const std::string& info) {
  require_finite(curves, path);
  for (std::size_t c = 0; c < curves.count(); ++c)
    if (curves.size(c) < 1 || curves.size(c) - 1 > 65535)
      throw std::logic_error("curve " + std::to_string(c) + " has " + std::to_string(curves.size(c)) +
                             " points; .hair allows 1 to 65536");
  const bool thickness = curves.widths.size() == curves.points.size() && !curves.points.empty();
  write_file_atomically(path, [&](std::ostream& out) {
    out.write("HAIR", 4);
    put<std::uint32_t>(out, static_cast<std::uint32_t>(curves.count()));
    put<std::uint32_t>(out, static_cast<std::uint32_t>(curves.points.size()));
    put<std::uint32_t>(out, 1u | 2u | (thickness ? 4u : 0u));  // segments, points[, thickness]
    put<std::uint32_t>(out, 0);                                // default segments (unused: bit 1 set)
    put<float>(out, 0.007f);                                   // default thickness, cm
    put<float>(out, 0.0f);                                     // default transparency
    for (float c : {0.35f, 0.22f, 0.12f}) put<float>(out, c);  // default colour: brown
    char text[88] = {};
    std::strncpy(text, info.c_str(), sizeof text - 1);
    out.write(text, sizeof text);
    // The arrays are converted into one buffer and written at once: a stream write per value
    // cost more than the conversion (tens of megabytes for a full head).
    std::vector<std::uint16_t> segments(curves.count());
    for (std::size_t c = 0; c < curves.count(); ++c) segments[c] = static_cast<std::uint16_t>(curves.size(c) - 1);
    out.write(reinterpret_cast<const char*>(segments.data()), segments.size() * sizeof(std::uint16_t));
    // Converted a block at a time into one reused buffer: a buffer for all of them (17 MB at
    // paper scale) cost more in fresh pages than the conversion itself.
    constexpr std::size_t kBlock = 16384;  // points
    std::vector<float> coordinates(3 * std::min(kBlock, curves.points.size()));
    for (std::size_t begin = 0; begin < curves.points.size(); begin += kBlock) {
      const std::size_t end = std::min(curves.points.size(), begin + kBlock);
      for (std::size_t i = begin; i < end; ++i)
        for (int k = 0; k < 3; ++k) coordinates[3 * (i - begin) + k] = static_cast<float>(curves.points[i][k]);
      out.write(reinterpret_cast<const char*>(coordinates.data()), 3 * (end - begin) * sizeof(float));
    }
    if (thickness) out.write(reinterpret_cast<const char*>(curves.widths.data()), curves.widths.size() * sizeof(float));
  });
}

Curves read_hair_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "no such file or not readable");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t at = 0;
  auto take = [&](void* dst, std::size_t n) {
    if (at + n > bytes.size()) throw InputError(file, "is truncated (a .hair file needs " + std::to_string(at + n) + " bytes here)");
    std::memcpy(dst, bytes.data() + at, n);
    at += n;
  };
  char magic[4];
  take(magic, 4);
  if (std::memcmp(magic, "HAIR", 4) != 0) throw InputError(file, "is not a cyHair file (it must start with \"HAIR\")");
  std::uint32_t strands, points, bits, default_segments;
  take(&strands, 4);
  take(&points, 4);
  take(&bits, 4);
  take(&default_segments, 4);
  float default_thickness;
  take(&default_thickness, 4);
  at = 128;
  if (!(bits & 2u)) throw InputError(file, "has no point array (bit 2 of the header flags)");
  Curves curves;
  std::vector<std::uint16_t> segments(strands, static_cast<std::uint16_t>(default_segments));
  if (bits & 1u) take(segments.data(), 2 * static_cast<std::size_t>(strands));
  std::uint64_t total = 0;
  for (std::uint16_t s : segments) {
    total += s + 1u;
    curves.offsets.push_back(static_cast<std::uint32_t>(total));
    curves.guide.push_back(-1);
  }
  if (total != points)
    throw InputError(file, "is inconsistent: segment counts add up to " + std::to_string(total) + " points but the header says " +
                               std::to_string(points));
  curves.points.resize(points);
  for (Vec3& p : curves.points) {
    float xyz[3];
    take(xyz, sizeof xyz);
    p = Vec3(xyz[0], xyz[1], xyz[2]);
  }
  if (bits & 4u) {
    curves.widths.resize(points);
    take(curves.widths.data(), 4 * static_cast<std::size_t>(points));
  }
  return curves;
}

void write_obj_curves(const std::filesystem::path& path, const Curves& curves, int threads) {
  require_finite(curves, path);
  // The `v` lines in blocks of points, then the `l` lines in blocks of curves, each block's text
  // formatted on its own (in parallel) and written in order.
  constexpr std::size_t kPoints = 8192, kCurves = 2048;
  const int digits = point_digits(curves);
  const std::size_t point_blocks = (curves.points.size() + kPoints - 1) / kPoints;
  const std::size_t curve_blocks = (curves.count() + kCurves - 1) / kCurves;
  std::vector<Text> blocks(1 + point_blocks + curve_blocks);
  blocks[0] << "# hairfit curves: ";
  blocks[0].integer(curves.count()) << " curves, ";
  blocks[0].integer(curves.points.size()) << " points\n";
  parallel_for(static_cast<int>(point_blocks + curve_blocks), threads, [&](int b) {
    Text& text = blocks[1 + b];
    if (static_cast<std::size_t>(b) < point_blocks) {
      const std::size_t end = std::min(curves.points.size(), (b + 1) * kPoints);
      for (std::size_t i = b * kPoints; i < end; ++i) {
        text << "v ";
        text.point(curves.points[i], " ", digits) << "\n";
      }
      return;
    }
    const std::size_t first = (b - point_blocks) * kCurves, last = std::min(curves.count(), first + kCurves);
    for (std::size_t c = first; c < last; ++c)
      for (std::uint32_t i = curves.offsets[c]; i + 1 < curves.offsets[c + 1]; ++i) {
        text << "l ";
        text.integer(i + 1) << " ";
        text.integer(i + 2) << "\n";
      }
  });
  write_file_atomically(path, [&](std::ostream& out) {
    for (const Text& text : blocks) text.write_to(out);
  });
}

void write_usda_curves(const std::filesystem::path& path, const Curves& curves, double default_width, const Vec3& up) {
  require_finite(curves, path);
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  double widest = default_width;
  for (std::size_t i = 0; i < curves.points.size(); ++i) {
    lo = lo.cwiseMin(curves.points[i]);
    hi = hi.cwiseMax(curves.points[i]);
    if (!curves.widths.empty()) widest = std::max(widest, static_cast<double>(curves.widths[i]));
  }
  if (curves.points.empty()) lo = hi = Vec3::Zero();
  lo.array() -= widest / 2;
  hi.array() += widest / 2;
  const char* up_axis = std::fabs(up.z()) > std::fabs(up.y()) ? "Z" : "Y";
  write_file_atomically(path, [&](std::ostream& out) {
    char text[128];
    out << "#usda 1.0\n(\n    defaultPrim = \"Hair\"\n    metersPerUnit = 0.01\n    upAxis = \"" << up_axis
        << "\"\n)\n\ndef BasisCurves \"Hair\"\n{\n    uniform token type = \"linear\"\n    uniform token wrap = \"nonperiodic\"\n";
    out << "    int[] curveVertexCounts = [";
    for (std::size_t c = 0; c < curves.count(); ++c) out << (c ? ", " : "") << curves.size(c);
    out << "]\n    point3f[] points = [";
    Text values;
    const int digits = point_digits(curves);
    for (std::size_t i = 0; i < curves.points.size(); ++i) {
      values << (i ? ", (" : "(");
      values.point(curves.points[i], ", ", digits) << ")";
    }
    values << "]\n    float[] widths = [";
    for (std::size_t i = 0; i < curves.points.size(); ++i) {
      values << (i ? ", " : "");
      values.number(curves.widths.empty() ? default_width : curves.widths[i], 6);
    }
    values.write_to(out);
    out << "] (\n        interpolation = \"vertex\"\n    )\n";
    if (curves.guide.size() == curves.count()) {
      out << "    int[] primvars:guide = [";
      for (std::size_t c = 0; c < curves.count(); ++c) out << (c ? ", " : "") << curves.guide[c];
      out << "] (\n        interpolation = \"uniform\"\n    )\n";
    }
    std::snprintf(text, sizeof text, "    float3[] extent = [(%.7g, %.7g, %.7g), (%.7g, %.7g, %.7g)]\n", lo.x(), lo.y(),
                  lo.z(), hi.x(), hi.y(), hi.z());
    out << text << "}\n";
  });
}

void write_ply_curves(const std::filesystem::path& path, const Curves& curves) {
  require_finite(curves, path);
  std::size_t edges = 0;
  for (std::size_t c = 0; c < curves.count(); ++c) edges += curves.size(c) > 0 ? curves.size(c) - 1 : 0;
  write_file_atomically(path, [&](std::ostream& out) {
    out << "ply\nformat binary_little_endian 1.0\ncomment hairfit curves, one edge per segment\n"
        << "element vertex " << curves.points.size() << "\nproperty float x\nproperty float y\nproperty float z\n"
        << "property int guide\nelement edge " << edges << "\nproperty int vertex1\nproperty int vertex2\nend_header\n";
    for (std::size_t c = 0; c < curves.count(); ++c) {
      const std::int32_t g = c < curves.guide.size() ? curves.guide[c] : -1;
      for (std::uint32_t i = curves.offsets[c]; i < curves.offsets[c + 1]; ++i) {
        for (int k = 0; k < 3; ++k) put<float>(out, static_cast<float>(curves.points[i][k]));
        put<std::int32_t>(out, g);
      }
    }
    for (std::size_t c = 0; c < curves.count(); ++c)
      for (std::uint32_t i = curves.offsets[c]; i + 1 < curves.offsets[c + 1]; ++i) {
        put<std::int32_t>(out, static_cast<std::int32_t>(i));
        put<std::int32_t>(out, static_cast<std::int32_t>(i + 1));
      }
  });
}

}  // namespace hairfit
