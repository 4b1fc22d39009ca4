// The JUnit XML report, for CI systems.
#include <pugixml.hpp>
#include <sstream>

#include "conformance/report.hpp"

namespace olcb::conform {

std::string to_junit(const std::vector<NodeReport>& reports, const RunInfo& run) {
    pugi::xml_document doc;
    auto decl = doc.append_child(pugi::node_declaration);
    decl.append_attribute("version") = "1.0";
    decl.append_attribute("encoding") = "UTF-8";
    auto suites = doc.append_child("testsuites");
    suites.append_attribute("name") = "lcc-conform";
    Summary all = summarize(reports);
    suites.append_attribute("tests") = static_cast<unsigned long long>(all.total());
    suites.append_attribute("failures") = static_cast<unsigned long long>(all.fail);
    suites.append_attribute("skipped") = static_cast<unsigned long long>(all.skip);
    for (const NodeReport& r : reports) {
        Summary s = summarize({r});
        auto suite = suites.append_child("testsuite");
        suite.append_attribute("name") = ("node " + r.node_id).c_str();
        suite.append_attribute("tests") = static_cast<unsigned long long>(s.total());
        suite.append_attribute("failures") = static_cast<unsigned long long>(s.fail);
        suite.append_attribute("errors") = 0;
        suite.append_attribute("skipped") = static_cast<unsigned long long>(s.skip);
        for (const CheckResult& c : r.checks) {
            auto tc = suite.append_child("testcase");
            tc.append_attribute("classname") = std::string(category_name(c.category)).c_str();
            tc.append_attribute("name") = c.id.c_str();
            std::string detail = printable(c.message);
            if (!c.expected.empty()) detail += "\nexpected: " + printable(c.expected);
            if (!c.seen.empty()) detail += "\nseen: " + printable(c.seen);
            if (!c.section.empty()) detail += "\nsection: " + printable(c.section);
            for (const std::string& d : c.details) detail += "\n- " + printable(d);
            if (c.status == Status::kFail) {
                auto f = tc.append_child("failure");
                f.append_attribute("message") = printable(c.message).c_str();
                f.append_attribute("type") = std::string(category_name(c.category)).c_str();
                f.text().set(detail.c_str());
            } else if (c.status == Status::kSkip) {
                tc.append_child("skipped").append_attribute("message") =
                    printable(c.message).c_str();
            } else if (c.status == Status::kWarn) {
                tc.append_child("system-out").text().set(("WARN: " + detail).c_str());
            }
        }
        if (!r.restore_summary.empty()) {
            suite.append_child("system-out")
                .text()
                .set(("restore: " + printable(r.restore_summary)).c_str());
        }
    }
    if (!run.error.empty()) {
        // CI must see a red result, not "no tests", when the run could not check anything.
        auto suite = suites.append_child("testsuite");
        suite.append_attribute("name") = "lcc-conform";
        suite.append_attribute("tests") = 1;
        suite.append_attribute("failures") = 0;
        suite.append_attribute("errors") = 1;
        suite.append_attribute("skipped") = 0;
        auto tc = suite.append_child("testcase");
        tc.append_attribute("classname") = "run";
        tc.append_attribute("name") = "run";
        auto e = tc.append_child("error");
        e.append_attribute("message") = printable(run.error).c_str();
        e.append_attribute("type") = "run";
        suites.append_attribute("errors") = 1;
    }
    std::ostringstream out;
    doc.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
    return out.str();
}

}  // namespace olcb::conform
