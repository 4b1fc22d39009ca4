// The JUnit report: a suite per node, lost links as errors, valid against junit.xsd.
#include "conformance/report/report.hpp"

#include <gtest/gtest.h>

#include <pugixml.hpp>
#include <string>

#include "conformance/report_test_util.hpp"
#include "support/report_schema.hpp"

namespace olcb::conform {
namespace {

using testing::sample;
using testing::sample_run;

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

}  // namespace
}  // namespace olcb::conform
