// The client audit's files: JSON with every finding in full, JUnit XML with one testcase per
// rule, both written through a temporary file.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "audit_script.hpp"
#include "simnode/audit/audit_report.hpp"

namespace olcb::simnode::audit::test {
namespace {

using nlohmann::json;

class AuditReport : public AuditScript {
protected:
    // One error (a write out of range), one note (a read past the end), one warning (no Update
    // Complete).
    void violate() {
        login();
        client_datagram(write_cmd(0xFD, 1, {0x07, 0xD0}));
        node_ok(0);
        client_datagram(read_cmd(0xFD, 400, 8));
        node(":X19A48343N012C1082;");
        advance(1s);
        finish();
    }
};
TEST_F(AuditReport, TheJsonNamesRuleStandardClientNodeFramesAndTime) {
    violate();
    const json j = json::parse(audit_json(audit_.log(), {"2024-07-04T17:38:48Z", true}));
    EXPECT_EQ(j["started"], "2024-07-04T17:38:48Z");
    EXPECT_EQ(j["complete"], true);
    EXPECT_EQ(j["rules"].size(), rules().size());
    EXPECT_EQ(j["summary"]["errors"], 1);
    EXPECT_EQ(j["summary"]["warnings"], 1);
    EXPECT_EQ(j["summary"]["notes"], 1);
    ASSERT_EQ(j["findings"].size(), 3u);
    const json& f = j["findings"][0];
    EXPECT_EQ(f["rule"], "cdi.int-out-of-range");
    EXPECT_EQ(f["level"], "error");
    EXPECT_EQ(f["standard"], "CDI §5.1.4.2");
    EXPECT_EQ(f["client"]["alias"], "0x12C");
    EXPECT_EQ(f["client"]["node_id"], "02.01.0D.00.00.01");
    EXPECT_EQ(f["client"]["remote"], "127.0.0.1:50000");
    EXPECT_EQ(f["client"]["connection"], kConnection);
    EXPECT_EQ(f["node"]["node_id"], "05.01.01.01.22.00");
    EXPECT_EQ(f["node"]["alias"], "0x343");
    EXPECT_EQ(f["frames"], json::array({":X1A34312CN20010000000107D0;"}));
    EXPECT_EQ(f["count"], 1);
    EXPECT_DOUBLE_EQ(f["time"].get<double>(), 0.2);  // after the 200 ms of the login
    EXPECT_EQ(j["findings"][2]["rule"], "memory.no-update-complete");
}

TEST(AuditFiles, AFindingWithBadUtf8StillGivesValidFiles) {
    const TimePoint now{};
    FindingLog log(now);
    Finding f;
    f.rule = RuleId::kCdiStringInvalid;
    f.message = "wrote \xC3( to a string";
    log.add(f, "", now);
    EXPECT_FALSE(json::parse(audit_json(log, {"x", true})).is_discarded());
    pugi::xml_document doc;
    EXPECT_TRUE(doc.load_string(audit_junit(log, {"x", true}).c_str()));
    EXPECT_NE(std::string(doc.select_node("//failure").node().attribute("message").value())
                  .find("wrote \xEF\xBF\xBD( to"),  // U+FFFD for the bad byte
              std::string::npos);
}

TEST_F(AuditReport, TheJunitHasOneTestcasePerRuleAndFailsOnlyOnErrors) {
    violate();
    const std::string xml = audit_junit(audit_.log(), {"2024-07-04T17:38:48Z", true});
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_string(xml.c_str())) << xml;
    const auto suite = doc.child("testsuites").child("testsuite");
    EXPECT_EQ(suite.attribute("tests").as_ullong(), rules().size());
    EXPECT_EQ(suite.attribute("failures").as_int(), 1);
    std::vector<std::string> names;
    for (auto tc : suite.children("testcase")) names.emplace_back(tc.attribute("name").value());
    ASSERT_EQ(names.size(), rules().size());
    for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(names[i], rules()[i].name);
    const auto failing = suite.find_child_by_attribute("testcase", "name", "cdi.int-out-of-range");
    ASSERT_TRUE(failing.child("failure"));
    EXPECT_NE(
        std::string(failing.child("failure").text().get()).find(":X1A34312CN20010000000107D0;"),
        std::string::npos);
    const auto warned = suite.find_child_by_attribute("testcase", "name", "memory.read-past-end");
    EXPECT_FALSE(warned.child("failure"));
    EXPECT_TRUE(warned.child("system-out"));
    const auto clean = suite.find_child_by_attribute("testcase", "name", "alias.unreserved");
    EXPECT_FALSE(clean.first_child());
}

}  // namespace
}  // namespace olcb::simnode::audit::test
