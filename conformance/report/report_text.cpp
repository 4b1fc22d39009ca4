// The text report: a line per check for people, colour on a terminal; and how node-supplied
// bytes are shown in every report (untrusted: any bytes at all may come).
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

void write_text(std::ostream& out, const NodeReport& report, bool colour) {
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
    out << "timing: " << report.timing.describe() << '\n';
    for (const CheckResult& c : report.checks) out << format_check(c, colour) << '\n';
    if (!report.restore_summary.empty()) out << "restore: " << report.restore_summary << '\n';
    for (const std::string& why : report.incomplete_reasons)
        out << "INCOMPLETE: " << printable(why) << '\n';
    Summary s = summarize({report});
    out << s.total() << " checks: " << s.pass << " passed, " << s.fail << " failed, " << s.warn
        << " warnings, " << s.skip << " skipped\n";
    for (const std::string& what : report.not_tested) out << what << '\n';
}

}  // namespace olcb::conform
