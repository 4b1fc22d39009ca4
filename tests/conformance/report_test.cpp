#include "conformance/report.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <sstream>

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

TEST(ToJson, HasNodeChecksAndSummary) {
    auto j = nlohmann::json::parse(to_json({sample()}));
    EXPECT_EQ(j["node"]["id"], "05.01.01.01.22.00");
    ASSERT_EQ(j["checks"].size(), 4u);
    EXPECT_EQ(j["checks"][1]["id"], "encoding.int");
    EXPECT_EQ(j["checks"][1]["category"], "encoding");
    EXPECT_EQ(j["checks"][1]["status"], "FAIL");
    EXPECT_EQ(j["checks"][1]["section"], "CDI S 5.1.4.2");
    EXPECT_EQ(j["summary"]["fail"], 1);
    EXPECT_EQ(j["summary"]["total"], 4);
    auto many = nlohmann::json::parse(to_json({sample(), sample()}));
    EXPECT_EQ(many["nodes"].size(), 2u);
    EXPECT_EQ(many["summary"]["fail"], 2);
}

TEST(ToJson, InvalidUtf8FromTheNodeIsReplacedNotFatal) {
    NodeReport r = sample();
    r.name = "bad\xff\xfename";
    r.checks[0].message = "user name \"bad\xff\xfename\"";
    const std::string text = to_json({r});
    const auto j = nlohmann::json::parse(text, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << text;
    EXPECT_EQ(j["node"]["name"], "bad\xEF\xBF\xBD\xEF\xBF\xBDname");  // two U+FFFD
}

TEST(ToJunit, WellFormedOneTestcasePerCheck) {
    std::string xml = to_junit({sample()});
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_string(xml.c_str())) << xml;
    auto suite = doc.child("testsuites").child("testsuite");
    ASSERT_TRUE(suite);
    EXPECT_EQ(suite.attribute("tests").as_int(), 4);
    EXPECT_EQ(suite.attribute("failures").as_int(), 1);
    EXPECT_EQ(suite.attribute("skipped").as_int(), 1);
    int cases = 0;
    for (auto tc : suite.children("testcase")) {
        ++cases;
        std::string name = tc.attribute("name").as_string();
        EXPECT_EQ(static_cast<bool>(tc.child("failure")), name == "encoding.int") << name;
        EXPECT_EQ(static_cast<bool>(tc.child("skipped")), name == "encoding.blob") << name;
    }
    EXPECT_EQ(cases, 4);
    EXPECT_EQ(xml.find('\x01'), std::string::npos);
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
