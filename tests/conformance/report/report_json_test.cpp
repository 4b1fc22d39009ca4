// The JSON report: one shape for any number of nodes, valid against its schema, node text made
// UTF-8.
#include "conformance/report/report.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <string>
#include <vector>

#include "conformance/report/run_timing.hpp"
#include "conformance/report_test_util.hpp"
#include "support/report_schema.hpp"

namespace olcb::conform {
namespace {

using std::chrono::milliseconds;
using testing::sample;
using testing::sample_run;

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

TEST(RunReports, TimingIsInTheJsonAndARunErrorInBothReports) {
    NodeReport r;
    r.node_id = "05.01.01.01.22.00";
    r.timing = derive_timing({milliseconds(40)}, 1.0);
    RunInfo run;
    run.late_nodes = {"05.01.01.01.22.10"};
    auto j = nlohmann::json::parse(to_json({r}, run));
    EXPECT_EQ(test::json_report_errors(to_json({r}, run)), "");
    EXPECT_EQ(j["nodes"][0]["timing"]["latency_ms"], 40);
    EXPECT_EQ(j["nodes"][0]["timing"]["silence_ms"], 250);
    EXPECT_EQ(j["run"]["late_nodes"][0], "05.01.01.01.22.10");
    run.error = "no node answered Verify Node ID";
    j = nlohmann::json::parse(to_json({}, run));
    EXPECT_EQ(test::json_report_errors(to_json({}, run)), "");
    EXPECT_EQ(j["run"]["error"], run.error);
    EXPECT_TRUE(j["nodes"].empty());
    pugi::xml_document doc;
    EXPECT_EQ(test::junit_report_errors(to_junit({}, run)), "");
    ASSERT_TRUE(doc.load_string(to_junit({}, run).c_str()));
    auto error = doc.select_node("//testsuite[@name='lcc-conform']/testcase/error");
    ASSERT_TRUE(error);
    EXPECT_EQ(std::string(error.node().attribute("message").value()), run.error);
}

}  // namespace
}  // namespace olcb::conform
