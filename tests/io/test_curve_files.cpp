#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <unistd.h>

#include "core/error.h"
#include "io/curve_files.h"
#include "../support/scratch.h"

using namespace hairfit;
namespace fs = std::filesystem;

namespace {

fs::path temp(const std::string& name) {
  const fs::path dir = hairfit::testing::scratch_path("curves");
  fs::create_directories(dir);
  return dir / name;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Three helices of different lengths, with guide ids and tapering widths.
Curves sample_curves(bool widths) {
  Curves c;
  for (int k = 0; k < 3; ++k) {
    std::vector<Vec3> pts;
    for (int i = 0; i < 4 + 3 * k; ++i) pts.emplace_back(std::cos(0.5 * i) + k, 0.25 * i, std::sin(0.5 * i) - 0.125 * k);
    c.add(pts, 10 + k);
  }
  if (widths)
    for (std::size_t i = 0; i < c.points.size(); ++i) c.widths.push_back(0.01f - 0.0005f * static_cast<float>(i % 7));
  return c;
}

int count_lines(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  int n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
  return n;
}

}  // namespace

TEST_CASE(".hair: header, sizes and round trip") {
  for (bool widths : {false, true}) {
    const Curves c = sample_curves(widths);
    const fs::path p = temp(widths ? "w.hair" : "n.hair");
    write_hair_file(p, c, "test");
    const std::string bytes = slurp(p);
    const std::size_t expected = 128 + 2 * c.count() + 12 * c.points.size() + (widths ? 4 * c.points.size() : 0);
    CHECK(bytes.size() == expected);
    CHECK(bytes.compare(0, 4, "HAIR") == 0);
    std::uint32_t header[4];
    std::memcpy(header, bytes.data() + 4, 16);
    CHECK(header[0] == 3);
    CHECK(header[1] == c.points.size());
    CHECK(header[2] == (widths ? 7u : 3u));
    CHECK(std::string(bytes.data() + 40) == "test");

    const Curves back = read_hair_file(p);
    CHECK(back.offsets == c.offsets);
    REQUIRE(back.points.size() == c.points.size());
    for (std::size_t i = 0; i < c.points.size(); ++i)
      CHECK((back.points[i] - c.points[i]).norm() < 1e-6);  // float32 storage
    CHECK(back.widths == c.widths);
  }
}

TEST_CASE(".hair reader refuses truncated and inconsistent files") {
  const fs::path p = temp("t.hair");
  write_hair_file(p, sample_curves(false));
  std::string bytes = slurp(p);
  std::ofstream(temp("cut.hair"), std::ios::binary) << bytes.substr(0, bytes.size() - 5);
  CHECK_THROWS_AS(read_hair_file(temp("cut.hair")), InputError);
  bytes[8] = 99;  // total point count
  std::ofstream(temp("bad.hair"), std::ios::binary) << bytes;
  CHECK_THROWS_WITH_AS(read_hair_file(temp("bad.hair")), doctest::Contains("is inconsistent"), InputError);
  std::ofstream(temp("nothair.hair"), std::ios::binary) << "HEIR and more bytes";
  CHECK_THROWS_WITH_AS(read_hair_file(temp("nothair.hair")), doctest::Contains("not a cyHair file"), InputError);
}

TEST_CASE("OBJ curves: one v per point and one two-index l per segment, root first") {
  const Curves c = sample_curves(false);
  write_obj_curves(temp("c.obj"), c);
  const std::string text = slurp(temp("c.obj"));
  CHECK(count_lines(text, "v ") == static_cast<int>(c.points.size()));
  CHECK(count_lines(text, "l ") == static_cast<int>(c.points.size() - c.count()));
  const std::regex two_indices("^l (\\d+) (\\d+)$");
  std::istringstream in(text);
  int previous_b = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("l ", 0) != 0) continue;
    std::smatch m;
    REQUIRE(std::regex_match(line, m, two_indices));
    const int a = std::stoi(m[1]), b = std::stoi(m[2]);
    CHECK(b == a + 1);
    CHECK(a > previous_b - 1);  // segments in order, root to tip
    previous_b = b;
  }
  CHECK(text.find("v 1 0 0\n") != std::string::npos);  // the first root, exactly
}

TEST_CASE("OBJ curves: every byte as printf writes it, for large files and any thread count") {
  // 40 000 points (over a megabyte of text, so the in-memory text grows many times).
  Curves c;
  for (int k = 0; k < 2000; ++k) {
    std::vector<Vec3> pts;
    for (int i = 0; i < 20; ++i)
      pts.emplace_back(std::cos(0.37 * i + k) * (k + 1) * 1e-3, 1e4 * std::sin(0.11 * i * k), -0.5 * i + 1e-7 * k);
    c.add(pts, k);
  }
  std::string expected = "# hairfit curves: 2000 curves, 40000 points\n";
  char line[128];
  for (const Vec3& p : c.points) {
    std::snprintf(line, sizeof line, "v %.7g %.7g %.7g\n", p.x(), p.y(), p.z());
    expected += line;
  }
  for (std::size_t k = 0; k < c.count(); ++k)
    for (std::uint32_t i = c.offsets[k]; i + 1 < c.offsets[k + 1]; ++i) {
      std::snprintf(line, sizeof line, "l %u %u\n", i + 1, i + 2);
      expected += line;
    }
  for (int threads : {1, 2, 3}) {  // formatted in blocks on several threads: the same bytes
    write_obj_curves(temp("big.obj"), c, threads);
    CHECK(slurp(temp("big.obj")) == expected);
  }
}

TEST_CASE("USDA: linear BasisCurves whose counts, points, widths and extent match the curves") {
  const Curves c = sample_curves(true);
  write_usda_curves(temp("c.usda"), c);
  const std::string text = slurp(temp("c.usda"));
  CHECK(text.rfind("#usda 1.0\n", 0) == 0);
  CHECK(text.find("uniform token type = \"linear\"") != std::string::npos);
  CHECK(text.find("uniform token wrap = \"nonperiodic\"") != std::string::npos);
  CHECK(text.find("metersPerUnit = 0.01") != std::string::npos);
  CHECK(text.find("int[] curveVertexCounts = [4, 7, 10]") != std::string::npos);
  const std::size_t points_at = text.find("point3f[] points = [");
  REQUIRE(points_at != std::string::npos);
  const std::string points = text.substr(points_at + 20, text.find(']', points_at + 20) - points_at - 20);
  CHECK(std::count(points.begin(), points.end(), '(') == static_cast<long>(c.points.size()));
  const std::size_t widths_at = text.find("float[] widths = [");
  const std::string widths = text.substr(widths_at + 18, text.find(']', widths_at + 18) - widths_at - 18);
  CHECK(std::count(widths.begin(), widths.end(), ',') + 1 == static_cast<long>(c.points.size()));
  CHECK(text.find("interpolation = \"vertex\"") != std::string::npos);
  CHECK(text.find("int[] primvars:guide = [10, 11, 12]") != std::string::npos);
  CHECK(text.find("float3[] extent = [(") != std::string::npos);
}

TEST_CASE("PLY: vertex and edge elements with the right counts and byte size") {
  const Curves c = sample_curves(false);
  write_ply_curves(temp("c.ply"), c);
  const std::string bytes = slurp(temp("c.ply"));
  const std::size_t end = bytes.find("end_header\n");
  REQUIRE(end != std::string::npos);
  const std::string header = bytes.substr(0, end);
  const std::size_t edges = c.points.size() - c.count();
  CHECK(header.find("format binary_little_endian 1.0") != std::string::npos);
  CHECK(header.find("element vertex " + std::to_string(c.points.size())) != std::string::npos);
  CHECK(header.find("element edge " + std::to_string(edges)) != std::string::npos);
  CHECK(bytes.size() - (end + 11) == 16 * c.points.size() + 8 * edges);
  // The first edge joins vertices 0 and 1, and the guide id of vertex 0 is 10.
  std::int32_t first_edge[2], guide0;
  std::memcpy(first_edge, bytes.data() + end + 11 + 16 * c.points.size(), 8);
  std::memcpy(&guide0, bytes.data() + end + 11 + 12, 4);
  CHECK(first_edge[0] == 0);
  CHECK(first_edge[1] == 1);
  CHECK(guide0 == 10);
}

TEST_CASE("a writer that fails leaves no file and keeps the previous one") {
  Curves c = sample_curves(false);
  const fs::path p = temp("keep.hair");
  write_hair_file(p, c);
  const std::string before = slurp(p);
  c.points[2].y() = std::nan("");
  CHECK_THROWS(write_hair_file(p, c));
  CHECK_THROWS(write_obj_curves(temp("never.obj"), c));
  CHECK(slurp(p) == before);
  CHECK_FALSE(fs::exists(temp("never.obj")));
}
