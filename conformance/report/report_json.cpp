// The JSON report (docs/report.schema.json, schema_version 1): one shape for any number of nodes.
#include <cmath>
#include <ctime>
#include <nlohmann/json.hpp>

#include "conformance/report/map_verdict.hpp"
#include "conformance/report/report.hpp"
#include "olcb_version.hpp"

namespace olcb::conform {
namespace {

constexpr int kSchemaVersion = 1;

double seconds(Duration d) {
    return std::round(std::chrono::duration<double>(d).count() * 1e6) / 1e6;
}

nlohmann::ordered_json summary_json(const Summary& s) {
    return {{"pass", s.pass},
            {"fail", s.fail},
            {"warn", s.warn},
            {"skip", s.skip},
            {"total", s.total()}};
}

nlohmann::ordered_json check_json(const CheckResult& c) {
    return {{"id", c.id},
            {"category", std::string(category_name(c.category))},
            {"status", std::string(status_name(c.status))},
            {"message", c.message},
            {"section", c.section},
            {"expected", c.expected},
            {"seen", c.seen},
            {"details", c.details},
            {"duration_s", seconds(c.duration)}};
}

nlohmann::ordered_json timing_json(const RunTiming& t) {
    auto ms = [](Duration d) {
        return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
    };
    nlohmann::ordered_json timing = {{"silence_ms", ms(t.silence)},
                                     {"answer_ms", ms(t.answer)},
                                     {"reply_ms", ms(t.reply)},
                                     {"quiet_ms", ms(t.quiet)},
                                     {"scale", t.scale}};
    if (t.latency) {
        timing["latency_ms"] = ms(*t.latency);
        timing["worst_ms"] = ms(t.worst);
    }
    return timing;
}

// The map is built as nlohmann::json (cdi/ and memory_map own its shape); the report keeps its
// fields in order, so it is carried over as text, CDI paths' invalid UTF-8 replaced on the way.
nlohmann::ordered_json map_json(const std::vector<MemoryMapSpace>& map) {
    const std::string text =
        memory_map_json(map).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    return nlohmann::ordered_json::parse(text);
}

nlohmann::ordered_json runs_json(const std::vector<ByteRun>& runs) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const ByteRun& b : runs)
        out.push_back({{"space", b.space}, {"address", b.address}, {"count", b.count}});
    return out;
}

// The numbers behind the restore line: what the ledger says was written and how it read back.
nlohmann::ordered_json writes_json(const RestoreRecord& r) {
    nlohmann::ordered_json identical = nullptr;
    if (r.identical) identical = *r.identical;
    return {{"sent", r.writes},
            {"saved_bytes", r.saved_bytes},
            {"rewritten_bytes", r.rewritten_bytes},
            {"identical", identical},
            {"past_end", runs_json(r.past_end)},
            {"left_as_found", runs_json(r.left_as_found)},
            {"backup_kept", r.backup_kept}};
}

nlohmann::ordered_json node_json(const NodeReport& report) {
    nlohmann::ordered_json checks = nlohmann::ordered_json::array();
    for (const CheckResult& c : report.checks) checks.push_back(check_json(c));
    const NodeIdentity& id = report.identity;
    return {{"id", report.node_id},
            {"name", report.name},
            {"identity",
             {{"manufacturer", id.manufacturer},
              {"model", id.model},
              {"hardware_version", id.hardware_version},
              {"software_version", id.software_version},
              {"user_name", id.user_name},
              {"user_description", id.user_description}}},
            {"started", iso_timestamp(report.started)},
            {"elapsed_s", seconds(report.elapsed)},
            {"scope", report.scope},
            {"incomplete", report.incomplete},
            {"incomplete_reasons", report.incomplete_reasons},
            {"timing", timing_json(report.timing)},
            {"checks", std::move(checks)},
            {"summary", summary_json(summarize({report}))},
            {"restore", report.restore_summary},
            {"writes", writes_json(report.restore)},
            {"not_tested", report.not_tested},
            {"memory_map", map_json(report.memory_map)}};
}

// Node names and messages carry the node's own bytes, which may not be UTF-8: they are written
// with U+FFFD in place of invalid bytes instead of aborting the report (and the run) on them.
std::string dump_json(const nlohmann::ordered_json& root) {
    return root.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace

std::string iso_timestamp(std::chrono::system_clock::time_point t) {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(t.time_since_epoch());
    const std::time_t secs = static_cast<std::time_t>(ms.count() / 1000);
    std::tm utc{};
    gmtime_r(&secs, &utc);
    char buf[40];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &utc);
    char out[48];
    std::snprintf(out, sizeof out, "%s.%03dZ", buf, static_cast<int>(ms.count() % 1000));
    return out;
}

std::string to_json(const std::vector<NodeReport>& reports, const RunInfo& run) {
    nlohmann::ordered_json nodes = nlohmann::ordered_json::array();
    for (const NodeReport& r : reports) nodes.push_back(node_json(r));
    const nlohmann::ordered_json root = {{"schema_version", kSchemaVersion},
                                         {"tool", {{"name", "lcc-conform"}, {"version", kVersion}}},
                                         {"run",
                                          {{"started", iso_timestamp(run.started)},
                                           {"elapsed_s", seconds(run.elapsed)},
                                           {"exit_code", run.exit_code},
                                           {"connection", run.connection},
                                           {"arguments", run.arguments},
                                           {"error", printable(run.error)},
                                           {"late_nodes", run.late_nodes},
                                           {"other_runs", run.other_runs},
                                           {"summary", summary_json(summarize(reports))}}},
                                         {"nodes", std::move(nodes)}};
    return dump_json(root);
}

}  // namespace olcb::conform
