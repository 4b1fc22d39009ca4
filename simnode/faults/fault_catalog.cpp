#include "simnode/faults/fault_catalog.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {
namespace {

constexpr std::vector<FaultDecl> (*kFamilies[])() = {
    snip_faults,    acdi_faults,    pip_faults,      cdi_faults,    encoding_faults,
    write_faults,   read_faults,    datagram_faults, timing_faults, frame_faults,
    message_faults, restart_faults, event_faults,    stream_faults,
};

// The order the faults were added in, which to_names(), --list-faults and docs/faults.md keep
// so their output stays stable; a fault not listed (a new one) follows in family order.
constexpr std::string_view kHistoricalOrder[] = {
    "snip-mismatch",
    "snip-invalid-utf8",
    "acdi-version",
    "pip-missing-bit",
    "cdi-unterminated",
    "cdi-padding",
    "cdi-invalid",
    "int-byte-order",
    "string-unterminated",
    "eventid-byte-order",
    "float-width",
    "write-dropped",
    "write-not-persisted",
    "readonly-writable",
    "read-past-end",
    "space-info-short",
    "reply-form",
    "no-datagram-ack",
    "slow-reply",
    "reject-temporary",
    "alias-conflict-ignored",
    "unsolicited-traffic",
    "abort-on-value",
    "reboot-on-write",
    "reset-rejected",
    "lock-rejected",
    "factory-reset-on-version-change",
    "new-alias-on-reboot",
    "field-reads-only",
    "unknown-space-0x1041",
    "readonly-0x1041",
    "latency",
    "read-past-end-garbage",
    "write-past-end-spills",
    "write-past-end-grows",
    "mask-ignored",
    "highest-unreadable",
    "events-stale-after-write",
    "events-missing",
    "duplicate-id-silent",
    "burst-drops",
    "answers-standard-frames",
    "stream-wrong-count",
    "stream-no-complete",
    "stream-ignore-proceed",
    "stream-exceed-buffer",
};

std::size_t historical_rank(std::string_view name) {
    const auto* it = std::find(std::begin(kHistoricalOrder), std::end(kHistoricalOrder), name);
    return static_cast<std::size_t>(it - std::begin(kHistoricalOrder));
}

std::vector<FaultDecl> collect() {
    std::vector<FaultDecl> all;
    for (const auto family : kFamilies) {
        for (FaultDecl& d : family()) all.push_back(std::move(d));
    }
    std::stable_sort(all.begin(), all.end(), [](const FaultDecl& a, const FaultDecl& b) {
        return historical_rank(a.name) < historical_rank(b.name);
    });
    return all;
}

std::string_view verdict_name(Verdict v) {
    switch (v) {
        case Verdict::kFail:
            return "fail";
        case Verdict::kWarn:
            return "warn";
        case Verdict::kIncomplete:
            return "incomplete";
        case Verdict::kNone:
            break;
    }
    return "none";
}

}  // namespace

const std::vector<FaultDecl>& fault_decls() {
    static const std::vector<FaultDecl> decls = collect();
    return decls;
}

const FaultDecl* find_fault(std::string_view name) {
    for (const FaultDecl& d : fault_decls()) {
        if (d.name == name) return &d;
    }
    return nullptr;
}

std::string category_column(const FaultDecl& d) {
    std::string out(d.category.empty() ? "none" : d.category);
    if (d.verdict == Verdict::kWarn) out += " (warn)";
    if (d.verdict == Verdict::kIncomplete) out += " (incomplete)";
    if (!d.category_note.empty()) out += " (" + std::string(d.category_note) + ")";
    return out;
}

std::string help_parameter(const FaultDecl& d) {
    const FaultParam& p = d.param;
    switch (p.kind) {
        case ParamKind::kNone:
            return "";
        case ParamKind::kChoice: {
            std::string out;
            for (const auto choice : p.choices)
                out += (out.empty() ? "" : "|") + std::string(choice);
            return out + " (default " + std::string(p.choices.at(p.fallback - 1)) + ")";
        }
        case ParamKind::kNumber:
        case ParamKind::kMsJitter:
            break;
    }
    return std::string(p.value_name) + " (default " + std::to_string(p.fallback) + ")";
}

std::string format_fault_markdown() {
    std::string out =
        "| Fault | Parameter | Rule broken | What a client sees | Category |\n"
        "|---|---|---|---|---|\n";
    for (const FaultDecl& d : fault_decls()) {
        out += "| `" + std::string(d.name) + "` | ";
        out += d.doc_parameter.empty() ? "–" : std::string(d.doc_parameter);
        out += " | " + std::string(d.rule_broken) + " | " + std::string(d.client_sees) + " | " +
               category_column(d) + " |\n";
    }
    return out;
}

std::string format_fault_json() {
    auto out = nlohmann::json::array();
    for (const FaultDecl& d : fault_decls()) {
        auto checks = nlohmann::json::array();
        for (const auto id : d.checks) checks.push_back(id);
        out.push_back({{"name", d.name},
                       {"parameter", help_parameter(d)},
                       {"summary", d.summary},
                       {"verdict", verdict_name(d.verdict)},
                       {"category", d.category},
                       {"checks", checks}});
    }
    return out.dump(2) + "\n";
}

}  // namespace olcb::simnode
