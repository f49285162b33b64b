// NRRD round trip and the `hairfit field` command against the in-process field.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "field/distance_field.h"
#include "io/nrrd.h"
#include "io/obj_mesh.h"
#include "test_meshes.h"
#include "../support/scratch.h"

using namespace hairfit;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  return hairfit::testing::scratch_path(name);
}

}  // namespace

TEST_CASE("NRRD: write then read gives back sizes, placement and every sample") {
  NrrdVolume v;
  v.sizes = Vec3i(3, 4, 5);
  v.origin = Vec3(-1.25, 0.1, 3.0 / 7.0);
  v.spacing = Vec3(0.25, 0.5, 1.0 / 3.0);
  for (int i = 0; i < 60; ++i) v.data.push_back(float(i * 0.37 - 7) * (i % 2 ? 1 : -1));
  v.data[7] = -0.0f;
  const fs::path path = scratch("round.nrrd");
  write_nrrd(path, v);
  const NrrdVolume w = read_nrrd(path);
  CHECK(w.sizes == v.sizes);
  CHECK(w.origin == v.origin);   // written with 17 significant digits
  CHECK(w.spacing == v.spacing);
  REQUIRE(w.data.size() == v.data.size());
  for (size_t i = 0; i < v.data.size(); ++i) CHECK(std::memcmp(&w.data[i], &v.data[i], 4) == 0);
  // The header is what ParaView/Slicer/unu need.
  std::ifstream in(path, std::ios::binary);
  std::string header((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  header = header.substr(0, header.find("\n\n"));
  CHECK(header.find("NRRD0004") == 0);
  CHECK(header.find("space: right-anterior-superior") != std::string::npos);
  CHECK(header.find("endian: little") != std::string::npos);
  CHECK(header.find("sizes: 3 4 5") != std::string::npos);
  CHECK(fs::file_size(path) == header.size() + 2 + 60 * 4);
}

TEST_CASE("NRRD: unsupported or broken files are refused with InputError") {
  const fs::path path = scratch("bad.nrrd");
  {
    std::ofstream out(path, std::ios::binary);
    out << "NRRD0004\ntype: short\ndimension: 3\nsizes: 1 1 1\nencoding: raw\n\n\x01\x02";
  }
  CHECK_THROWS_AS(read_nrrd(path), InputError);
  {
    std::ofstream out(path, std::ios::binary);
    out << "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n\x01\x02";  // too short
  }
  CHECK_THROWS_AS(read_nrrd(path), InputError);
  CHECK_THROWS_AS(read_nrrd(scratch("missing.nrrd")), InputError);
}

TEST_CASE("hairfit field writes the field as NRRD, placed in world space") {
  const Mesh mesh = test::icosphere(2, 2.0, Vec3(1, -2, 0.5));
  const fs::path obj = scratch("sphere.obj");
  const fs::path out = scratch("sphere.nrrd");
  fs::remove(out);
  write_obj_mesh(obj, mesh);
  const std::string command = std::string(HAIRFIT_BINARY) + " field " + obj.string() +
                              " --voxel 0.2 --band 3 --margin 0.6 --threads 2 --out " + out.string() + " > " +
                              scratch("log.txt").string();
  REQUIRE(std::system(command.c_str()) == 0);
  const NrrdVolume v = read_nrrd(out);

  FieldSpec spec;
  spec.voxel = 0.2;
  spec.band = 3;
  spec.margin = 0.6;
  const DistanceField f = make_distance_field(load_obj_mesh(obj).mesh, spec, 1);
  REQUIRE(v.sizes == f.dims());
  CHECK(v.origin.isApprox(f.origin(), 1e-15));
  CHECK(v.spacing == Vec3::Constant(0.2));
  int differ = 0;
  size_t at = 0;
  for (int k = 0; k < f.dims().z(); ++k)
    for (int j = 0; j < f.dims().y(); ++j)
      for (int i = 0; i < f.dims().x(); ++i) differ += v.data[at++] != float(f.sample(i, j, k));
  CHECK(differ == 0);
  // World placement: the sample nearest a point 0.4 cm outside the sphere (radius 2, in the
  // band) reads about 0.4 (within half a voxel diagonal).
  const Vec3 u = (Vec3(1, -2, 0.5) + Vec3(0, 0, 2.4) - v.origin).cwiseQuotient(v.spacing);
  const int i = int(std::lround(u.x())), j = int(std::lround(u.y())), k = int(std::lround(u.z()));
  CHECK(std::abs(v.data[i + v.sizes.x() * (j + v.sizes.y() * k)] - 0.4) < 0.18);

  // Bad input: exit code 2, no output written.
  fs::remove(out);
  const std::string bad = std::string(HAIRFIT_BINARY) + " field " + obj.string() + " --voxel 0 --band 3 --out " +
                          out.string() + " 2> /dev/null";
  CHECK(WEXITSTATUS(std::system(bad.c_str())) == 2);
  CHECK(!fs::exists(out));
}
