#include "conformance/report/report.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <sstream>

#include "support/report_schema.hpp"

namespace olcb::conform {
namespace {

NodeReport sample() {
    NodeReport r;
    r.node_id = "05.01.01.01.22.00";
    r.name = "ACME Sim CDI Node";
    r.checks = {
        {"frame.ame-answered", Category::kFrame, Status::kPass, "AMD came",
         "CanFrameTransferS 6.2.3", "", ""},
        {"encoding.int", Category::kEncoding, Status::kFail, "bytes <differ> & \"x\"",
         "CDI S 5.1.4.2", "03 E8", "E8 03"},
        {"encoding.blob", Category::kEncoding, Status::kSkip, "not asked", "", "", ""},
        {"cdi.xml-declaration", Category::kCdi, Status::kWarn, "odd \x01 text", "CDI S 5", "", ""},
    };
    r.restore_summary = "node memory byte-identical to before";
    return r;
}

TEST(FormatCheck, FailureCarriesExpectedSeenAndSection) {
    std::string line = format_check(sample().checks[1], false);
    EXPECT_EQ(line.rfind("FAIL  encoding.int", 0), 0u) << line;
    EXPECT_NE(line.find("expected: 03 E8"), std::string::npos);
    EXPECT_NE(line.find("seen:     E8 03"), std::string::npos);
    EXPECT_NE(line.find("CDI S 5.1.4.2"), std::string::npos);
    EXPECT_EQ(line.find('\033'), std::string::npos);
    EXPECT_NE(format_check(sample().checks[1], true).find("\033[31m"), std::string::npos);
}

TEST(WriteText, OneLinePerCheckAndTotals) {
    std::ostringstream out;
    write_text(out, sample(), false);
    std::string text = out.str();
    EXPECT_NE(text.find("PASS  frame.ame-answered"), std::string::npos);
    EXPECT_NE(text.find("SKIP  encoding.blob"), std::string::npos);
    EXPECT_NE(text.find("restore: node memory byte-identical"), std::string::npos);
    EXPECT_NE(text.find("4 checks: 1 passed, 1 failed, 1 warnings, 1 skipped"), std::string::npos);
    EXPECT_EQ(text.find('\x01'), std::string::npos);
}

RunInfo sample_run() {
    RunInfo run;
    run.connection = "connect 127.0.0.1:12021";
    run.arguments = {"lcc-conform", "--connect", "127.0.0.1:12021"};
    run.started = std::chrono::system_clock::time_point{} + std::chrono::hours(24 * 365 * 57);
    run.elapsed = std::chrono::milliseconds(2500);
    run.exit_code = 1;
    return run;
}

TEST(ToJson, RootHasOneShapeForAnyNumberOfNodes) {
    for (std::size_t n : {0u, 1u, 2u}) {
        const std::vector<NodeReport> reports(n, sample());
        const std::string text = to_json(reports, sample_run());
        EXPECT_EQ(test::json_report_errors(text), "") << text;
        const auto j = nlohmann::json::parse(text);
        EXPECT_EQ(j["schema_version"], 1);
        EXPECT_EQ(j["tool"]["name"], "lcc-conform");
        EXPECT_EQ(j["nodes"].size(), n);
        EXPECT_EQ(j["run"]["summary"]["fail"], n);
        EXPECT_EQ(j["run"]["exit_code"], 1);
        EXPECT_EQ(j["run"]["elapsed_s"], 2.5);
    }
}

TEST(ToJson, NodeCarriesIdentityChecksAndSummary) {
    NodeReport r = sample();
    r.identity.model = "Sim CDI Node";
    r.checks[1].duration = std::chrono::milliseconds(15);
    const auto j = nlohmann::json::parse(to_json({r}, sample_run()));
    const auto& node = j["nodes"][0];
    EXPECT_EQ(node["id"], "05.01.01.01.22.00");
    EXPECT_EQ(node["identity"]["model"], "Sim CDI Node");
    ASSERT_EQ(node["checks"].size(), 4u);
    EXPECT_EQ(node["checks"][1]["id"], "encoding.int");
    EXPECT_EQ(node["checks"][1]["category"], "encoding");
    EXPECT_EQ(node["checks"][1]["status"], "FAIL");
    EXPECT_EQ(node["checks"][1]["expected"], "03 E8");
    EXPECT_EQ(node["checks"][1]["duration_s"], 0.015);
    EXPECT_EQ(node["checks"][2]["expected"], "");  // always present, one shape
    EXPECT_EQ(node["summary"]["fail"], 1);
    EXPECT_EQ(node["summary"]["total"], 4);
    EXPECT_EQ(j["run"]["started"], "2026-12-18T00:00:00.000Z");
}

TEST(ToJson, SchemaRejectsWhatItShould) {
    // The validator itself must be able to fail, or "every report validates" proves nothing.
    auto j = nlohmann::json::parse(to_json({sample()}, sample_run()));
    j["nodes"][0]["checks"][0]["status"] = "OK";
    EXPECT_NE(test::json_report_errors(j.dump()), "");
    j = nlohmann::json::parse(to_json({sample()}, sample_run()));
    j["nodes"][0].erase("checks");
    EXPECT_NE(test::json_report_errors(j.dump()), "");
    j = nlohmann::json::parse(to_json({sample()}, sample_run()));
    j["schema_version"] = 2;
    EXPECT_NE(test::json_report_errors(j.dump()), "");
}

TEST(ToJson, InvalidUtf8FromTheNodeIsReplacedNotFatal) {
    NodeReport r = sample();
    r.name = "bad\xff\xfename";
    r.identity.user_name = "bad\xff\xfename";
    r.checks[0].message = "user name \"bad\xff\xfename\"";
    const std::string text = to_json({r}, sample_run());
    const auto j = nlohmann::json::parse(text, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << text;
    EXPECT_EQ(j["nodes"][0]["name"], "bad\xEF\xBF\xBD\xEF\xBF\xBDname");  // two U+FFFD
    EXPECT_EQ(test::json_report_errors(text), "");
}

TEST(ToJunit, SuitePerNodeWithPropertiesTimesAndUniqueNames) {
    NodeReport a = sample();
    a.identity.model = "Sim CDI Node";
    a.identity.user_name = "bad\xff\x01name";
    NodeReport b = sample();
    b.node_id = "05.01.01.01.22.01";
    const std::string xml = to_junit({a, b}, sample_run());
    EXPECT_EQ(test::junit_report_errors(xml), "") << xml;
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_string(xml.c_str())) << xml;
    auto suite = doc.child("testsuites").child("testsuite");
    ASSERT_TRUE(suite);
    EXPECT_STREQ(suite.attribute("name").as_string(), "node 05.01.01.01.22.00 Sim CDI Node");
    EXPECT_EQ(suite.attribute("tests").as_int(), 4);
    EXPECT_EQ(suite.attribute("failures").as_int(), 1);
    EXPECT_EQ(suite.attribute("skipped").as_int(), 1);
    EXPECT_TRUE(suite.attribute("timestamp"));
    EXPECT_TRUE(suite.attribute("hostname"));
    EXPECT_STREQ(suite.child("properties")
                     .find_child_by_attribute("property", "name", "node.id")
                     .attribute("value")
                     .as_string(),
                 "05.01.01.01.22.00");
    int cases = 0;
    for (auto tc : suite.children("testcase")) {
        ++cases;
        std::string name = tc.attribute("name").as_string();
        EXPECT_TRUE(tc.attribute("time")) << name;
        EXPECT_EQ(static_cast<bool>(tc.child("failure")), name.starts_with("encoding.int "))
            << name;
        EXPECT_EQ(static_cast<bool>(tc.child("skipped")), name.starts_with("encoding.blob "))
            << name;
    }
    EXPECT_EQ(cases, 4);
    EXPECT_EQ(xml.find('\x01'), std::string::npos);
}

TEST(ToJunit, LostLinkIsAnErrorAndRunErrorsAreCounted) {
    NodeReport r = sample();
    r.checks.push_back({"link.lost", Category::kLink, Status::kFail, "the hub went away", "",
                        "the link stays up", "connection reset"});
    RunInfo run = sample_run();
    run.error = "the link went down during the run";
    const std::string xml = to_junit({r}, run);
    EXPECT_EQ(test::junit_report_errors(xml), "") << xml;
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_string(xml.c_str()));
    auto suites = doc.child("testsuites");
    EXPECT_EQ(suites.attribute("errors").as_int(), 2);
    EXPECT_EQ(suites.attribute("failures").as_int(), 1);
    EXPECT_EQ(suites.attribute("tests").as_int(), 6);
    EXPECT_TRUE(suites.child("testsuite")
                    .find_child_by_attribute("testcase", "name", "link.lost on 05.01.01.01.22.00")
                    .child("error"));
}

TEST(ToJunit, SchemaRejectsDuplicateNames) {
    std::string xml = to_junit({sample(), sample()}, sample_run());  // same node twice
    EXPECT_NE(test::junit_report_errors(xml), "");
}

TEST(ProgressBar, ShowsBytesAndEta) {
    std::ostringstream out;
    ProgressBar bar(out, true);
    auto t0 = std::chrono::steady_clock::time_point{} + std::chrono::hours(1);
    bar.start("CDI", 1000, t0);
    std::string s = bar.render(500, t0 + std::chrono::seconds(2));
    EXPECT_NE(s.find("500/1000 B"), std::string::npos) << s;
    EXPECT_NE(s.find("ETA 0:02"), std::string::npos) << s;
    bar.update(500, t0 + std::chrono::seconds(2));
    EXPECT_FALSE(out.str().empty());
    std::ostringstream quiet;
    ProgressBar off(quiet, false);
    off.start("CDI", 10, t0);
    off.update(5, t0);
    off.finish();
    EXPECT_TRUE(quiet.str().empty());
}

}  // namespace
}  // namespace olcb::conform
