#include "io/obj_mesh.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <string_view>

#include "core/error.h"
#include "core/weld.h"
#include "io/atomic_file.h"
#include "io/number_text.h"

namespace hairfit {

namespace {

// Whitespace as `istream >> std::string` skips it in the C locale.
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r'; }

// The next whitespace-separated token of `line` from `at` (empty at the end), as `>>` reads it.
std::string_view next_token(std::string_view line, std::size_t& at) {
  while (at < line.size() && is_space(line[at])) ++at;
  const std::size_t begin = at;
  while (at < line.size() && !is_space(line[at])) ++at;
  return line.substr(begin, at - begin);
}

// -?[0-9]+ from s[i]; advances i past it when it is there.
bool integer_at(std::string_view s, std::size_t& i) {
  std::size_t j = i + (i < s.size() && s[i] == '-');
  const std::size_t digits = j;
  while (j < s.size() && s[j] >= '0' && s[j] <= '9') ++j;
  if (j == digits) return false;
  i = j;
  return true;
}

// The whole token is v, v/vt, v//vn or v/vt/vn with integers: -?[0-9]+(/(-?[0-9]+)?(/-?[0-9]+)?)?
bool is_face_token(std::string_view s) {
  std::size_t i = 0;
  if (!integer_at(s, i)) return false;
  if (i == s.size()) return true;
  if (s[i++] != '/') return false;
  integer_at(s, i);  // optional
  if (i == s.size()) return true;
  if (s[i++] != '/') return false;
  return integer_at(s, i) && i == s.size();
}

// Line-level checks tinyobjloader does not make: it reads "nan" as a number silently and has no
// line numbers in its messages. Returns every vertex's coordinates in file order, each the double
// nearest its text (strtod): tinyobjloader keeps 32-bit floats (a step of 10⁻³ cm at 10⁴ cm from
// the origin) and its double build sums digit by digit, off by an ulp. (A scan of the text in
// place: string streams and a regular expression take 9 000 instructions a line.)
std::vector<Vec3> check_obj_text(const std::filesystem::path& path, const std::string& text, int& faces) {
  const std::string file = path.string();
  const std::size_t probe = std::min<std::size_t>(text.size(), 4096);
  if (std::memchr(text.data(), '\0', probe) != nullptr)
    throw InputError(file, "is a binary file, not an OBJ text file; export the mesh as Wavefront OBJ");

  const std::string_view all(text);
  int line_number = 0, vertices = 0;
  faces = 0;
  std::vector<Vec3> positions;
  std::vector<std::pair<int, std::string_view>> face_lines;
  for (std::size_t begin = 0; begin < all.size();) {
    std::size_t end = all.find('\n', begin);
    if (end == std::string_view::npos) end = all.size();
    const std::string_view line = all.substr(begin, end - begin);
    begin = end + 1;
    ++line_number;
    if (line.size() >= 2 && line[0] == 'v' && (line[1] == ' ' || line[1] == '\t')) {
      ++vertices;
      std::size_t at = 2;
      Vec3& position = positions.emplace_back();
      for (int axis = 0; axis < 3; ++axis) {
        const std::string token(next_token(line, at));
        char* number_end = nullptr;
        const double value = std::strtod(token.c_str(), &number_end);
        if (token.empty() || *number_end != '\0' || !std::isfinite(value)) {
          const std::string whole(line);
          const int column = static_cast<int>(whole.find(token.empty() ? std::string("v") : token)) + 1;
          throw InputError({Diagnostic{{file, line_number, column},
                                       "vertex " + std::to_string(vertices) + " has " +
                                           (token.empty() ? std::string("fewer than 3 coordinates")
                                                          : "a non-finite or unreadable coordinate \"" + token + "\"") +
                                           "; every vertex needs three finite numbers",
                                       whole}});
        }
        position[axis] = value;
      }
    } else if (line.size() >= 2 && line[0] == 'f' && (line[1] == ' ' || line[1] == '\t')) {
      ++faces;
      face_lines.emplace_back(line_number, line);
    }
  }
  for (const auto& [number, face] : face_lines) {
    std::size_t at = 2;
    for (std::string_view entry = next_token(face, at); !entry.empty(); entry = next_token(face, at)) {
      // v, v/vt, v//vn or v/vt/vn: integers only (tinyobjloader reads other text as index 0).
      const std::string token(entry);
      if (!is_face_token(entry)) {
        const std::string whole(face);
        throw InputError({Diagnostic{{file, number, static_cast<int>(whole.find(token)) + 1},
                                     "face entry \"" + token + "\" is not a vertex index (write v, v/vt, v//vn or v/vt/vn "
                                     "with integers)",
                                     whole}});
      }
      const long index = std::strtol(token.c_str(), nullptr, 10);
      const long resolved = index < 0 ? vertices + index + 1 : index;
      if (index == 0 || resolved < 1 || resolved > vertices) {
        const std::string whole(face);
        throw InputError({Diagnostic{{file, number, static_cast<int>(whole.find(token)) + 1},
                                     "face refers to vertex " + std::to_string(index) + " but the file has " +
                                         std::to_string(vertices) + " vertices (valid: 1.." +
                                         std::to_string(vertices) + " or negative relative indices)",
                                     whole}});
      }
    }
  }
  return positions;
}

// The text tinyobjloader parses: only vertex (`v`) and face (`f`) lines, and with `texture` the
// texture coordinates (`vt`), the others blanked. The mesh needs nothing else, and tinyobjloader
// reads some other statements unchecked (a `vw` weight of 1e15 overflows an int inside it, found
// by fuzzing).
std::string vertex_and_face_lines(const std::string& text, bool texture = false) {
  std::string out;
  out.reserve(text.size());
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    const bool keep = (end - begin >= 2 && (text[begin] == 'v' || text[begin] == 'f') &&
                       (text[begin + 1] == ' ' || text[begin + 1] == '\t')) ||
                      (texture && end - begin >= 3 && text.compare(begin, 2, "vt") == 0 &&
                       (text[begin + 2] == ' ' || text[begin + 2] == '\t'));
    if (keep) out.append(text, begin, end - begin);
    out += '\n';
    begin = end + 1;
  }
  return out;
}

// The whole file, or InputError naming it when it is missing, a folder or unreadable.
std::string read_obj_text(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const std::string file = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(file, "no such file; check the path (relative paths start at the scene file's folder)");
  if (fs::is_directory(path, ec)) throw InputError(file, "is a folder, not an OBJ mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "cannot be read (permissions?)");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// tinyobjloader's reading of the checked text; `triangulate` false keeps every polygon whole.
void parse_obj(tinyobj::ObjReader& reader, const std::string& file, const std::string& text, bool triangulate,
               bool texture) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = triangulate;
  config.vertex_color = false;
  config.mtl_search_path = "";
  if (!reader.ParseFromString(vertex_and_face_lines(text, texture), "", config))
    throw InputError(file, "is not a readable OBJ mesh: " + reader.Error());
}

// Significant digits for the coordinates: 9 (%.9g: 10⁻⁸ of the mesh's size about the origin);
// a mesh far from the origin gets all 17, so it reads back exactly.
int position_digits(const Mesh& mesh) {
  if (mesh.positions.empty()) return 9;
  const auto [lo, hi] = bounding_box(mesh);
  const double size = (hi - lo).maxCoeff(), farthest = lo.cwiseAbs().cwiseMax(hi.cwiseAbs()).maxCoeff();
  return digits_for_far_data(9, farthest, size) > 9 ? 17 : 9;
}

}  // namespace

LoadedMesh load_obj_mesh(const std::filesystem::path& path, double scale_to_cm) {
  const std::string file = path.string();
  const std::string text = read_obj_text(path);

  LoadedMesh result;
  const std::vector<Vec3> file_positions = check_obj_text(path, text, result.file_faces);
  result.file_vertices = static_cast<int>(file_positions.size());

  tinyobj::ObjReader reader;
  parse_obj(reader, file, text, true, false);

  const std::vector<tinyobj::real_t>& v = reader.GetAttrib().vertices;
  const int n = static_cast<int>(v.size() / 3);
  if (n != result.file_vertices)  // both count the `v` lines parse_obj keeps
    throw InputError(file, "the OBJ reader sees " + std::to_string(n) + " vertices where the file has " +
                               std::to_string(result.file_vertices) + " `v` lines; check the `v` lines");
  // tinyobjloader keeps colours only when every vertex has them (vertex_color = false: no fallback).
  const std::vector<tinyobj::real_t>& rgb = reader.GetAttrib().colors;
  const bool with_colors = n > 0 && rgb.size() == v.size();
  // Weld exact duplicates: scans often repeat vertices along patch seams. Each vertex joins the
  // first vertex at its position (weld_points at tolerance 0); welded vertices keep the order of
  // their first appearance, and the first one's colour.
  std::vector<Vec3> at(n);
  for (int i = 0; i < n; ++i) at[i] = file_positions[i] * scale_to_cm;
  for (int i = 0; i < n; ++i)
    if (!at[i].allFinite())
      throw InputError(file, "vertex " + std::to_string(i + 1) + " is beyond the range of numbers once scaled to cm; " +
                                 "check the scene's units.length and the file's coordinates");
  const std::vector<int> first = weld_points(at, 0.0);
  std::vector<int> weld(n);
  std::vector<Vec3> welded, welded_colors;
  for (int i = 0; i < n; ++i) {
    if (first[i] == i) {
      weld[i] = static_cast<int>(welded.size());
      welded.push_back(at[i]);
      if (with_colors) welded_colors.emplace_back(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]);
    } else {
      weld[i] = weld[first[i]];
      ++result.welded_duplicates;
    }
  }

  std::vector<Vec3i> triangles;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const std::vector<tinyobj::index_t>& idx = shape.mesh.indices;
    for (std::size_t f = 0; f + 2 < idx.size(); f += 3) {
      for (std::size_t k = f; k < f + 3; ++k)  // after the text checks, only a reader disagreement gets here
        if (idx[k].vertex_index < 0 || idx[k].vertex_index >= n)
          throw InputError(file, "a face refers to vertex " + std::to_string(idx[k].vertex_index + 1) + " of " +
                                     std::to_string(n) + " as the OBJ reader sees them; check the `v` and `f` lines");
      Vec3i t(weld[idx[f].vertex_index], weld[idx[f + 1].vertex_index], weld[idx[f + 2].vertex_index]);
      const Vec3 e1 = welded[t[1]] - welded[t[0]], e2 = welded[t[2]] - welded[t[0]];
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || e1.cross(e2).squaredNorm() == 0.0) {
        ++result.dropped_degenerate;
        continue;
      }
      triangles.push_back(t);
    }
  }
  if (triangles.empty())
    throw InputError(file, result.file_vertices == 0
                               ? "has no vertices; it must be a triangle mesh in Wavefront OBJ format"
                               : "has no triangle of non-zero area; it must be a triangle mesh (faces as `f a b c` lines)");

  // Keep only the vertices triangles use, in their original order.
  std::vector<int> compact(welded.size(), -1);
  for (const Vec3i& t : triangles)
    for (int k = 0; k < 3; ++k) compact[t[k]] = 0;
  for (std::size_t i = 0; i < welded.size(); ++i) {
    if (compact[i] < 0) {
      ++result.unused_vertices;
      continue;
    }
    compact[i] = static_cast<int>(result.mesh.positions.size());
    result.mesh.positions.push_back(welded[i]);
    if (with_colors) result.colors.push_back(welded_colors[i]);
  }
  for (Vec3i& t : triangles) t = Vec3i(compact[t[0]], compact[t[1]], compact[t[2]]);
  result.mesh.triangles = std::move(triangles);
  return result;
}

TexturedMesh load_obj_textured(const std::filesystem::path& path, double scale_to_cm) {
  const std::string file = path.string();
  const std::string text = read_obj_text(path);
  int faces = 0;
  const std::vector<Vec3> file_positions = check_obj_text(path, text, faces);
  tinyobj::ObjReader reader;
  parse_obj(reader, file, text, false, true);

  TexturedMesh result;
  const int n = static_cast<int>(file_positions.size());
  if (static_cast<int>(reader.GetAttrib().vertices.size() / 3) != n)
    throw InputError(file, "the OBJ reader sees another number of vertices than the file's `v` lines; check them");
  for (int i = 0; i < n; ++i) {
    result.mesh.positions.push_back(file_positions[i] * scale_to_cm);
    if (!result.mesh.positions.back().allFinite())
      throw InputError(file, "vertex " + std::to_string(i + 1) + " is beyond the range of numbers once scaled to cm");
  }
  const std::vector<tinyobj::real_t>& vt = reader.GetAttrib().texcoords;
  const int m = static_cast<int>(vt.size() / 2);
  for (int i = 0; i < m; ++i) {
    result.texture_coordinates.emplace_back(vt[2 * i], vt[2 * i + 1]);
    if (!result.texture_coordinates.back().allFinite())
      throw InputError(file, "texture coordinate " + std::to_string(i + 1) + " is not a finite number pair");
  }
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const std::vector<tinyobj::index_t>& idx = shape.mesh.indices;
    std::size_t first = 0;
    for (const unsigned char corners : shape.mesh.num_face_vertices) {
      for (std::size_t k = 1; k + 1 < corners; ++k) {  // the fan from the polygon's first corner
        const tinyobj::index_t &a = idx[first], &b = idx[first + k], &c = idx[first + k + 1];
        for (const tinyobj::index_t* corner : {&a, &b, &c}) {
          if (corner->vertex_index < 0 || corner->vertex_index >= n)
            throw InputError(file, "a face refers to vertex " + std::to_string(corner->vertex_index + 1) + " of " +
                                       std::to_string(n));
          if (corner->texcoord_index >= m)
            throw InputError(file, "a face refers to texture coordinate " + std::to_string(corner->texcoord_index + 1) +
                                       " of " + std::to_string(m));
        }
        result.mesh.triangles.emplace_back(a.vertex_index, b.vertex_index, c.vertex_index);
        result.triangle_texture.emplace_back(a.texcoord_index, b.texcoord_index, c.texcoord_index);
      }
      first += corners;
    }
  }
  if (result.mesh.triangles.empty()) throw InputError(file, "has no faces; it must be a polygon mesh in Wavefront OBJ format");
  return result;
}

void write_obj_mesh(const std::filesystem::path& path, const Mesh& mesh,
                    const std::vector<Vec2>& texture_coordinates, const std::vector<Vec3>& colors) {
  // Built in memory and written once; numbers as printf's %.9g / %.4g / %d would write them.
  std::string text;
  char buffer[48];
  auto number = [&](double v, int precision) { text.append(buffer, format_general(buffer, v, precision)); };
  auto index = [&](int i) { text.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, i).ptr); };
  const bool with_colors = colors.size() == mesh.positions.size();
  const int digits = position_digits(mesh);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3& p = mesh.positions[i];
    text += "v";
    for (int k = 0; k < 3; ++k) text += ' ', number(p[k], digits);
    if (with_colors)
      for (int k = 0; k < 3; ++k) text += ' ', number(colors[i][k], 4);
    text += '\n';
  }
  for (const Vec2& uv : texture_coordinates) {
    text += "vt ";
    number(uv.x(), 9);
    text += ' ';
    number(uv.y(), 9);
    text += '\n';
  }
  const bool with_uv = texture_coordinates.size() == mesh.positions.size();
  for (const Vec3i& t : mesh.triangles) {
    text += 'f';
    for (int k = 0; k < 3; ++k) {
      text += ' ';
      index(t[k] + 1);
      if (with_uv) text += '/', index(t[k] + 1);
    }
    text += '\n';
  }
  write_text_file_atomically(path, text);
}

}  // namespace hairfit
