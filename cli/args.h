// Command-line arguments of one subcommand: positionals and --options. Both "--name value" and
// "--name=value" are accepted; the second form lets values start with '-' (negative numbers).
#pragma once
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/types.h"

namespace hairfit::cli {

// Raised for unusable arguments; main prints it and exits with code 2.
struct UsageError {
  std::string message;
};

class Args {
 public:
  // `valued` lists the options that take a value, `flags` those that do not.
  Args(const std::vector<std::string>& argv, const std::set<std::string>& valued, const std::set<std::string>& flags);

  const std::vector<std::string>& positionals() const { return positionals_; }
  bool has(const std::string& name) const { return options_.count(name) > 0; }
  std::optional<std::string> text(const std::string& name) const;
  double number(const std::string& name, double fallback) const;
  int integer(const std::string& name, int fallback) const;
  Vec3 vector3(const std::string& name, const Vec3& fallback) const;

 private:
  std::vector<std::string> positionals_;
  std::map<std::string, std::string> options_;
};

}  // namespace hairfit::cli
