// The JUnit XML report, for CI systems (tests/support/junit.xsd describes what is written).
#include <unistd.h>

#include <array>
#include <cstdio>
#include <pugixml.hpp>
#include <sstream>

#include "conformance/report/report.hpp"
#include "olcb_version.hpp"

namespace olcb::conform {
namespace {

std::string seconds_text(std::chrono::steady_clock::duration d) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3f", std::chrono::duration<double>(d).count());
    return buf;
}

std::string host_name() {
    std::array<char, 256> buf{};
    if (::gethostname(buf.data(), buf.size() - 1) != 0) return "localhost";
    return buf.data();
}

// Ant writes the suite's timestamp in local ISO 8601 without a zone; UTC without the "Z" is what
// every reader takes (GitLab, Jenkins).
std::string junit_timestamp(std::chrono::system_clock::time_point t) {
    std::string iso = iso_timestamp(t);
    return iso.substr(0, iso.find('.'));
}

void set(pugi::xml_node node, const char* name, const std::string& value) {
    node.append_attribute(name) = value.c_str();
}

void set(pugi::xml_node node, const char* name, std::size_t value) {
    node.append_attribute(name) = static_cast<unsigned long long>(value);
}

void add_property(pugi::xml_node props, const char* name, const std::string& value) {
    auto p = props.append_child("property");
    set(p, "name", name);
    set(p, "value", printable(value));
}

void add_properties(pugi::xml_node suite, const NodeReport& r, const RunInfo& run) {
    auto props = suite.append_child("properties");
    add_property(props, "node.id", r.node_id);
    const NodeIdentity& id = r.identity;
    add_property(props, "snip.manufacturer", id.manufacturer);
    add_property(props, "snip.model", id.model);
    add_property(props, "snip.hardware_version", id.hardware_version);
    add_property(props, "snip.software_version", id.software_version);
    add_property(props, "snip.user_name", id.user_name);
    add_property(props, "snip.user_description", id.user_description);
    add_property(props, "tool.version", kVersion);
    if (!run.connection.empty()) add_property(props, "connection", run.connection);
}

std::string detail_text(const CheckResult& c) {
    std::string detail = printable(c.message);
    if (!c.expected.empty()) detail += "\nexpected: " + printable(c.expected);
    if (!c.seen.empty()) detail += "\nseen: " + printable(c.seen);
    if (!c.section.empty()) detail += "\nsection: " + printable(c.section);
    for (const std::string& d : c.details) detail += "\n- " + printable(d);
    return detail;
}

// A lost link or a node that died is not a finding about the node's conformance: CI shows it
// as an error (the run could not judge), not as a failed check.
bool is_error(const CheckResult& c) {
    return c.status == Status::kFail &&
           (c.category == Category::kLink || c.category == Category::kNode);
}

void add_testcase(pugi::xml_node suite, const CheckResult& c, const std::string& node_id) {
    auto tc = suite.append_child("testcase");
    set(tc, "classname", std::string(category_name(c.category)));
    set(tc, "name", c.id + " on " + node_id);
    set(tc, "time", seconds_text(c.duration));
    if (c.status == Status::kFail) {
        auto f = tc.append_child(is_error(c) ? "error" : "failure");
        set(f, "message", printable(c.message));
        set(f, "type", c.id);
        f.text().set(detail_text(c).c_str());
    } else if (c.status == Status::kSkip) {
        set(tc.append_child("skipped"), "message", printable(c.message));
    } else if (c.status == Status::kWarn) {
        tc.append_child("system-out").text().set(("WARN: " + detail_text(c)).c_str());
    }
}

std::size_t count_errors(const NodeReport& r) {
    std::size_t n = 0;
    for (const CheckResult& c : r.checks)
        if (is_error(c)) ++n;
    return n;
}

std::size_t add_node_suite(pugi::xml_node suites, const NodeReport& r, const RunInfo& run,
                           const std::string& host) {
    const Summary s = summarize({r});
    const std::size_t errors = count_errors(r);
    auto suite = suites.append_child("testsuite");
    std::string name = "node " + r.node_id;
    if (!r.identity.model.empty()) name += " " + printable(r.identity.model);
    set(suite, "name", name);
    set(suite, "tests", s.total());
    set(suite, "failures", s.fail - errors);
    set(suite, "errors", errors);
    set(suite, "skipped", s.skip);
    set(suite, "time", seconds_text(r.elapsed));
    set(suite, "timestamp", junit_timestamp(r.started));
    set(suite, "hostname", host);
    add_properties(suite, r, run);
    for (const CheckResult& c : r.checks) add_testcase(suite, c, r.node_id);
    if (!r.restore_summary.empty()) {
        suite.append_child("system-out")
            .text()
            .set(("restore: " + printable(r.restore_summary)).c_str());
    }
    return errors;
}

void add_run_error(pugi::xml_node suites, const RunInfo& run, const std::string& host) {
    // CI must see a red result, not "no tests", when the run could not check anything.
    auto suite = suites.append_child("testsuite");
    set(suite, "name", "lcc-conform");
    set(suite, "tests", std::size_t{1});
    set(suite, "failures", std::size_t{0});
    set(suite, "errors", std::size_t{1});
    set(suite, "skipped", std::size_t{0});
    set(suite, "time", seconds_text(run.elapsed));
    set(suite, "timestamp", junit_timestamp(run.started));
    set(suite, "hostname", host);
    auto tc = suite.append_child("testcase");
    set(tc, "classname", "run");
    set(tc, "name", "run");
    set(tc, "time", seconds_text(run.elapsed));
    auto e = tc.append_child("error");
    set(e, "message", printable(run.error));
    set(e, "type", "run");
}

}  // namespace

std::string to_junit(const std::vector<NodeReport>& reports, const RunInfo& run) {
    pugi::xml_document doc;
    auto decl = doc.append_child(pugi::node_declaration);
    decl.append_attribute("version") = "1.0";
    decl.append_attribute("encoding") = "UTF-8";
    auto suites = doc.append_child("testsuites");
    set(suites, "name", "lcc-conform");
    const Summary all = summarize(reports);
    const std::string host = host_name();
    std::size_t errors = 0;
    // The totals come first in the file but are known last: fill them in afterwards.
    auto tests = suites.append_attribute("tests");
    auto failures = suites.append_attribute("failures");
    auto errs = suites.append_attribute("errors");
    set(suites, "skipped", all.skip);
    set(suites, "time", seconds_text(run.elapsed));
    for (const NodeReport& r : reports) errors += add_node_suite(suites, r, run, host);
    const std::size_t failed = all.fail - errors;  // the node suites' errors are FAILs too
    std::size_t total = all.total();
    if (!run.error.empty()) {
        add_run_error(suites, run, host);
        ++errors;
        ++total;
    }
    tests = static_cast<unsigned long long>(total);
    failures = static_cast<unsigned long long>(failed);
    errs = static_cast<unsigned long long>(errors);
    std::ostringstream out;
    doc.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
    return out.str();
}

}  // namespace olcb::conform
