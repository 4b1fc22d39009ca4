#include "cdi/diagnostic.hpp"

#include <algorithm>

namespace olcb::cdi {

bool has_errors(const Diagnostics& diagnostics) {
    return std::any_of(diagnostics.begin(), diagnostics.end(),
                       [](const Diagnostic& d) { return d.severity == Severity::kError; });
}

std::string format_diagnostic(const std::string& file, const Diagnostic& diagnostic) {
    std::string out = file;
    if (diagnostic.line != 0) out += ":" + std::to_string(diagnostic.line);
    out += diagnostic.severity == Severity::kError ? ": error: " : ": warning: ";
    out += diagnostic.message;
    return out;
}

std::string located(const Diagnostic& diagnostic) {
    if (diagnostic.line == 0) return diagnostic.message;
    return "line " + std::to_string(diagnostic.line) + ": " + diagnostic.message;
}

}  // namespace olcb::cdi
