#include "core/error.h"

namespace hairfit {

std::string format_diagnostic(const Diagnostic& d) {
  std::string out = d.where.file;
  if (d.where.line > 0) {
    out += ':' + std::to_string(d.where.line);
    if (d.where.column > 0) out += ':' + std::to_string(d.where.column);
  }
  out += ": error: " + d.message;
  if (!d.source_line.empty()) {
    out += "\n    " + d.source_line;
    if (d.where.column > 0) out += "\n    " + std::string(d.where.column - 1, ' ') + '^';
  }
  return out;
}

static std::string join(const std::vector<Diagnostic>& diagnostics) {
  std::string out;
  for (const Diagnostic& d : diagnostics) {
    if (!out.empty()) out += '\n';
    out += format_diagnostic(d);
  }
  return out;
}

InputError::InputError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(join(diagnostics)), diagnostics_(std::move(diagnostics)) {}

InputError::InputError(const std::string& file, const std::string& message)
    : InputError(std::vector<Diagnostic>{Diagnostic{SourceLocation{file, 0, 0}, message, std::string()}}) {}

}  // namespace hairfit
