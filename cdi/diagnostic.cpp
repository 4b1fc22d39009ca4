#include "cdi/diagnostic.hpp"

#include <algorithm>
#include <iterator>
#include <utility>

#include "base/run_sort.hpp"

namespace olcb::cdi {

void append(Diagnostics& out, Diagnostics&& more) {
    out.insert(out.end(), std::make_move_iterator(more.begin()),
               std::make_move_iterator(more.end()));
    more.clear();
}

bool has_errors(const Diagnostics& diagnostics) {
    return std::any_of(diagnostics.begin(), diagnostics.end(),
                       [](const Diagnostic& d) { return d.severity == Severity::kError; });
}

void sort_and_dedupe(Diagnostics& diagnostics) {
    base::run_sort(diagnostics.begin(), diagnostics.end(),
                   [](const Diagnostic& a, const Diagnostic& b) { return a.line < b.line; });
    Diagnostics unique;
    unique.reserve(diagnostics.size());
    for (Diagnostic& d : diagnostics) {
        bool repeat = false;
        for (auto u = unique.rbegin(); u != unique.rend() && u->line == d.line && !repeat; ++u) {
            repeat = u->severity == d.severity && u->message == d.message;
        }
        if (!repeat) unique.push_back(std::move(d));
    }
    diagnostics = std::move(unique);
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

std::string quoted_excerpt(std::string_view text) {
    constexpr std::size_t kMaxShown = 40;
    std::string out = "'";
    out += text.substr(0, kMaxShown);
    if (text.size() > kMaxShown) out += "...";
    out += "'";
    return out;
}

}  // namespace olcb::cdi
