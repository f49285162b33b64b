#include "io/ply_points.h"

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "io/atomic_file.h"

namespace hairfit {

namespace {

bool valid_name(const std::string& name) {
  if (name.empty() || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

// Size in bytes of a PLY scalar type name, 0 if unknown.
int type_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32") return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

double decode(const char* p, const std::string& type) {
  auto get = [p](auto tag) {
    decltype(tag) v;
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  };
  if (type == "char" || type == "int8") return get(std::int8_t{});
  if (type == "uchar" || type == "uint8") return get(std::uint8_t{});
  if (type == "short" || type == "int16") return get(std::int16_t{});
  if (type == "ushort" || type == "uint16") return get(std::uint16_t{});
  if (type == "int" || type == "int32") return get(std::int32_t{});
  if (type == "uint" || type == "uint32") return get(std::uint32_t{});
  if (type == "float" || type == "float32") return get(float{});
  return get(double{});
}

bool is_integer_type(const std::string& type) { return type != "float" && type != "float32" && type != "double" && type != "float64"; }

}  // namespace

const PlyColumn* PlyPoints::column(const std::string& name) const {
  for (const PlyColumn& c : columns)
    if (c.name == name) return &c;
  return nullptr;
}

void write_ply_points(const std::filesystem::path& path, const PlyPoints& points, bool binary) {
  const std::size_t n = points.positions.size();
  for (const PlyColumn& c : points.columns) {
    if (!valid_name(c.name)) throw std::invalid_argument("PLY property name \"" + c.name + "\" is not valid");
    if (c.values.size() != n) throw std::invalid_argument("PLY column \"" + c.name + "\" has the wrong length");
  }
  write_file_atomically(path, [&](std::ostream& out) {
    out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\ncomment written by hairfit\n";
    out << "element vertex " << n << "\nproperty float x\nproperty float y\nproperty float z\n";
    for (const PlyColumn& c : points.columns) out << "property " << (c.is_int ? "int" : "float") << ' ' << c.name << '\n';
    out << "end_header\n";
    if (binary) {
      // Rows are assembled in one buffer and written at once: a stream write per value cost
      // more than the conversion. Every value is 4 bytes (float or int32), little-endian like
      // the hosts we build for, so memcpy keeps it exact.
      const std::size_t row = 4 * (3 + points.columns.size());
      std::vector<char> bytes(n * row);
      for (std::size_t i = 0; i < n; ++i) {
        char* at = bytes.data() + i * row;
        auto store = [&at](auto value) {
          std::memcpy(at, &value, sizeof value);
          at += sizeof value;
        };
        for (int k = 0; k < 3; ++k) store(static_cast<float>(points.positions[i][k]));
        for (const PlyColumn& c : points.columns) {
          if (c.is_int)
            store(static_cast<std::int32_t>(c.values[i]));
          else
            store(static_cast<float>(c.values[i]));
        }
      }
      out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      return;
    }
    char text[64];
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& p = points.positions[i];
      std::snprintf(text, sizeof text, "%.9g %.9g %.9g", p.x(), p.y(), p.z());
      out << text;
      for (const PlyColumn& c : points.columns) {
        if (c.is_int)
          std::snprintf(text, sizeof text, " %d", static_cast<int>(c.values[i]));
        else
          std::snprintf(text, sizeof text, " %.9g", static_cast<float>(c.values[i]));
        out << text;
      }
      out << '\n';
    }
  });
}

PlyPoints read_ply_points(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "cannot open the PLY file");
  std::string line;
  std::getline(in, line);
  if (line != "ply") throw InputError(file, "not a PLY file (first line is not \"ply\")");
  bool binary = false;
  long long vertices = -1;
  bool in_vertex = false, vertex_seen = false, vertex_done = false;
  std::vector<std::pair<std::string, std::string>> properties;  // (type, name)
  for (;;) {
    if (!std::getline(in, line)) throw InputError(file, "the PLY header has no end_header");
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "end_header") break;
    if (word == "format") {
      std::string format;
      words >> format;
      if (format == "binary_little_endian")
        binary = true;
      else if (format != "ascii")
        throw InputError(file, "PLY format \"" + format + "\" is not supported (ascii or binary_little_endian)");
    } else if (word == "element") {
      std::string name;
      long long count = 0;
      words >> name >> count;
      if (in_vertex) vertex_done = true;
      in_vertex = name == "vertex";
      if (in_vertex) {
        if (vertex_done || vertex_seen) throw InputError(file, "two vertex elements");
        vertex_seen = true;
        vertices = count;
      } else if (!vertex_seen) {
        throw InputError(file, "the element \"" + name + "\" comes before the vertices; not supported");
      }
    } else if (word == "property" && in_vertex) {
      std::string type, name;
      words >> type >> name;
      if (type == "list") throw InputError(file, "list properties on vertices are not supported");
      if (type_size(type) == 0) throw InputError(file, "unknown PLY property type \"" + type + "\"");
      properties.emplace_back(type, name);
    }
  }
  if (vertices < 0) throw InputError(file, "the PLY file has no vertex element");
  int ix = -1, iy = -1, iz = -1;
  PlyPoints pts;
  std::vector<int> column_of(properties.size(), -1);
  for (std::size_t k = 0; k < properties.size(); ++k) {
    const std::string& name = properties[k].second;
    if (name == "x") ix = static_cast<int>(k);
    else if (name == "y") iy = static_cast<int>(k);
    else if (name == "z") iz = static_cast<int>(k);
    else {
      column_of[k] = static_cast<int>(pts.columns.size());
      pts.columns.push_back({name, is_integer_type(properties[k].first), {}});
    }
  }
  if (ix < 0 || iy < 0 || iz < 0) throw InputError(file, "the vertices lack x, y or z");
  pts.positions.resize(vertices);
  for (PlyColumn& c : pts.columns) c.values.resize(vertices);
  std::vector<double> row(properties.size());
  for (long long i = 0; i < vertices; ++i) {
    for (std::size_t k = 0; k < properties.size(); ++k) {
      if (binary) {
        char bytes[8];
        in.read(bytes, type_size(properties[k].first));
        row[k] = decode(bytes, properties[k].first);
      } else {
        in >> row[k];
      }
    }
    if (!in) throw InputError(file, "the PLY data ends after " + std::to_string(i) + " of " + std::to_string(vertices) + " vertices");
    pts.positions[i] = Vec3(row[ix], row[iy], row[iz]);
    for (std::size_t k = 0; k < properties.size(); ++k)
      if (column_of[k] >= 0) pts.columns[column_of[k]].values[i] = row[k];
  }
  return pts;
}

}  // namespace hairfit
