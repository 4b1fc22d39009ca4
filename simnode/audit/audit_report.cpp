#include "simnode/audit/audit_report.hpp"

#include <pugixml.hpp>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/utf8.hpp"
#include "simnode/audit/audit_context.hpp"

namespace olcb::simnode::audit {
namespace {

using nlohmann::json;

double microseconds(double seconds) {
    return std::round(seconds * 1e6) / 1e6;
}

json client_json(const ClientRef& c) {
    return {{"connection", c.connection},
            {"remote", c.remote.empty() ? json(nullptr) : json(c.remote)},
            {"alias", alias_text(c.alias)},
            {"node_id", c.node_id ? json(c.node_id->to_string()) : json(nullptr)}};
}

json finding_json(const Finding& f) {
    const Rule& r = rule(f.rule);
    json node = nullptr;
    if (f.node)
        node = {{"node_id", f.node->node_id.to_string()}, {"alias", alias_text(f.node->alias)}};
    return {{"rule", r.name},
            {"level", level_name(r.level)},
            {"standard", r.standard},
            {"message", f.message},
            {"time", microseconds(f.time)},
            {"last_time", microseconds(f.last_time)},
            {"count", f.count},
            {"client", client_json(f.client)},
            {"node", std::move(node)},
            {"frames", f.frames}};
}

// Findings per level, in Level order.
std::array<std::size_t, 3> count_levels(const FindingLog& log) {
    std::array<std::size_t, 3> n{};
    for (const Finding& f : log.findings()) ++n[static_cast<std::size_t>(rule(f.rule).level)];
    return n;
}

// Text a reader can show (base/utf8.hpp): control characters as '?', bytes that are not UTF-8
// as U+FFFD (a client's bad string must not make the report unreadable).
using base::printable;

// "1.234567 s client 0x12C (02.01.0D.00.00.01, 127.0.0.1:4567) -> node 05.01.01.01.22.00: ..."
std::string finding_line(const Finding& f) {
    char t[32];
    std::snprintf(t, sizeof t, "%.6f s", f.time);
    std::string line = std::string(t) + " client " + alias_text(f.client.alias);
    if (f.client.node_id || !f.client.remote.empty()) {
        line += " (";
        if (f.client.node_id) line += f.client.node_id->to_string();
        if (f.client.node_id && !f.client.remote.empty()) line += ", ";
        line += f.client.remote + ")";
    }
    if (f.node) line += " -> node " + f.node->node_id.to_string();
    line += ": " + printable(f.message);
    if (f.count > 1) line += " (" + std::to_string(f.count) + " times)";
    for (const std::string& frame : f.frames) line += "\n    " + frame;
    return line;
}

void add_testcase(pugi::xml_node suite, const Rule& r, const FindingLog& log) {
    auto tc = suite.append_child("testcase");
    tc.append_attribute("classname") = "simnode.audit";
    tc.append_attribute("name") = std::string(r.name).c_str();
    std::string text;
    std::size_t found = 0;
    std::string first;
    for (const Finding& f : log.findings()) {
        if (f.rule != r.id) continue;
        if (found++ == 0) first = printable(f.message);
        text += finding_line(f) + "\n";
    }
    if (found == 0) return;
    const std::string heading = std::string(level_name(r.level)) + " " + std::string(r.standard) +
                                ": " + std::string(r.summary) + "\n";
    if (r.level == Level::kError) {
        auto failure = tc.append_child("failure");
        failure.append_attribute("type") = "error";
        failure.append_attribute("message") =
            (std::to_string(found) + " finding(s); first: " + first).c_str();
        failure.text().set((heading + text).c_str());
    } else {
        tc.append_child("system-out").text().set((heading + text).c_str());
    }
}

}  // namespace

std::string audit_json(const FindingLog& log, const ReportInfo& info) {
    json rule_list = json::array();
    for (const Rule& r : rules()) {
        rule_list.push_back({{"id", r.name},
                             {"level", level_name(r.level)},
                             {"standard", r.standard},
                             {"summary", r.summary}});
    }
    json findings = json::array();
    for (const Finding& f : log.findings()) findings.push_back(finding_json(f));
    const auto levels = count_levels(log);
    const json root = {{"audit", "simnode client audit"},
                       {"started", info.started},
                       {"complete", info.complete},
                       {"summary",
                        {{"errors", levels[0]},
                         {"warnings", levels[1]},
                         {"notes", levels[2]},
                         {"dropped", log.dropped()}}},
                       {"rules", std::move(rule_list)},
                       {"findings", std::move(findings)}};
    return root.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

std::string audit_junit(const FindingLog& log, const ReportInfo& info) {
    std::size_t failing = 0;
    for (const Rule& r : rules()) {
        if (r.level != Level::kError) continue;
        for (const Finding& f : log.findings()) {
            if (f.rule == r.id) {
                ++failing;
                break;
            }
        }
    }
    pugi::xml_document doc;
    auto decl = doc.append_child(pugi::node_declaration);
    decl.append_attribute("version") = "1.0";
    decl.append_attribute("encoding") = "UTF-8";
    auto suites = doc.append_child("testsuites");
    suites.append_attribute("name") = "simnode client audit";
    suites.append_attribute("tests") = static_cast<unsigned long long>(rules().size());
    suites.append_attribute("failures") = static_cast<unsigned long long>(failing);
    auto suite = suites.append_child("testsuite");
    suite.append_attribute("name") = "simnode client audit";
    suite.append_attribute("tests") = static_cast<unsigned long long>(rules().size());
    suite.append_attribute("failures") = static_cast<unsigned long long>(failing);
    suite.append_attribute("errors") = 0;
    suite.append_attribute("skipped") = 0;
    suite.append_attribute("timestamp") = info.started.c_str();
    for (const Rule& r : rules()) add_testcase(suite, r, log);
    if (!info.complete) {
        suite.append_child("system-out")
            .text()
            .set("simnode is still running: findings may follow");
    }
    std::ostringstream out;
    doc.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
    return out.str();
}

std::string utc_now() {
    const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm tm{};
    ::gmtime_r(&t, &tm);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buf;
}

}  // namespace olcb::simnode::audit
