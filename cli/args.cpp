#include "args.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace hairfit::cli {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& valued, const std::set<std::string>& flags) {
  auto known = [&] {
    std::string list;
    for (const auto* set : {&valued, &flags})
      for (const std::string& o : *set) list += " --" + o;
    return list;
  };
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.size() < 3 || a.compare(0, 2, "--") != 0) {
      positionals_.push_back(a);
      continue;
    }
    std::string name = a.substr(2), value;
    const std::size_t eq = name.find('=');
    const bool inline_value = eq != std::string::npos;
    if (inline_value) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    if (valued.count(name)) {
      if (!inline_value) {
        if (i + 1 >= argv.size()) throw UsageError{"--" + name + " needs a value"};
        value = argv[++i];
      }
    } else if (flags.count(name)) {
      if (inline_value) throw UsageError{"--" + name + " takes no value"};
    } else {
      throw UsageError{"unknown option --" + name + "; valid options:" + known()};
    }
    options_[name] = value;
  }
}

std::optional<std::string> Args::text(const std::string& name) const {
  const auto it = options_.find(name);
  if (it == options_.end()) return std::nullopt;
  return it->second;
}

static double parse_number(const std::string& name, const std::string& text) {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(x))
    throw UsageError{"--" + name + " needs a finite number, not \"" + text + "\""};
  return x;
}

double Args::number(const std::string& name, double fallback) const {
  const auto t = text(name);
  return t ? parse_number(name, *t) : fallback;
}

int Args::integer(const std::string& name, int fallback) const {
  const auto t = text(name);
  if (!t) return fallback;
  const double x = parse_number(name, *t);
  if (x != std::floor(x) || std::fabs(x) > 2e9) throw UsageError{"--" + name + " needs an integer, not \"" + *t + "\""};
  return static_cast<int>(x);
}

Vec3 Args::vector3(const std::string& name, const Vec3& fallback) const {
  const auto t = text(name);
  if (!t) return fallback;
  std::stringstream in(*t);
  std::string part;
  std::vector<double> parts;
  while (std::getline(in, part, ',')) parts.push_back(parse_number(name, part));
  if (parts.size() != 3) throw UsageError{"--" + name + " needs three comma-separated numbers x,y,z, not \"" + *t + "\""};
  return Vec3(parts[0], parts[1], parts[2]);
}

}  // namespace hairfit::cli
