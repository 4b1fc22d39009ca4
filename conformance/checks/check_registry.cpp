#include "conformance/checks/check_registry.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <array>
#include <sstream>

#include "conformance/checks/checks.hpp"

namespace olcb::conform {
namespace {

using C = Category;
namespace k = checks;

std::vector<CheckSpec> build_registry() {
    std::vector<CheckSpec> all;
    for (auto family : {k::frame_checks,
                        k::message_checks,
                        k::snip_checks,
                        k::memory_checks,
                        k::cdi_checks,
                        k::datagram_checks,
                        k::acdi_checks,
                        k::pip_checks,
                        k::encoding_checks,
                        k::node_checks,
                        k::frame_bus_checks,
                        k::message_addressing_checks,
                        k::final_checks,
                        k::datagram_protocol_checks,
                        k::memory_bounds_checks,
                        k::event_checks,
                        k::event_robustness_checks,
                        k::stream_checks,
                        k::event_phase_checks,
                        k::train_control_checks,
                        k::train_search_checks,
                        k::fdi_checks,
                        k::broadcast_time_checks,
                        k::clock_consumer_checks}) {
        std::vector<CheckSpec> part = family();
        all.insert(all.end(), part.begin(), part.end());
    }
    std::stable_sort(all.begin(), all.end(),
                     [](const CheckSpec& a, const CheckSpec& b) { return a.order < b.order; });
    return all;
}

bool matches(const std::string& pattern, std::string_view id) {
    return fnmatch(pattern.c_str(), std::string(id).c_str(), 0) == 0;
}

// The result IDs an entry can produce (a per-space entry: one per space number).
template <typename F>
bool any_result_id(const CheckSpec& spec, F&& f) {
    if (!spec.id.ends_with(kPerSpace)) return f(spec.id);
    const std::string_view base = spec.id.substr(0, spec.id.size() - kPerSpace.size());
    if (f(base)) return true;
    for (unsigned sp = 0; sp <= 0xFF; ++sp) {
        if (f(std::string(base) + "." + space_suffix(static_cast<std::uint8_t>(sp)))) return true;
    }
    return false;
}

bool selected(const CheckSelection& sel, std::string_view id) {
    if (!sel.categories.empty()) {
        const std::string_view first = id.substr(0, id.find('.'));
        const bool in = std::any_of(sel.categories.begin(), sel.categories.end(),
                                    [&](Category c) { return category_name(c) == first; });
        if (!in) return false;
    }
    const auto hit = [&](const std::string& p) { return matches(p, id); };
    if (!sel.only.empty() && std::none_of(sel.only.begin(), sel.only.end(), hit)) return false;
    return std::none_of(sel.skip.begin(), sel.skip.end(), hit);
}

}  // namespace

std::string_view strength_name(Strength strength) {
    switch (strength) {
        case Strength::kShall:
            return "shall";
        case Strength::kShould:
            return "should";
        case Strength::kMay:
            return "may";
        case Strength::kNone:
            return "none";
        case Strength::kRun:
            return "run";
    }
    return "none";
}

void cite(CheckResult& result) {
    const CheckSpec* spec = find_check(result.id);
    if (spec == nullptr) return;
    result.category = spec->category;
    result.section = std::string(spec->section);
    const bool binding = spec->strength == Strength::kShall || spec->strength == Strength::kRun;
    if (binding || result.status != Status::kFail) return;
    result.status = Status::kWarn;
    // "none" is no word of the standard's: such a check has no "shall" behind it at all.
    const std::string says =
        spec->strength == Strength::kNone
            ? "no \"shall\" covers it"
            : "the standard says \"" + std::string(strength_name(spec->strength)) + "\" here";
    result.message += " (a WARN, not a FAIL: " + says + ", " + std::string(spec->section) + ")";
}

const std::vector<CheckSpec>& check_registry() {
    static const std::vector<CheckSpec> registry = build_registry();
    return registry;
}

const CheckSpec* find_check(std::string_view result_id) {
    for (const CheckSpec& spec : check_registry()) {
        if (spec.id == result_id) return &spec;
        if (!spec.id.ends_with(kPerSpace)) continue;
        const std::string_view base = spec.id.substr(0, spec.id.size() - kPerSpace.size() + 1);
        if (result_id.size() == base.size() + 2 && result_id.starts_with(base)) return &spec;
    }
    return nullptr;
}

bool is_check_pattern(std::string_view pattern) {
    static constexpr std::array<Category, 17> kAll = {
        C::kFrame,  C::kMessage, C::kPip,      C::kSnip, C::kDatagram, C::kMemory,
        C::kCdi,    C::kAcdi,    C::kEncoding, C::kLink, C::kNode,     C::kEvents,
        C::kStream, C::kTrain,   C::kSearch,   C::kFdi,  C::kClock};
    const std::string_view first = pattern.substr(0, pattern.find('.'));
    return std::any_of(kAll.begin(), kAll.end(),
                       [&](Category c) { return category_name(c) == first; });
}

bool CheckSelection::wants(const CheckSpec& spec) const {
    if (spec.thorough && !thorough) return false;
    if (spec.past_end_writes && !write_past_end) return false;
    return any_result_id(spec, [&](std::string_view id) { return selected(*this, id); });
}

bool CheckSelection::wants_id(std::string_view id) const {
    if (const CheckSpec* spec = find_check(id);
        spec && ((spec->thorough && !thorough) || (spec->past_end_writes && !write_past_end)))
        return false;
    return selected(*this, id);
}

bool CheckSelection::wants_writes() const {
    const auto& all = check_registry();
    return std::any_of(all.begin(), all.end(), [&](const CheckSpec& s) {
        return !s.run &&
               (s.category == C::kEncoding || s.category == C::kEvents ||
                s.id == "snip.follows-acdi-user-write") &&
               wants(s);
    });
}

std::string format_check_list() {
    std::ostringstream out;
    for (const CheckSpec& s : check_registry()) {
        out << s.id << "\t" << category_name(s.category) << "\t" << s.section << "\t"
            << strength_name(s.strength) << "\t" << (s.olcbchecker.empty() ? "-" : s.olcbchecker)
            << "\t" << s.summary << (s.thorough ? " [--thorough]" : "")
            << (s.past_end_writes ? " [--write-past-end]" : "") << "\n";
    }
    return out.str();
}

// A data table, one row per OlcbChecker check: its length is not complexity.
// NOLINTNEXTLINE(readability-function-size)
const std::vector<OlcbCheckerCheck>& olcbchecker_checks() {
    static const std::vector<OlcbCheckerCheck> all = {
        {"fr10", "start-up sequence after a reboot", ""},
        {"fr20", "AME answered", ""},
        {"fr30", "alias collision: CID, then another node's frame with the node's alias", ""},
        {"fr40", "AME with bit 28 clear", ""},
        {"fr50", "capacity: 300 frames back to back around an addressed Verify", ""},
        {"fr60", "2,047 standard (11-bit) frames ignored", ""},
        {"me10", "Initialization Complete after a reboot", ""},
        {"me20", "Verify Node ID global, addressed, addressed to another node", ""},
        {"me30", "Protocol Support Inquiry; to another node silence; 4th byte", ""},
        {"me40", "unknown MTI: global silence, addressed OIR, to another node silence", ""},
        {"me50", "duplicate node ID indicated", ""},
        {"me60", "PIP simple bit agrees with the Verified MTI", ""},
        {"sn10", "SNIP reply", ""},
        {"ev10", "Identify Events addressed", ""},
        {"ev20", "Identify Events global", ""},
        {"ev30", "Identify Producer", ""},
        {"ev40", "Identify Consumer", ""},
        {"ev50", "event identification after start-up",
         "not covered: needs a reboot for every run; the reboot lcc-conform makes (--reboot) is "
         "judged by frame.startup-sequence and encoding.persist-after-reboot"},
        {"ev60", "PCER with payload does not upset the node", ""},
        {"ev70", "Learn Event does not upset the node", ""},
        {"da30", "datagrams of 1, 10 and 72 bytes of no known protocol", ""},
        {"da40", "unknown datagram protocol rejected, no restart in a 30-s soak", ""},
        {"mc10", "Get Configuration Options, write-lengths byte", ""},
        {"mc20", "Get Address Space Information", ""},
        {"mc30", "reads of 2/10/64 bytes in both forms", ""},
        {"mc40", "Lock/Reserve sequence", ""},
        {"mc50", "Reset/Reboot: the node restarts", ""},
        {"mc60", "read past the end of 0xFD fails", ""},
        {"mc70", "write under mask (if advertised)", ""},
        {"mc80", "write, read back, restore one byte", ""},
        {"cd10", "CDI valid against its schema", ""},
        {"cd20", "CDI read to its NUL (datagrams; stream variant)", ""},
        {"cd30", "ACDI spaces agree with SNIP and the CDI", ""},
        {"cd40", "writes to 0xFB byte 0 and to 0xFC refused",
         "the 0xFC half only: the standard lists 251 with its version byte as read and write "
         "(ConfigurationDescriptionInformationS §5.1.2; MemoryConfigurationS §4.1: no space is "
         "partly read-only), so accepting a write of 0xFB byte 0 is no fault"},
        {"st10-st210", "stream transport (lcc-conform as the source, the node as the sink)",
         "covered only as the node's source side in memory-config stream reads (the node "
         "streams to lcc-conform); the checks with lcc-conform as the source are not covered"},
        {"tr010", "Is Train event produced", ""},
        {"tr020", "set and query speed and direction (0.75 and 0, both directions)", ""},
        {"tr030", "set and query F0", ""},
        {"tr040", "Emergency Stop", ""},
        {"tr050", "Emergency Stop All event", ""},
        {"tr060", "Emergency Off All event", ""},
        {"tr070", "spaces 0xF9 and 0xFA",
         "0xFA FAILs only when the PIP claims FDI: FDI is strongly recommended, not required "
         "(TrainControlS §3), so a node without it gets a WARN"},
        {"tr080", "listener attach, query, detach", ""},
        {"tr090", "controller assign, query, release",
         "the Query Controller flags byte is shown, not judged: the standard marks 0x01 "
         "reserved, while tr090 fails a reply without bit 0 set"},
        {"tr100", "reserve, reserve again, release",
         "a refused second Reserve from the same node is no FAIL: the standard gives Reserve no "
         "rules beyond its reply (tr100 fails it; the plan's other section expects it)"},
        {"tr110", "heartbeat", ""},
        {"ts10", "allocate a train, then find it", ""},
        {"ts20", "partial (prefix) searches", ""},
        {"ts30", "a reserved nibble allocates nothing", ""},
        {"ts40", "reserved protocol values allocate nothing", ""},
        {"fd10", "space 0xFA present", ""},
        {"fd20", "FDI read to its NUL, declaration, schema",
         "the text is judged by cdi's FDI support (check_fdi_rules, validate_fdi), as lcc-cdi "
         "validate judges a file; the functions it names are queried (fdi.functions)"},
        {"fd30", "FDI space refuses writes", ""},
        {"bt10", "Query answered with the synchronization sequence", ""},
        {"bt20", "Set: the sequence carries what was set", ""},
        {"bt30", "Set: the effective Report at once", ""},
        {"bt40", "Sets 1 s apart: one sequence", ""},
        {"bt50", "Report Time at most once a real minute (at least once in 2 minutes)",
         "the upper bound only: §6.2 asks for a report at least once a real hour, not every two "
         "minutes, so a clock reporting every four minutes (OpenMRN) is no fault"},
        {"bt60", "a Report Time asked for by Consumer Identified is produced", ""},
        {"bt70", "Date Rollover, Report Year and Date after midnight", ""},
        {"bt80", "generator start-up: ranges and sequence", ""},
        {"bt100", "consumer start-up: Consumer (Range) Identified", ""},
        {"bt110", "consumer: Identify Consumer after a sequence", ""},
        {"bt120", "consumer: Identify Consumer after Stop and Start", ""},
        {"bt130", "consumer: Identify Consumer after a rate change", ""},
        {"dd", "DCC detector",
         "not covered: protocols of other node kinds than configurable nodes, trains and clocks"},
    };
    return all;
}

namespace {

// "`a`, `b`" of the registry IDs naming an OlcbChecker check in their olcbchecker field.
std::string covering(std::string_view olcb) {
    std::string out;
    for (const CheckSpec& s : check_registry()) {
        std::string_view list = s.olcbchecker;
        bool hit = false;
        while (!list.empty()) {
            const std::size_t comma = list.find(',');
            std::string_view one = list.substr(0, comma);
            while (one.starts_with(' ')) one.remove_prefix(1);
            if (one == olcb) hit = true;
            list = comma == std::string_view::npos ? "" : list.substr(comma + 1);
        }
        if (hit) out += (out.empty() ? "`" : ", `") + std::string(s.id) + "`";
    }
    return out;
}

std::string cell(std::string_view text) {
    std::string out;
    for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

}  // namespace

std::string format_check_markdown() {
    std::ostringstream out;
    out << "| ID | Category | Standard, section | Strength: the clause | OlcbChecker | What is "
           "sent, "
           "what passes |\n"
           "|---|---|---|---|---|---|\n";
    for (const CheckSpec& s : check_registry()) {
        out << "| `" << s.id << "` | " << category_name(s.category) << " | " << cell(s.section)
            << " | **" << strength_name(s.strength) << "**: " << cell(s.clause) << " | "
            << (s.olcbchecker.empty() ? "–" : s.olcbchecker) << " | " << cell(s.summary)
            << (s.thorough ? " (only with `--thorough`)" : "")
            << (s.past_end_writes ? " (only with `--write-past-end`)" : "")
            << (s.run ? "" : " (produced by the node run's phases)") << " |\n";
    }
    out << "\n| OlcbChecker | What it checks | lcc-conform |\n|---|---|---|\n";
    for (const OlcbCheckerCheck& c : olcbchecker_checks()) {
        const std::string by = covering(c.id);
        out << "| " << c.id << " | " << cell(c.title) << " | " << (by.empty() ? "" : by)
            << (by.empty() || c.not_why.empty() ? "" : "; ") << cell(c.not_why) << " |\n";
    }
    return out.str();
}

}  // namespace olcb::conform
