#include "conformance/report_html.hpp"

#include <ctime>

#include <nlohmann/json.hpp>

#include "cdi/html_page.hpp"
#include "conformance/memory_map.hpp"
#include "olcb_version.hpp"

namespace olcb::conform {
namespace {

// "2025-06-14T12:34:56Z", or "" for a time never set.
std::string utc_text(std::chrono::system_clock::time_point t) {
    if (t == std::chrono::system_clock::time_point{}) return "";
    const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
    std::tm parts{};
    gmtime_r(&seconds, &parts);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &parts);
    return buf;
}

template <class D>
long long milliseconds(D d) {
    return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
}

nlohmann::json summary_json(const Summary& s) {
    return {{"pass", s.pass},
            {"fail", s.fail},
            {"warn", s.warn},
            {"skip", s.skip},
            {"total", s.total()}};
}

nlohmann::json check_json(const CheckResult& c) {
    return {{"id", c.id},
            {"category", std::string(category_name(c.category))},
            {"status", std::string(status_name(c.status))},
            {"message", c.message},
            {"section", c.section},
            {"expected", c.expected},
            {"seen", c.seen},
            {"details", c.details},
            {"duration_ms", milliseconds(c.duration)}};
}

nlohmann::json node_json(const NodeReport& r) {
    nlohmann::json checks = nlohmann::json::array();
    for (const CheckResult& c : r.checks) checks.push_back(check_json(c));
    const NodeIdentity& id = r.identity;
    return {{"id", r.node_id},
            {"name", r.name},
            {"identity",
             {{"manufacturer", id.manufacturer},
              {"model", id.model},
              {"hardware_version", id.hardware_version},
              {"software_version", id.software_version},
              {"user_name", id.user_name},
              {"user_description", id.user_description}}},
            {"started", utc_text(r.started)},
            {"elapsed_ms", milliseconds(r.elapsed)},
            {"restore", r.restore_summary},
            {"incomplete", r.incomplete},
            {"summary", summary_json(summarize({r}))},
            {"checks", std::move(checks)},
            {"memory_map", memory_map_json(r.memory_map)}};
}

}  // namespace

nlohmann::json html_report_json(const std::vector<NodeReport>& reports, const RunInfo& run) {
    nlohmann::json nodes = nlohmann::json::array();
    for (const NodeReport& r : reports) nodes.push_back(node_json(r));
    return {{"tool", {{"name", "lcc-conform"}, {"version", kVersion}}},
            {"run",
             {{"started", utc_text(run.started)},
              {"elapsed_ms", milliseconds(run.elapsed)},
              {"connection", run.connection},
              {"arguments", run.arguments},
              {"error", run.error},
              {"late_nodes", run.late_nodes}}},
            {"summary", summary_json(summarize(reports))},
            {"nodes", std::move(nodes)}};
}

std::string to_html(const std::vector<NodeReport>& reports, const RunInfo& run) {
    return cdi::html_page(cdi::PageKind::kConformance, html_report_json(reports, run));
}

}  // namespace olcb::conform
