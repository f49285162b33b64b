// Errors a user can fix (bad scene, bad mesh, bad map) carry where they come from, in the style of
// a compiler diagnostic: "scene.toml:14:3: error: ...". They map to exit code 2; every other
// exception is an internal error (exit code 1).
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

namespace hairfit {

// A place in an input file. line and column are 1-based; 0 means "the whole file".
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
};

struct Diagnostic {
  SourceLocation where;
  std::string message;      // what is wrong, naming the key or item and the offending value
  std::string source_line;  // the text of the offending line, when there is one
};

// "file:line:col: error: message" followed by the source line and a caret under the column.
std::string format_diagnostic(const Diagnostic& d);

// One or more problems with the user's input; what() is all of them, formatted.
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<Diagnostic> diagnostics);
  InputError(const std::string& file, const std::string& message);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

}  // namespace hairfit
