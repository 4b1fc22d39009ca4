// The JSON report (docs/report.schema.json).
#include <nlohmann/json.hpp>

#include "conformance/report.hpp"

namespace olcb::conform {
namespace {

nlohmann::json node_json(const NodeReport& report) {
    nlohmann::json checks = nlohmann::json::array();
    for (const CheckResult& c : report.checks) {
        nlohmann::json j = {{"id", c.id},
                            {"category", std::string(category_name(c.category))},
                            {"status", std::string(status_name(c.status))},
                            {"message", c.message},
                            {"section", c.section}};
        if (!c.expected.empty()) j["expected"] = c.expected;
        if (!c.seen.empty()) j["seen"] = c.seen;
        if (!c.details.empty()) j["details"] = c.details;
        checks.push_back(std::move(j));
    }
    Summary s = summarize({report});
    const RunTiming& t = report.timing;
    auto ms = [](Duration d) {
        return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
    };
    nlohmann::json timing = {{"silence_ms", ms(t.silence)},
                             {"answer_ms", ms(t.answer)},
                             {"reply_ms", ms(t.reply)},
                             {"quiet_ms", ms(t.quiet)},
                             {"scale", t.scale}};
    if (t.latency) {
        timing["latency_ms"] = ms(*t.latency);
        timing["worst_ms"] = ms(t.worst);
    }
    return {{"node", {{"id", report.node_id}, {"name", report.name}}},
            {"timing", std::move(timing)},
            {"checks", std::move(checks)},
            {"summary",
             {{"pass", s.pass},
              {"fail", s.fail},
              {"warn", s.warn},
              {"skip", s.skip},
              {"total", s.total()},
              {"restore", report.restore_summary}}}};
}

// Node names and messages carry the node's own bytes, which may not be UTF-8: they are written
// with U+FFFD in place of invalid bytes instead of aborting the report (and the run) on them.
std::string dump_json(const nlohmann::json& root) {
    return root.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace

std::string to_json(const std::vector<NodeReport>& reports, const RunInfo& run) {
    auto extras = [&](nlohmann::json& root) {
        if (!run.error.empty()) root["error"] = printable(run.error);
        if (!run.late_nodes.empty()) root["late_nodes"] = run.late_nodes;
    };
    if (reports.size() == 1) {
        nlohmann::json root = node_json(reports.front());
        extras(root);
        return dump_json(root);
    }
    nlohmann::json nodes = nlohmann::json::array();
    for (const NodeReport& r : reports) nodes.push_back(node_json(r));
    Summary s = summarize(reports);
    nlohmann::json root = {{"nodes", std::move(nodes)},
                           {"summary",
                            {{"pass", s.pass},
                             {"fail", s.fail},
                             {"warn", s.warn},
                             {"skip", s.skip},
                             {"total", s.total()}}}};
    extras(root);
    return dump_json(root);
}

}  // namespace olcb::conform
