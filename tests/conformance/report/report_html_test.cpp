// The HTML report: the page carries the JSON report itself, so the two never differ.
#include "conformance/report/report_html.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "conformance/report_test_util.hpp"

namespace olcb::conform {
namespace {

using testing::sample;
using testing::sample_run;

TEST(ReportHtmlTest, ThePageDataIsTheJsonReport) {
    const nlohmann::json j = html_report_json({sample()}, sample_run());
    EXPECT_EQ(j, nlohmann::json::parse(to_json({sample()}, sample_run())));
    EXPECT_EQ(j["nodes"][0]["checks"][1]["id"], "encoding.int");
}

TEST(ReportHtmlTest, OneSelfContainedPageNamingTheNode) {
    const std::string page = to_html({sample()}, sample_run());
    EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u) << page.substr(0, 80);
    EXPECT_NE(page.find("05.01.01.01.22.00"), std::string::npos);
    EXPECT_NE(page.find("encoding.int"), std::string::npos);
    EXPECT_EQ(page.find("<script src="), std::string::npos);  // nothing fetched from elsewhere
    // A node's text cannot open a tag inside the page's script.
    EXPECT_EQ(page.find("<differ>"), std::string::npos);
    EXPECT_NE(page.find("\\u003cdiffer\\u003e"), std::string::npos);
}

}  // namespace
}  // namespace olcb::conform
