#include "simnode/faults/fault_catalog.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {
namespace {

std::vector<FaultDecl> collect() {
    std::vector<FaultDecl> all;
    for (const FaultFamily family : fault_families()) {
        for (FaultDecl& d : family()) all.push_back(std::move(d));
    }
    std::stable_sort(all.begin(), all.end(),
                     [](const FaultDecl& a, const FaultDecl& b) { return a.order < b.order; });
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

FaultValue fault_value(const FaultSet& faults, const FaultDecl& d) {
    const auto it = faults.by_name.find(d.name);
    return it == faults.by_name.end() ? FaultValue{} : it->second;
}

void set_fault(FaultSet& faults, const FaultDecl& d, FaultValue v) {
    if (v == FaultValue{}) {
        faults.by_name.erase(std::string(d.name));
    } else {
        faults.by_name[std::string(d.name)] = v;
    }
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
        case ParamKind::kExponentMs:
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
