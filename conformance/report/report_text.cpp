// The text report: a line per check for people, colour on a terminal; and how node-supplied
// bytes are shown in every report (untrusted: any bytes at all may come).
#include <algorithm>
#include <ostream>
#include <span>

#include "base/utf8.hpp"
#include "conformance/link/memory_access.hpp"
#include "conformance/report/report.hpp"

namespace olcb::conform {
namespace {

const char* colour_of(Status status) {
    switch (status) {
        case Status::kPass:
            return "\033[32m";
        case Status::kFail:
            return "\033[31m";
        case Status::kWarn:
            return "\033[33m";
        case Status::kSkip:
            return "\033[36m";
    }
    return "";
}

}  // namespace

std::string show_node_text(std::string_view text, bool quote, std::size_t max_bytes) {
    const std::string_view shown = base::truncate_utf8(text, max_bytes);
    const std::string safe = printable(shown);
    std::string out = quote ? "\"" : "";
    out += safe;
    if (shown.size() < text.size()) out += "...";
    if (quote) out += "\"";
    if (safe != shown) {
        const std::span<const std::uint8_t> bytes(
            reinterpret_cast<const std::uint8_t*>(shown.data()), shown.size());
        out += " (bytes " + hex_bytes(bytes, bytes.size()) + ")";
    }
    return out;
}

std::string format_check(const CheckResult& check, bool colour) {
    std::string line;
    if (colour) line += colour_of(check.status);
    line += status_name(check.status);
    if (colour) line += "\033[0m";
    line += "  " + check.id;
    if (!check.message.empty()) line += "  " + printable(check.message);
    if (check.status == Status::kFail || check.status == Status::kWarn) {
        if (!check.expected.empty()) line += "\n      expected: " + printable(check.expected);
        if (!check.seen.empty()) line += "\n      seen:     " + printable(check.seen);
        if (!check.section.empty()) line += "\n      section:  " + check.section;
    }
    // Details (every CDI error, every merged result) under the line, the first few only.
    constexpr std::size_t kShown = 10;
    for (std::size_t i = 0; i < check.details.size() && i < kShown; ++i)
        line += "\n      - " + printable(check.details[i]);
    if (check.details.size() > kShown)
        line +=
            "\n      ... " + std::to_string(check.details.size() - kShown) + " more (see --json)";
    return line;
}

std::string_view depends_on(const CheckResult& check) {
    constexpr std::string_view kPrefix = "depends on ";
    const std::string_view m = check.message;
    if (check.status != Status::kSkip || !m.starts_with(kPrefix)) return {};
    const std::string_view rest = m.substr(kPrefix.size());
    return rest.substr(0, rest.find_first_of(": "));
}

namespace {

bool is_finding(const CheckResult& c) {
    return c.status == Status::kFail || c.status == Status::kWarn;
}

// For each check, the index of the FAIL or WARN its "depends on" chain ends at (npos for none):
// a consequence is shown under its cause, so the cause is read first and once.
std::vector<std::size_t> causes_of(const std::vector<CheckResult>& checks) {
    constexpr std::size_t kNone = std::string::npos;
    std::vector<std::size_t> cause(checks.size(), kNone);
    for (std::size_t i = 0; i < checks.size(); ++i) {
        std::size_t at = i;
        // Bounded: a chain that loops (it should not) ends after one step per check.
        for (std::size_t steps = 0; steps < checks.size(); ++steps) {
            const std::string_view id = depends_on(checks[at]);
            if (id.empty()) break;
            const auto next = std::find_if(checks.begin(), checks.end(),
                                           [&](const CheckResult& c) { return c.id == id; });
            if (next == checks.end()) break;
            at = static_cast<std::size_t>(next - checks.begin());
            if (is_finding(*next)) {
                cause[i] = at;
                break;
            }
        }
    }
    return cause;
}

std::string status_word(Status status, bool colour) {
    if (!colour) return std::string(status_name(status));
    return colour_of(status) + std::string(status_name(status)) + "\033[0m";
}

void write_header(std::ostream& out, const NodeReport& report) {
    out << "node " << report.node_id;
    if (!report.name.empty()) out << "  " << printable(report.name);
    // The raw bytes of each SNIP string the header had to change, so nothing is hidden.
    const NodeIdentity& id = report.identity;
    const std::pair<const char*, const std::string*> shown[] = {
        {"manufacturer", &id.manufacturer}, {"model", &id.model}, {"user name", &id.user_name}};
    for (const auto& [label, text] : shown) {
        if (printable(*text) == *text) continue;
        const std::span<const std::uint8_t> bytes(
            reinterpret_cast<const std::uint8_t*>(text->data()), text->size());
        out << " (" << label << " bytes " << hex_bytes(bytes, bytes.size()) << ")";
    }
    out << '\n';
    if (report.scope != "configurable") out << "scope: " << printable(report.scope) << '\n';
    out << "timing: " << report.timing.describe() << '\n';
}

// Every FAIL and WARN, each with the SKIPs its failure left unjudged under it; the "depends on
// <cause>: " that names the cause again is left out there.
void write_findings(std::ostream& out, const NodeReport& report,
                    const std::vector<std::size_t>& cause, bool colour) {
    const std::vector<CheckResult>& checks = report.checks;
    for (std::size_t i = 0; i < checks.size(); ++i) {
        if (!is_finding(checks[i])) continue;
        out << format_check(checks[i], colour) << '\n';
        for (std::size_t j = 0; j < checks.size(); ++j) {
            if (cause[j] != i) continue;
            std::string why = checks[j].message;
            const std::string direct = "depends on " + checks[i].id + ": ";
            if (why.starts_with(direct)) why = why.substr(direct.size());
            out << "      " << status_word(Status::kSkip, colour) << "  " << checks[j].id << "  "
                << printable(why) << '\n';
        }
    }
}

// The passes as one block of IDs, wrapped at 100 columns under the first line.
void write_passes(std::ostream& out, const NodeReport& report, bool colour) {
    const std::size_t passed = report.count(Status::kPass);
    if (passed == 0) return;
    constexpr std::size_t kWidth = 100;
    constexpr std::string_view kIndent = "      ";
    std::string line = std::string(status_name(Status::kPass)) + "  " + std::to_string(passed) +
                       (passed == 1 ? " check:" : " checks:");
    out << status_word(Status::kPass, colour) << line.substr(4);
    std::size_t width = line.size();
    for (const CheckResult& c : report.checks) {
        if (c.status != Status::kPass) continue;
        if (width + 1 + c.id.size() > kWidth) {
            out << '\n' << kIndent << c.id;
            width = kIndent.size() + c.id.size();
        } else {
            out << ' ' << c.id;
            width += 1 + c.id.size();
        }
    }
    out << '\n';
}

void write_ids(std::ostream& out, const char* label, const NodeReport& report, Status status) {
    if (report.count(status) == 0) return;
    out << label << ':';
    for (const CheckResult& c : report.checks)
        if (c.status == status) out << ' ' << c.id;
    out << '\n';
}

void write_summary(std::ostream& out, const NodeReport& report, bool quiet) {
    if (!report.restore_summary.empty()) out << "restore: " << report.restore_summary << '\n';
    for (const std::string& why : report.incomplete_reasons)
        out << "INCOMPLETE: " << printable(why) << '\n';
    const Summary s = summarize({report});
    out << s.total() << " checks: " << s.pass << " passed, " << s.fail << " failed, " << s.warn
        << " warnings, " << s.skip << " skipped\n";
    write_ids(out, "failed", report, Status::kFail);
    write_ids(out, "warnings", report, Status::kWarn);
    if (quiet) return;
    for (const std::string& what : report.not_tested) out << what << '\n';
}

}  // namespace

void write_text(std::ostream& out, const NodeReport& report, TextStyle style) {
    const bool quiet = style.detail == TextDetail::kQuiet;
    if (quiet) {
        out << "node " << report.node_id << '\n';
    } else {
        write_header(out, report);
    }
    const std::vector<std::size_t> cause = causes_of(report.checks);
    write_findings(out, report, cause, style.colour);
    if (style.detail == TextDetail::kFull) {
        write_passes(out, report, style.colour);
        for (std::size_t i = 0; i < report.checks.size(); ++i) {
            const CheckResult& c = report.checks[i];
            if (c.status == Status::kSkip && cause[i] == std::string::npos)
                out << format_check(c, style.colour) << '\n';
        }
    }
    write_summary(out, report, quiet);
}

}  // namespace olcb::conform
