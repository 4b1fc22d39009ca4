// Errors and warnings about a CDI, with the source line they refer to.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace olcb::cdi {

/// Errors make a CDI unusable or non-conforming; warnings flag legal-but-suspect content.
enum class Severity : std::uint8_t { kError, kWarning };

/// One finding about a CDI: severity, 1-based source line (0 = whole document), message.
struct Diagnostic {
    Severity severity = Severity::kError;
    std::uint32_t line = 0;
    std::string message;
};

/// The findings of one pass over a document, in document order.
using Diagnostics = std::vector<Diagnostic>;

/// Moves every finding of `more` to the end of `out`.
void append(Diagnostics& out, Diagnostics&& more);

/// True when any finding is an error.
bool has_errors(const Diagnostics& diagnostics);

/// "FILE:LINE: error: message" (or "FILE: error: message" when the line is 0).
std::string format_diagnostic(const std::string& file, const Diagnostic& diagnostic);

/// "line 4: message" ("message" when the line is 0): a diagnostic quoted inside another report.
std::string located(const Diagnostic& diagnostic);

}  // namespace olcb::cdi
