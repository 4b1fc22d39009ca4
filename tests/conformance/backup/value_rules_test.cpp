// The CDI's rules a restored value must keep: each rule named, the bytes a forced write would
// store, and values judged by what their bytes hold (an unsigned form of a signed int).
#include "conformance/backup/value_rules.hpp"

#include <gtest/gtest.h>

#include "conformance/backup_test_util.hpp"

namespace olcb::conform {
namespace {

constexpr const char* kRulesCdi = R"(<?xml version="1.0"?>
<cdi><segment space="253"><name>S</name>
<int size="2"><name>Trim</name><min>-1000</min><max>1000</max></int>
<int size="1"><name>Mode</name>
<map><relation><property>1</property><value>A</value></relation>
<relation><property>3</property><value>B</value></relation></map></int>
<string size="8"><name>Label</name></string>
<eventid><name>Ev</name></eventid>
<eventid><name>Pick</name><map><relation><property>01.02.03.04.05.06.07.08</property>
<value>One</value></relation></map></eventid>
<float size="4"><name>Gain</name><min>0</min><max>4</max></float>
<int size="4"><name>Delay</name><max>600000</max></int>
</segment></cdi>)";

class ValueRulesTest : public ::testing::Test {
protected:
    const cdi::Element& element(const std::string& key) {
        for (const ConfigEntry& e : entries_) {
            if (e.key == key) return *e.element;
        }
        ADD_FAILURE() << "no " << key;
        return *entries_.front().element;
    }
    ValueVerdict judge(const std::string& key, std::string_view text) {
        return judge_backup_value(element(key), text);
    }
    testing::Cdi cdi_{kRulesCdi};
    std::vector<ConfigEntry> entries_ = config_entries(*cdi_.layout);
};

TEST_F(ValueRulesTest, ValuesWithinTheRulesAreAllowed) {
    for (const auto& [key, text] : std::vector<std::pair<std::string, std::string>>{
             {"S.Trim", "-5"},
             {"S.Trim", "65531"},  // OpenLCB_Java's unsigned form of -5
             {"S.Trim", "1000"},
             {"S.Mode", "3"},
             {"S.Label", "1234567"},
             {"S.Label", "\xC3\xA9t\xC3\xA9"},
             {"S.Ev", "05.01.01.01.22.00.00.01"},
             {"S.Pick", "0102030405060708"},
             {"S.Gain", "4"},
             {"S.Delay", "600000"}}) {
        const ValueVerdict v = judge(key, text);
        EXPECT_TRUE(v.allowed()) << key << "=" << text << ": " << v.why;
        EXPECT_TRUE(v.bytes) << key;
    }
}

TEST_F(ValueRulesTest, EachRuleIsNamedWithItsClause) {
    struct Case {
        const char* key;
        std::string text;
        ValueRule rule;
        bool forcible;
        const char* clause;
    };
    const std::vector<Case> cases = {
        {"S.Trim", "2000", ValueRule::kOutOfRange, true, "CDI §5.1.4.2"},
        {"S.Trim", "40000", ValueRule::kOutOfRange, true, "CDI §5.1.4.2"},   // -25536 stored
        {"S.Trim", "70000", ValueRule::kOutOfRange, false, "CDI §5.1.4.2"},  // fits no form
        {"S.Trim", "12a", ValueRule::kMalformed, false, "CDI §5.1.4.2"},
        {"S.Delay", "600001", ValueRule::kOutOfRange, true, "CDI §5.1.4.2"},
        {"S.Mode", "7", ValueRule::kNotInMap, true, "CDI §5.1.4.2"},
        {"S.Label", "12345678", ValueRule::kTooLong, true, "CDI §5.1.4.3"},  // no room for NUL
        {"S.Label", "123456789", ValueRule::kTooLong, false, "CDI §5.1.4.3"},
        {"S.Label", "ab\xC3", ValueRule::kNotUtf8, true, "CDI §5.1.4.3"},
        {"S.Ev", "05.01.01.01.22.0", ValueRule::kMalformed, false, "CDI §5.1.4.4"},
        {"S.Ev", "x", ValueRule::kMalformed, false, "CDI §5.1.4.4"},
        {"S.Pick", "01.02.03.04.05.06.07.09", ValueRule::kNotInMap, true, "CDI §5.1.4.4"},
        {"S.Gain", "4.5", ValueRule::kOutOfRange, true, "CDI §5.1.4.5"},
        {"S.Gain", "nan", ValueRule::kOutOfRange, true, "CDI §5.1.4.5"},
        {"S.Gain", "1e99", ValueRule::kOutOfRange, false, "CDI §5.1.4.5"},
        {"S.Gain", "one", ValueRule::kMalformed, false, "CDI §5.1.4.5"},
    };
    for (const Case& c : cases) {
        const ValueVerdict v = judge(c.key, c.text);
        ASSERT_TRUE(v.broken) << c.key << "=" << c.text;
        EXPECT_EQ(rule_name(*v.broken), rule_name(c.rule))
            << c.key << "=" << c.text << ": " << v.why;
        EXPECT_EQ(v.forcible(), c.forcible) << c.key << "=" << c.text;
        EXPECT_EQ(v.clause.rfind(std::string(c.clause) + ": ", 0), 0u) << c.key << ": " << v.clause;
        EXPECT_FALSE(v.why.empty()) << c.key;
    }
}

TEST_F(ValueRulesTest, TheWhySaysWhatTheCdiAllows) {
    EXPECT_EQ(judge("S.Trim", "2000").why, "value 2000 above max 1000 of 'Trim'");
    EXPECT_NE(judge("S.Mode", "7").why.find("not one of the map properties (1, 3)"),
              std::string::npos);
    EXPECT_EQ(judge("S.Label", "ab\xC3").why,
              "'Label': the text ends inside a UTF-8 character (byte 2)");
    EXPECT_EQ(judge("S.Label",
                    "a\xFF"
                    "b")
                  .why,
              "'Label': the text is not valid UTF-8 (byte 1)");
    EXPECT_EQ(judge("S.Trim", "2000").clause, "CDI §5.1.4.2: invalid values shall not be written");
    EXPECT_EQ(judge("S.Label", "12345678").clause,
              "CDI §5.1.4.3: a string shall be written with a trailing NUL");
    EXPECT_TRUE(judge("S.Trim", "5").clause.empty());
    const ValueVerdict forced = judge("S.Trim", "2000");
    EXPECT_EQ(*forced.bytes, (std::vector<std::uint8_t>{0x07, 0xD0}));
}

}  // namespace
}  // namespace olcb::conform
