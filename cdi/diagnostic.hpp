// Errors and warnings about a CDI, with the source line they refer to.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
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

/// Sorts by line (stable, so each pass keeps its own order within a line; each pass reports in
/// document order, so this merges a few runs) and drops exact repeats, which arise when two
/// passes word the same finding identically: how a validator merges its passes.
void sort_and_dedupe(Diagnostics& diagnostics);

/// "FILE:LINE: error: message" (or "FILE: error: message" when the line is 0).
std::string format_diagnostic(const std::string& file, const Diagnostic& diagnostic);

/// "line 4: message" ("message" when the line is 0): a diagnostic quoted inside another report.
std::string located(const Diagnostic& diagnostic);

/// The text in single quotes for a message about it, its first 40 bytes then "..." when longer:
/// a value from the CDI or the user can be any length, a message line should not be.
std::string quoted_excerpt(std::string_view text);

}  // namespace olcb::cdi
