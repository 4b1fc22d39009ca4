// check_fdi_rules(): the text rules of FunctionDescriptionInformationS §5 under fdi.* IDs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/fdi_validator.hpp"
#include "cdi/rule_finding.hpp"

namespace olcb::cdi {
namespace {

using test::fdi_function;
using test::fdi_text;
using ::testing::HasSubstr;

// A copy: callers pass the findings of a call as a temporary.
RuleFinding rule(const std::vector<RuleFinding>& findings, std::string_view id) {
    for (const RuleFinding& f : findings)
        if (f.check_id == id) return f;
    ADD_FAILURE() << "no finding " << id;
    return {};
}

TEST(CheckFdiRules, OneFindingPerRuleInOrderEachWithItsClause) {
    const std::string text = fdi_text(fdi_function(0)) + '\0';
    const auto findings = check_fdi_rules(text);
    ASSERT_EQ(findings.size(), kFdiRuleCheckIds.size());
    for (std::size_t i = 0; i < findings.size(); ++i) {
        EXPECT_EQ(findings[i].check_id, kFdiRuleCheckIds[i]);
        EXPECT_EQ(findings[i].status, RuleStatus::kPass) << findings[i].message;
        EXPECT_EQ(findings[i].clause, "FunctionDescriptionInformationS §5");
    }
    EXPECT_EQ(rule(findings, "fdi.schema-location").message,
              "schema location names an openlcb.org FDI schema");
    // The same result from a validation the caller keeps.
    const auto again = check_fdi_rules(text, validate_fdi(text));
    ASSERT_EQ(again.size(), findings.size());
    for (std::size_t i = 0; i < again.size(); ++i) EXPECT_EQ(again[i].message, findings[i].message);
}

TEST(CheckFdiRules, CdiFindingsCarryNoClauseOfTheirOwn) {
    for (const RuleFinding& f : check_rules("<?xml version=\"1.0\"?>\n<cdi/>\n"))
        EXPECT_EQ(f.clause, "") << f.check_id;
}

TEST(CheckFdiRules, TheSharedTextRulesSpeakOfAnFdi) {
    const std::string body = fdi_text(fdi_function(0));
    const std::string rest = body.substr(body.find('\n') + 1);
    EXPECT_EQ(rule(check_fdi_rules("\xEF\xBB\xBF" + body), "fdi.no-bom").status, RuleStatus::kFail);
    const RuleFinding encoding =
        rule(check_fdi_rules("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n" + rest),
             "fdi.xml-declaration");
    EXPECT_EQ(encoding.status, RuleStatus::kFail);
    EXPECT_THAT(encoding.message, HasSubstr("an FDI's bytes are UTF-8"));
    const RuleFinding version =
        rule(check_fdi_rules("<?xml version=\"1.1\"?>\n" + rest), "fdi.xml-declaration");
    EXPECT_THAT(version.message, HasSubstr("an FDI is XML 1.0"));
    const auto bad_utf8 = check_fdi_rules(fdi_text(fdi_function(0, "\xC3(")));
    EXPECT_EQ(rule(bad_utf8, "fdi.utf8").status, RuleStatus::kFail);
    EXPECT_EQ(rule(bad_utf8, "fdi.utf8").line, 4U);
}

TEST(CheckFdiRules, ValidityAndWellFormedness) {
    const auto invalid = check_fdi_rules(fdi_text(fdi_function(16777216)));
    const RuleFinding valid = rule(invalid, "fdi.valid");
    EXPECT_EQ(valid.status, RuleStatus::kFail);
    EXPECT_EQ(valid.line, 4U);
    EXPECT_THAT(valid.message,
                HasSubstr("1 error(s), 0 warning(s); first: line 4: FDI 1.1 schema:"));

    const auto broken = check_fdi_rules("<?xml version=\"1.0\"?>\n<fdi><segment></fdi>\n");
    EXPECT_EQ(rule(broken, "fdi.well-formed").status, RuleStatus::kFail);
    EXPECT_EQ(rule(broken, "fdi.valid").status, RuleStatus::kSkip);
    EXPECT_EQ(rule(broken, "fdi.valid").message, "depends on fdi.well-formed: the text is not XML");
    EXPECT_EQ(rule(broken, "fdi.schema-location").status, RuleStatus::kSkip);

    const auto warned = check_fdi_rules(fdi_text(fdi_function(0) + fdi_function(0)));
    EXPECT_EQ(rule(warned, "fdi.valid").status, RuleStatus::kWarn);
}

TEST(CheckFdiRules, SchemaLocation) {
    const auto none = check_fdi_rules(fdi_text(fdi_function(0), -1));
    EXPECT_EQ(rule(none, "fdi.schema-location").status, RuleStatus::kWarn);
    std::string old = fdi_text(fdi_function(0), -1);
    old.replace(old.find("\">"), 2,
                "\" xsi:noNamespaceSchemaLocation='http://openlcb.org/trunk/prototypes/xml/"
                "schema/fdi.xsd'>");
    const RuleFinding prototype = rule(check_fdi_rules(old), "fdi.schema-location");
    EXPECT_EQ(prototype.status, RuleStatus::kWarn);
    EXPECT_THAT(prototype.message,
                HasSubstr("does not name http(s)://openlcb.org/schema/fdi/.../fdi.xsd"));
    // xs:anyURI collapses whitespace: a location with a leading blank names the same URL.
    std::string blank = fdi_text(fdi_function(0));
    blank.replace(blank.find("\"https://"), 1, "\" ");
    EXPECT_EQ(rule(check_fdi_rules(blank), "fdi.schema-location").status, RuleStatus::kPass);
}

}  // namespace
}  // namespace olcb::cdi
