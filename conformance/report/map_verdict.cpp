#include "conformance/report/map_verdict.hpp"

#include <nlohmann/json.hpp>

namespace olcb::conform {
namespace {

void add_verdict(const VariableVerdict& v, nlohmann::json& out) {
    out["verdict"] = std::string(map_verdict_name(v.verdict));
    if (!v.reason.empty()) out["reason"] = v.reason;
    if (!v.original_bytes.empty()) {
        out["original"] = {{"value", v.original_value}, {"bytes", v.original_bytes}};
    }
    if (!v.values.empty()) {
        nlohmann::json values = nlohmann::json::array();
        for (const TestedValue& t : v.values) {
            values.push_back({{"value", t.value},
                              {"written", t.written},
                              {"read", t.read},
                              {"read_value", t.read_value},
                              {"error", t.error},
                              {"ok", t.ok}});
        }
        out["values"] = std::move(values);
    }
}

}  // namespace

std::string_view map_verdict_name(MapVerdict verdict) {
    switch (verdict) {
        case MapVerdict::kVerified:
            return "verified";
        case MapVerdict::kFailed:
            return "failed";
        case MapVerdict::kProtected:
            return "protected";
        case MapVerdict::kSkipped:
            break;
    }
    return "skipped";
}

nlohmann::json memory_map_json(const std::vector<MemoryMapSpace>& spaces) {
    nlohmann::json out = nlohmann::json::array();
    for (const MemoryMapSpace& s : spaces) {
        nlohmann::json j = cdi::memory_map_json(s.map);
        std::array<std::size_t, 4> counts{};
        for (std::size_t i = 0; i < s.verdicts.size() && i < j["variables"].size(); ++i) {
            ++counts[static_cast<std::size_t>(s.verdicts[i].verdict)];
            add_verdict(s.verdicts[i], j["variables"][i]);
        }
        j["verdicts"] = {{"verified", counts[0]},
                         {"failed", counts[1]},
                         {"skipped", counts[2]},
                         {"protected", counts[3]}};
        out.push_back(std::move(j));
    }
    return out;
}

}  // namespace olcb::conform
