#include "reference/round_trip_scene.h"

#include <sstream>

namespace hairfit {

namespace {

std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string toml_vector(const Vec3& v) {
  std::ostringstream out;
  out.precision(17);
  out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return out.str();
}

}  // namespace

std::string round_trip_scene_text(const RoundTripScene& s) {
  std::ostringstream out;
  out.precision(17);
  out << "# The round trip against reference hair (issue 47): the hull voxelised from the reference,\n"
         "# every hair key at its default but the guides and the hairs per cm².\n"
         "format = \"hairfit-scene/1\"\n"
      << "seed = " << s.seed << "\n\n"
      << "[units]\nlength = \"cm\"\ndown = " << toml_vector(s.down) << "\nfront = " << toml_vector(s.front) << "\n\n"
      << "[inputs]\nscalp = " << toml_string(s.scalp) << "\nvolume = " << toml_string(s.volume) << "\n\n"
      << "[hair]\ndensity = " << s.density << "\n\n"
      << "[roots]\nguides = " << s.guides << "\n\n"
      << "[output]\nstrands = [\"hair\"]\nrenders = []\n";
  return out.str();
}

}  // namespace hairfit
