#include "io/nrrd.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "io/atomic_file.h"

namespace hairfit {

namespace {

// Shortest text that reads back to the same double.
std::string exact(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r");
  const size_t e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// Parses "(a,b,c)" tuples from a header value.
std::vector<Vec3> parse_vectors(const std::string& text, bool& ok) {
  std::vector<Vec3> out;
  size_t pos = 0;
  ok = true;
  while ((pos = text.find('(', pos)) != std::string::npos) {
    const size_t end = text.find(')', pos);
    if (end == std::string::npos) {
      ok = false;
      break;
    }
    std::string inner = text.substr(pos + 1, end - pos - 1);
    for (char& ch : inner)
      if (ch == ',') ch = ' ';
    std::istringstream in(inner);
    Vec3 v;
    if (!(in >> v.x() >> v.y() >> v.z())) ok = false;
    out.push_back(v);
    pos = end + 1;
  }
  return out;
}

}  // namespace

void write_nrrd(const std::filesystem::path& path, const NrrdVolume& v) {
  const int64_t count = int64_t(v.sizes.x()) * v.sizes.y() * v.sizes.z();
  if (v.sizes.minCoeff() < 1 || int64_t(v.data.size()) != count)
    throw std::invalid_argument("write_nrrd: data size does not match the volume sizes");
  std::string header = "NRRD0004\n# written by hairfit\ntype: float\ndimension: 3\nspace: right-anterior-superior\n";
  header += "sizes: " + std::to_string(v.sizes.x()) + " " + std::to_string(v.sizes.y()) + " " +
            std::to_string(v.sizes.z()) + "\n";
  header += "space directions: (" + exact(v.spacing.x()) + ",0,0) (0," + exact(v.spacing.y()) + ",0) (0,0," +
            exact(v.spacing.z()) + ")\n";
  header += "space origin: (" + exact(v.origin.x()) + "," + exact(v.origin.y()) + "," + exact(v.origin.z()) + ")\n";
  header += "kinds: domain domain domain\nendian: little\nencoding: raw\n\n";
  // The file is little-endian, like the machines hairfit runs on: the floats are written as they
  // lie in memory.
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "NRRD files are written little-endian");
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(header.data(), header.size());
    out.write(reinterpret_cast<const char*>(v.data.data()), std::streamsize(v.data.size() * sizeof(float)));
  });
}

NrrdVolume read_nrrd(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "cannot open the NRRD file");
  std::string line;
  if (!std::getline(in, line) || line.rfind("NRRD000", 0) != 0)
    throw InputError(file, "not a NRRD file (the first line must start with NRRD000)");
  std::map<std::string, std::string> fields;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) break;
    if (line[0] == '#') continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) throw InputError(file, "header line without a field name: \"" + line + "\"");
    const size_t value_start = line.compare(colon, 2, ":=") == 0 ? colon + 2 : colon + 1;
    fields[trim(line.substr(0, colon))] = trim(line.substr(value_start));
  }
  auto need = [&](const std::string& key, const std::string& expected) {
    const auto it = fields.find(key);
    if (it == fields.end()) throw InputError(file, "the header has no \"" + key + "\" field");
    if (!expected.empty() && it->second != expected)
      throw InputError(file, "\"" + key + ": " + it->second + "\" is not supported (expected " + expected + ")");
    return it->second;
  };
  const std::string type = need("type", "");
  if (type != "float" && type != "float32")
    throw InputError(file, "\"type: " + type + "\" is not supported (expected float)");
  need("dimension", "3");
  need("encoding", "raw");
  if (fields.count("endian") && fields["endian"] != "little")
    throw InputError(file, "\"endian: " + fields["endian"] + "\" is not supported (expected little)");
  NrrdVolume v;
  {
    std::istringstream s(need("sizes", ""));
    if (!(s >> v.sizes.x() >> v.sizes.y() >> v.sizes.z()) || v.sizes.minCoeff() < 1)
      throw InputError(file, "\"sizes\" must be three positive integers");
  }
  bool ok = true;
  if (fields.count("space directions")) {
    const std::vector<Vec3> dirs = parse_vectors(fields["space directions"], ok);
    if (!ok || dirs.size() != 3) throw InputError(file, "\"space directions\" must be three (x,y,z) vectors");
    for (int d = 0; d < 3; ++d) {
      for (int e = 0; e < 3; ++e)
        if (e != d && dirs[d][e] != 0)
          throw InputError(file, "only axis-aligned \"space directions\" are supported");
      v.spacing[d] = dirs[d][d];
    }
  }
  if (fields.count("space origin")) {
    const std::vector<Vec3> origin = parse_vectors(fields["space origin"], ok);
    if (!ok || origin.size() != 1) throw InputError(file, "\"space origin\" must be one (x,y,z) vector");
    v.origin = origin[0];
  }
  const int64_t count = int64_t(v.sizes.x()) * v.sizes.y() * v.sizes.z();
  std::string raw(static_cast<size_t>(count) * 4, '\0');
  if (!in.read(raw.data(), raw.size()))
    throw InputError(file, "the data ends early: expected " + std::to_string(count) + " float samples");
  v.data.resize(count);
  for (int64_t i = 0; i < count; ++i) {
    uint32_t bits = 0;
    for (int b = 0; b < 4; ++b) bits |= uint32_t(static_cast<unsigned char>(raw[4 * i + b])) << (8 * b);
    std::memcpy(&v.data[i], &bits, 4);
  }
  return v;
}

}  // namespace hairfit
