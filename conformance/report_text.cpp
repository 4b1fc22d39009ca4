// The text report: a line per check for people, colour on a terminal.
#include <ostream>

#include "conformance/report.hpp"

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

namespace {

// Length of the valid UTF-8 sequence at the start of text, 0 when it is not one.
std::size_t utf8_sequence(std::string_view text) {
    const auto b = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
    const unsigned char lead = b(0);
    std::size_t n = 0;
    unsigned min = 0;
    if (lead < 0x80) return 1;
    if (lead >= 0xC2 && lead <= 0xDF)
        n = 2, min = 0x80;
    else if (lead >= 0xE0 && lead <= 0xEF)
        n = 3, min = 0x800;
    else if (lead >= 0xF0 && lead <= 0xF4)
        n = 4, min = 0x10000;
    else
        return 0;
    if (text.size() < n) return 0;
    unsigned cp = lead & (0x7F >> n);
    for (std::size_t i = 1; i < n; ++i) {
        if ((b(i) & 0xC0) != 0x80) return 0;
        cp = (cp << 6) | (b(i) & 0x3F);
    }
    const bool surrogate = cp >= 0xD800 && cp <= 0xDFFF;
    return cp < min || cp > 0x10FFFF || surrogate ? 0 : n;
}

}  // namespace

std::string printable(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    while (!text.empty()) {
        const std::size_t n = utf8_sequence(text);
        if (n == 0) {
            out += "\xEF\xBF\xBD";  // U+FFFD for a byte that starts no valid sequence
            text.remove_prefix(1);
            continue;
        }
        const auto c = static_cast<unsigned char>(text[0]);
        if (n == 1)
            out.push_back(c < 0x20 || c == 0x7F ? '?' : static_cast<char>(c));
        else
            out.append(text.substr(0, n));
        text.remove_prefix(n);
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
    out << '\n';
    out << "timing: " << report.timing.describe() << '\n';
    for (const CheckResult& c : report.checks) out << format_check(c, colour) << '\n';
    if (!report.restore_summary.empty()) out << "restore: " << report.restore_summary << '\n';
    Summary s = summarize({report});
    out << s.total() << " checks: " << s.pass << " passed, " << s.fail << " failed, " << s.warn
        << " warnings, " << s.skip << " skipped\n";
}

}  // namespace olcb::conform
