#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <unistd.h>

#include "core/error.h"
#include "core/random.h"
#include "io/atomic_file.h"
#include "io/obj_mesh.h"
#include "io/png_chunks.h"
#include "io/png_image.h"
#include "io/png_map.h"
#include "../support/run_hairfit.h"
#include "../support/scratch.h"

using namespace hairfit;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir() {
  const fs::path dir = hairfit::testing::scratch_path("io");
  fs::create_directories(dir);
  return dir;
}

fs::path write(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("OBJ: quads are triangulated, units scaled, duplicates welded, degenerate faces dropped") {
  const fs::path p = write("quad.obj",
                           "# a unit square as one quad, a duplicate of vertex 1 and a zero-area triangle\n"
                           "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 0\nv 2 0 0\n"
                           "f 1 2 3 4\nf 5 2 6\n");
  const LoadedMesh m = load_obj_mesh(p, 10.0);
  CHECK(m.file_vertices == 6);
  CHECK(m.file_faces == 2);
  CHECK(m.mesh.triangles.size() == 2);
  CHECK(m.welded_duplicates == 1);
  CHECK(m.dropped_degenerate == 1);
  CHECK(m.unused_vertices == 1);  // vertex 6 only served the degenerate triangle
  CHECK(m.mesh.positions.size() == 4);
  CHECK(surface_area(m.mesh) == doctest::Approx(100.0));  // 10 × 10 cm
}

TEST_CASE("OBJ: welded duplicates keep the order of first appearance and the first one's colour") {
  // Vertices 1, 4 and 6 are one point (6 written as -0), 2 and 5 another; the welded vertices run
  // in the order their first copies appear, each with its first copy's colour.
  const fs::path p = write("dupes.obj",
                           "v 1 0 0 1 0 0\nv 0 1 0 0 1 0\nv 0 0 1 0 0 1\nv 1 0 0 0.5 0.5 0.5\n"
                           "v 0 1 0 0.2 0.2 0.2\nv 1 -0 0 0.9 0.9 0.9\nv 0 0 2 1 1 0\n"
                           "f 1 2 3\nf 4 5 7\nf 6 3 5\n");
  const LoadedMesh m = load_obj_mesh(p);
  CHECK(m.welded_duplicates == 3);
  REQUIRE(m.mesh.positions.size() == 4);
  CHECK(m.mesh.positions[0] == Vec3(1, 0, 0));
  CHECK(m.mesh.positions[1] == Vec3(0, 1, 0));
  CHECK(m.mesh.positions[2] == Vec3(0, 0, 1));
  CHECK(m.mesh.positions[3] == Vec3(0, 0, 2));
  REQUIRE(m.colors.size() == 4);
  CHECK(m.colors[0] == Vec3(1, 0, 0));
  CHECK(m.colors[1] == Vec3(0, 1, 0));
  REQUIRE(m.mesh.triangles.size() == 3);
  CHECK(m.mesh.triangles[1] == Vec3i(0, 1, 3));
  CHECK(m.mesh.triangles[2] == Vec3i(0, 2, 1));
}

TEST_CASE("OBJ: negative (relative) indices") {
  const LoadedMesh m = load_obj_mesh(write("rel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"));
  CHECK(m.mesh.triangles.size() == 1);
}

TEST_CASE("OBJ: statements other than v and f are ignored, however odd (a fuzzed vw line overflowed the reader)") {
  const LoadedMesh m = load_obj_mesh(write("odd.obj", "mtllib missing.mtl\no part\nvw 2 1e15 3\nvt 0.5 0.5\n"
                                                     "vn 0 0 1\ng group\nusemtl none\ns 1\nv 0 0 0\nv 1 0 0\n"
                                                     "v 0 1 0\nl 1 2\nf 1 2 3\n"));
  CHECK(m.mesh.triangles.size() == 1);
  CHECK(m.mesh.positions.size() == 3);
  // Faces naming texture coordinates and normals still read (those are ignored too).
  const LoadedMesh uv = load_obj_mesh(write("uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvn 0 0 1\n"
                                                      "f 1/1/1 2/2/1 3/1/1\nf 1//1 3//1 2//1\n"));
  CHECK(uv.mesh.triangles.size() == 2);
}

TEST_CASE("OBJ errors name the file, the line and the fix") {
  CHECK(error_of([] { load_obj_mesh("/nonexistent/x.obj"); }).find("/nonexistent/x.obj: error: no such file") == 0);
  CHECK(error_of([] { load_obj_mesh(temp_dir()); }).find("is a folder") != std::string::npos);
  const fs::path nan = write("nan.obj", "v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n");
  CHECK(error_of([&] { load_obj_mesh(nan); }).find(nan.string() + ":2:7: error: vertex 2 has a non-finite") == 0);
  const fs::path range = write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  CHECK(error_of([&] { load_obj_mesh(range); }).find(":4:7: error: face refers to vertex 4 but the file has 3 vertices") !=
        std::string::npos);
  CHECK(error_of([&] { load_obj_mesh(write("empty.obj", "# nothing\n")); }).find("has no vertices") != std::string::npos);
  CHECK(error_of([&] { load_obj_mesh(write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n")); })
            .find("no triangle of non-zero area") != std::string::npos);
  CHECK(error_of([&] { load_obj_mesh(write("bin.obj", std::string("v 0\0\x01\x02 binary", 14))); })
            .find("is a binary file") != std::string::npos);
  CHECK(error_of([&] { load_obj_mesh(write("short.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")); })
            .find("fewer than 3 coordinates") != std::string::npos);
  // Finite as text, but beyond a double once scaled to cm: named, not welded as inf.
  CHECK(error_of([&] { load_obj_mesh(write("huge.obj", "v 0 0 0\nv 1e307 0 0\nv 0 1 0\nf 1 2 3\n"), 100.0); })
            .find("vertex 2 is beyond the range of numbers once scaled to cm") != std::string::npos);
}

TEST_CASE("OBJ coordinates far from the origin are read as the doubles nearest their text") {
  // 4·10⁵ cm from the origin a float's step is 0.03 cm: these three vertices 10⁻⁴ cm apart would
  // collapse into one and the triangle be dropped. Each coordinate is the double strtod gives.
  const std::string x0 = "400000.0001", x1 = "400000.0002", y = "-123456.78901234", z = "0.1";
  const LoadedMesh m = load_obj_mesh(write("far.obj", "v " + x0 + " " + y + " " + z + "\nv " + x1 + " " + y + " " + z +
                                                          "\nv " + x0 + " -123456.78891234 " + z + "\nf 1 2 3\n"));
  REQUIRE(m.mesh.positions.size() == 3);
  CHECK(m.dropped_degenerate == 0);
  CHECK(m.mesh.positions[0] == Vec3(std::strtod(x0.c_str(), nullptr), std::strtod(y.c_str(), nullptr), 0.1));
  CHECK(m.mesh.positions[1].x() == std::strtod(x1.c_str(), nullptr));
  CHECK(m.mesh.positions[2].y() == std::strtod("-123456.78891234", nullptr));
  // Text without an exact float: 0.1 is read as the double 0.1, not the float 0.1f.
  CHECK(m.mesh.positions[0].z() != static_cast<double>(0.1f));
}

TEST_CASE("OBJ writing keeps a far mesh's resolution relative to its size") {
  // The same small triangle about the origin and 10⁴ of its sizes away: both written, read back
  // within 10⁻⁸ of their size (9 digits about the origin, 13 far away).
  Mesh near;
  near.positions = {Vec3(0.123456789123, 1.0, 2.0), Vec3(3.0, -2.987654321987, 1.0), Vec3(-1.0, 0.5, 2.000000123)};
  near.triangles = {Vec3i(0, 1, 2)};
  Mesh far = near;
  const Vec3 shift(6.0e4, -4.0e4, 2.5e4);
  for (Vec3& p : far.positions) p += shift;
  const fs::path near_file = temp_dir() / "near.obj", far_file = temp_dir() / "far_written.obj";
  write_obj_mesh(near_file, near);
  write_obj_mesh(far_file, far);
  const LoadedMesh near_back = load_obj_mesh(near_file), far_back = load_obj_mesh(far_file);
  for (int v = 0; v < 3; ++v) {
    CHECK((near_back.mesh.positions[v] - near.positions[v]).norm() < 1e-8 * 6.0);
    CHECK((far_back.mesh.positions[v] - far.positions[v]).norm() < 1e-8 * 6.0);
  }
  // The mesh about the origin is written as before: %.9g.
  CHECK(hairfit::testing::read_all(near_file.string()).substr(0, 30) == "v 0.123456789 1 2\nv 3 -2.98765");
}

TEST_CASE("OBJ write → read round trip keeps positions and triangles") {
  Mesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1.25, 0, 0), Vec3(0, 2.5, -1)};
  m.triangles = {Vec3i(0, 1, 2)};
  const fs::path p = temp_dir() / "round.obj";
  write_obj_mesh(p, m, {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)});
  const LoadedMesh back = load_obj_mesh(p);
  CHECK(back.mesh.positions == m.positions);
  CHECK(back.mesh.triangles == m.triangles);
}

TEST_CASE("PNG maps: 8-bit grey round trip and bilinear sampling") {
  GreyMap map;
  map.width = 2;
  map.height = 1;
  map.values = {0.0f, 1.0f};
  const fs::path p = temp_dir() / "ramp.png";
  write_grey_png(p, map);
  const GreyMap back = load_grey_map(p);
  CHECK(back.width == 2);
  CHECK(back.height == 1);
  CHECK(back.bits == 8);
  CHECK(back.values == map.values);
  CHECK(back.sample(Vec2(0.25, 0.5)) == doctest::Approx(0.0));  // pixel centre
  CHECK(back.sample(Vec2(0.5, 0.5)) == doctest::Approx(0.5));   // halfway between centres
  CHECK(back.sample(Vec2(-3, 9)) == doctest::Approx(0.0));      // clamped to the edge
}

TEST_CASE("PNG errors: missing, not a PNG, corrupt") {
  CHECK(error_of([] { load_grey_map("/nonexistent/m.png"); }).find("no such file") != std::string::npos);
  CHECK(error_of([&] { load_grey_map(write("text.png", "hello")); }).find("is not a PNG file") != std::string::npos);
  CHECK(error_of([&] { load_grey_map(write("bad.png", std::string("\x89PNG\r\n\x1a\n", 8) + "garbage")); })
            .find("is a corrupt PNG") != std::string::npos);
}

TEST_CASE("PNG chunks: zero-length IDAT chunks are dropped (stb_image memcpys into null for a leading one), nothing else") {
  Image image = make_image(3, 2, 10, 20, 30);
  image.rgba[4] = 200;
  const std::vector<std::uint8_t> encoded = encode_png(image);
  const std::string png(encoded.begin(), encoded.end());
  const std::string empty_idat("\0\0\0\0IDAT\x35\xaf\x06\x1e", 12);  // length 0, type, CRC-32 of "IDAT"
  constexpr std::size_t kAfterHeader = 8 + 12 + 13;                         // signature, IHDR chunk
  REQUIRE(png.compare(kAfterHeader + 4, 4, "IDAT") == 0);
  std::string padded = png;
  padded.insert(kAfterHeader, empty_idat);                 // before the data: the case stb mishandles
  padded.insert(padded.size() - 12, empty_idat);           // and one before IEND
  CHECK(without_empty_idat_chunks(padded) == png);
  CHECK(without_empty_idat_chunks(png) == png);
  // A length running past the end stops the pass; the rest is kept for stb to call corrupt.
  const std::string truncated = png.substr(0, kAfterHeader) + empty_idat + std::string("\0\0\1\0IDATabc", 11);
  CHECK(without_empty_idat_chunks(truncated) == png.substr(0, kAfterHeader) + std::string("\0\0\1\0IDATabc", 11));
  CHECK(without_empty_idat_chunks("\x89PNG") == "\x89PNG");
  // A zero-length IDAT at the end whose CRC is cut off (the fuzzer's find) goes too.
  CHECK(without_empty_idat_chunks(png.substr(0, kAfterHeader) + empty_idat.substr(0, 11)) == png.substr(0, kAfterHeader));
  // Both loaders decode the padded file to the same pixels.
  const Image back = load_png_image(write("padded.png", padded));
  CHECK(back.width == 3);
  CHECK(back.rgba == image.rgba);
}

TEST_CASE("atomic writes leave the old file intact when writing fails") {
  const fs::path p = temp_dir() / "keep.txt";
  write_text_file_atomically(p, "old");
  CHECK_THROWS(write_file_atomically(p, [](std::ostream& out) {
    out << "half";
    throw std::runtime_error("interrupted");
  }));
  std::ifstream in(p);
  std::string text;
  in >> text;
  CHECK(text == "old");
  for (const auto& entry : fs::directory_iterator(temp_dir()))
    CHECK(entry.path().filename().string().find(".tmp-") == std::string::npos);
}

TEST_CASE("an atomic write to a folder's path is refused by name and leaves the folder as it was") {
  const fs::path dir = temp_dir() / "a-folder";
  fs::create_directories(dir);
  CHECK_THROWS_WITH_AS(write_text_file_atomically(dir, "text"), doctest::Contains("is a folder; name the file"), InputError);
  CHECK(fs::is_directory(dir));
  for (const auto& entry : fs::directory_iterator(temp_dir()))
    CHECK(entry.path().filename().string().find(".tmp-") == std::string::npos);
}

TEST_CASE("OBJ: a face entry is refused exactly when it is not v, v/vt, v//vn or v/vt/vn with integers") {
  // The reader's scan against the regular expression it replaced, on random short entries.
  const std::regex face_token("-?[0-9]+(/(-?[0-9]+)?(/-?[0-9]+)?)?");
  const char alphabet[] = "-/0123/1x";
  Random r(9, RandomStage::test, 0);
  int refused = 0, accepted = 0;
  for (int n = 0; n < 1500; ++n) {
    std::string token;
    const int length = 1 + static_cast<int>(r.uniform(0, 7));
    for (int i = 0; i < length; ++i) token += alphabet[static_cast<int>(r.uniform(0, sizeof alphabet - 1))];
    const std::string error =
        error_of([&] { load_obj_mesh(write("token.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 " + token + "\n")); });
    const bool refused_as_token = error.find("is not a vertex index") != std::string::npos;
    CHECK_MESSAGE(refused_as_token == !std::regex_match(token, face_token), token);
    refused += refused_as_token;
    accepted += !refused_as_token;
  }
  CHECK(refused > 300);
  CHECK(accepted > 300);
}
