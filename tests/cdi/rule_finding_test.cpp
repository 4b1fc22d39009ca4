#include "cdi/rule_finding.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/validator.hpp"
#include "support/temp_files.hpp"

namespace olcb::cdi {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRoot =
    "<cdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
    "xsi:noNamespaceSchemaLocation=\"http://openlcb.org/schema/cdi/1/4/cdi.xsd\">\n";
constexpr const char* kBody =
    "<segment space=\"253\"><int size=\"2\"><name>A</name></int></segment>\n</cdi>\n";

std::string cdi_with(const std::string& first_line) {
    return first_line + (first_line.empty() ? "" : "\n") + kRoot + kBody;
}

RuleFinding rule(const std::vector<RuleFinding>& findings, std::string_view id) {
    for (const RuleFinding& f : findings)
        if (f.check_id == id) return f;
    static const RuleFinding missing = [] {
        RuleFinding f;
        f.check_id = "(missing)";
        return f;
    }();
    ADD_FAILURE() << "no finding " << id;
    return missing;
}

std::string listing(const std::vector<RuleFinding>& findings) {
    std::string out;
    for (const RuleFinding& f : findings)
        out += std::string(rule_status_name(f.status)) + " " + f.check_id + " " + f.message + "\n";
    return out;
}

TEST(CheckRules, OneFindingPerRuleInRegistryOrder) {
    const auto findings = check_rules(cdi_with("<?xml version=\"1.0\"?>"));
    ASSERT_EQ(findings.size(), kRuleCheckIds.size());
    for (std::size_t i = 0; i < findings.size(); ++i)
        EXPECT_EQ(findings[i].check_id, kRuleCheckIds[i]);
}

TEST(CheckRules, ACleanCdiPassesEveryRuleItHas) {
    const auto findings = check_rules(cdi_with("<?xml version=\"1.0\"?>") + '\0' + '\0');
    for (const RuleFinding& f : findings) {
        if (f.check_id == "cdi.acdi-spaces") {
            EXPECT_EQ(f.status, RuleStatus::kSkip) << f.message;  // no <acdi/>
        } else {
            EXPECT_EQ(f.status, RuleStatus::kPass) << listing(findings);
        }
    }
}

// lcc-conform judges the rules with the validation it keeps for its model: the verdicts on the
// model come from that validation, those on the bytes from the text.
TEST(CheckRules, WithAKeptValidationJudgesThatValidation) {
    const std::string clean = cdi_with("<?xml version=\"1.0\"?>");
    const std::string malformed = "<cdi><segment space=\"253\"><int size=\"9\"/></segment>";
    const auto kept = check_rules(clean + '\0', validate_model(clean));
    for (const RuleFinding& f : kept) {
        const RuleStatus expected =
            f.check_id == "cdi.acdi-spaces" ? RuleStatus::kSkip : RuleStatus::kPass;
        EXPECT_EQ(f.status, expected) << listing(kept);
    }
    // Not parsed again: a validation of other text is what the model rules judge.
    const auto other = check_rules(clean, validate_model(malformed));
    EXPECT_EQ(rule(other, "cdi.well-formed").status, RuleStatus::kFail) << listing(other);
    EXPECT_EQ(rule(other, "cdi.xml-declaration").status, RuleStatus::kPass) << listing(other);

    const std::string acdi_conflict =
        std::string("<?xml version=\"1.0\"?>\n") + kRoot +
        "<acdi/><segment space=\"251\"><int size=\"2\"><name>V</name></int></segment>\n</cdi>\n";
    const auto conflict = check_rules(acdi_conflict, validate_model(acdi_conflict));
    EXPECT_EQ(rule(conflict, "cdi.acdi-spaces").status, RuleStatus::kWarn) << listing(conflict);
}

TEST(XmlDeclarationRule, NoDeclarationFailsOnLineOne) {
    const RuleFinding f = rule(check_rules(cdi_with("")), "cdi.xml-declaration");
    EXPECT_EQ(f.status, RuleStatus::kFail);
    EXPECT_EQ(f.line, 1U);
    EXPECT_EQ(f.expected, "<?xml version=\"1.0\"?>");
    EXPECT_EQ(f.seen.substr(0, 5), "\"<cdi");
}

TEST(XmlDeclarationRule, SameVersionAndUtf8InOtherWordsWarns) {
    for (const char* first :
         {"<?xml version=\"1.0\" encoding=\"utf-8\"?>", "<?xml version='1.0' encoding='UTF-8'?>",
          "<?xml version='1.0'?>", "<?xml version=\"1.0\" standalone=\"yes\"?>"}) {
        const RuleFinding f = rule(check_rules(cdi_with(first)), "cdi.xml-declaration");
        EXPECT_EQ(f.status, RuleStatus::kWarn) << first;
        EXPECT_EQ(f.message, std::string("first line is an XML declaration other than <?xml "
                                         "version=\"1.0\"?>: ") +
                                 first);
    }
}

TEST(XmlDeclarationRule, AnotherEncodingOrVersionFails) {
    const RuleFinding latin =
        rule(check_rules(cdi_with("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>")),
             "cdi.xml-declaration");
    EXPECT_EQ(latin.status, RuleStatus::kFail);
    EXPECT_NE(latin.message.find("encoding ISO-8859-1"), std::string::npos) << latin.message;
    const RuleFinding v11 =
        rule(check_rules(cdi_with("<?xml version=\"1.1\"?>")), "cdi.xml-declaration");
    EXPECT_EQ(v11.status, RuleStatus::kFail);
    EXPECT_NE(v11.message.find("XML 1.1"), std::string::npos) << v11.message;
}

TEST(XmlDeclarationRule, ABomIsNoBomsFindingAlone) {
    const auto findings = check_rules("\xEF\xBB\xBF" + cdi_with("<?xml version=\"1.0\"?>"));
    EXPECT_EQ(rule(findings, "cdi.no-bom").status, RuleStatus::kFail);
    EXPECT_EQ(rule(findings, "cdi.xml-declaration").status, RuleStatus::kPass);
}

TEST(XmlDeclarationRule, CrlfLinesAndOneLineCdisPass) {
    std::string crlf = cdi_with("<?xml version=\"1.0\"?>\r");
    EXPECT_EQ(rule(check_rules(crlf), "cdi.xml-declaration").status, RuleStatus::kPass);
    std::string one = cdi_with("<?xml version=\"1.0\"?>");
    std::replace(one.begin(), one.end(), '\n', ' ');
    EXPECT_EQ(rule(check_rules(one), "cdi.xml-declaration").status, RuleStatus::kPass);
}

TEST(Utf8Rule, NamesTheOffsetLineAndBytes) {
    std::string text = cdi_with("<?xml version=\"1.0\"?>");
    const std::size_t at = text.find("<name>A") + 6;
    text.replace(at, 1, "\xFF\xFE");
    const RuleFinding f = rule(check_rules(text), "cdi.utf8");
    EXPECT_EQ(f.status, RuleStatus::kFail);
    EXPECT_EQ(f.line, 3U);
    EXPECT_EQ(f.seen.substr(0, 5), "FF FE");
    EXPECT_NE(f.message.find("offset " + std::to_string(at)), std::string::npos) << f.message;
}

TEST(Utf8Rule, IsTheCauseWhereLibxml2StopsAtTheInvalidByte) {
    std::string text = cdi_with("<?xml version=\"1.0\"?>");
    text.insert(text.find("<name>A") + 6, "\xFF");
    const auto findings = check_rules(text);
    EXPECT_EQ(rule(findings, "cdi.utf8").status, RuleStatus::kFail);
    const RuleFinding f = rule(findings, "cdi.well-formed");
    EXPECT_EQ(f.status, RuleStatus::kSkip);
    EXPECT_EQ(f.message.rfind("depends on cdi.utf8", 0), 0U) << f.message;
    EXPECT_EQ(rule(findings, "cdi.valid").status, RuleStatus::kSkip);

    // A parse error on a line before the invalid byte's has a cause of its own.
    std::string both = text;
    both.insert(both.find("xmlns:xsi"), "<");
    EXPECT_EQ(rule(check_rules(both), "cdi.well-formed").status, RuleStatus::kFail);
}

TEST(ValidRule, FailsWithEveryDiagnosticErrorsFirst) {
    const std::string text = std::string("<?xml version=\"1.0\"?>\n") + kRoot +
                             "<segment space=\"253\">\n"               // 3
                             "<int size=\"3\"><name>A</name></int>\n"  // 4
                             "</segment>\n</cdi>\n";
    const RuleFinding f = rule(check_rules(text), "cdi.valid");
    EXPECT_EQ(f.status, RuleStatus::kFail);
    EXPECT_EQ(f.line, 4U);
    ASSERT_FALSE(f.diagnostics.empty());
    EXPECT_EQ(f.diagnostics.front().severity, Severity::kError);
    EXPECT_EQ(f.seen, located(f.diagnostics.front()));
    EXPECT_EQ(f.message.find(std::to_string(f.diagnostics.size()) + " error(s), 0 warning(s)"), 0U)
        << f.message;
}

TEST(WellFormedRule, QuotesTheFirstParseError) {
    const auto findings = check_rules(std::string("<?xml version=\"1.0\"?>\n") + kRoot +
                                      "<segment space=\"253\">\n</cdi>\n");
    const RuleFinding f = rule(findings, "cdi.well-formed");
    EXPECT_EQ(f.status, RuleStatus::kFail);
    EXPECT_NE(f.seen.find("XML parse error"), std::string::npos) << f.seen;
    EXPECT_FALSE(f.diagnostics.empty());
    EXPECT_EQ(rule(findings, "cdi.valid").status, RuleStatus::kSkip);  // one cause, one FAIL
    EXPECT_EQ(rule(findings, "cdi.schema-location").status, RuleStatus::kSkip);
    EXPECT_EQ(rule(findings, "cdi.acdi-spaces").status, RuleStatus::kSkip);
}

// The standard shows the URL but sets no rule for other spellings: both cases are notes.
TEST(SchemaLocationRule, WarnsWhenAbsentOrForeign) {
    const std::string body = kBody;
    EXPECT_EQ(
        rule(check_rules("<?xml version=\"1.0\"?>\n<cdi>\n" + body), "cdi.schema-location").status,
        RuleStatus::kWarn);
    const std::string foreign =
        "<?xml version=\"1.0\"?>\n<cdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
        "xsi:noNamespaceSchemaLocation=\"http://example.com/cdi.xsd\">\n" +
        body;
    const RuleFinding f = rule(check_rules(foreign), "cdi.schema-location");
    EXPECT_EQ(f.status, RuleStatus::kWarn);
    EXPECT_NE(f.message.find("http://example.com/cdi.xsd"), std::string::npos) << f.message;
}

// §5.1.2 lets a CDI describe 252/251 as segments too (the TN's own example lays the version
// ints at byte 0): only variables that contradict the ACDI layout are noted.
TEST(AcdiSpacesRule, SegmentsThatFollowTheAcdiLayoutPass) {
    const std::string text =
        std::string("<?xml version=\"1.0\"?>\n") + kRoot +
        "<acdi/>\n<segment space=\"252\"><int size=\"1\"><name>Version</name></int>"
        "<string size=\"41\"><name>Manufacturer</name></string></segment>\n"
        "<segment space=\"251\"><int size=\"1\"/><string size=\"63\"><name>Name</name></string>"
        "<string size=\"64\"><name>Description</name></string></segment>\n</cdi>\n";
    EXPECT_EQ(rule(check_rules(text), "cdi.acdi-spaces").status, RuleStatus::kPass);
}

TEST(AcdiSpacesRule, VariablesAcrossAnAcdiFieldWarn) {
    const std::string text = std::string("<?xml version=\"1.0\"?>\n") + kRoot +
                             "<acdi/>\n<segment space=\"252\"><int size=\"4\"><name>Speed</name>"
                             "</int></segment>\n</cdi>\n";
    const RuleFinding f = rule(check_rules(text), "cdi.acdi-spaces");
    EXPECT_EQ(f.status, RuleStatus::kWarn);
    EXPECT_NE(f.message.find("Speed (space 252 bytes 0..3)"), std::string::npos) << f.message;
}

using test_support::read_text;

// The project's own sample CDIs are what it tells CDI authors to write.
TEST(CheckRules, EveryScenarioCdiHasNoFinding) {
    int files = 0;
    for (const auto& e : fs::directory_iterator(fs::path(OLCB_SOURCE_DIR) / "scenarios")) {
        if (e.path().extension() != ".xml") continue;
        ++files;
        for (const RuleFinding& f : check_rules(read_text(e.path()))) {
            EXPECT_TRUE(f.status == RuleStatus::kPass || f.status == RuleStatus::kSkip)
                << e.path().filename() << ": " << rule_status_name(f.status) << " " << f.check_id
                << " " << f.message;
        }
    }
    EXPECT_GE(files, 3);
}

// A valid CDI of 200 or 1,000 nested groups passes the well-formedness and validity rules (deep
// nesting: parser_test.cpp).
class RuleFindingDeepNesting : public ::testing::TestWithParam<std::size_t> {};

TEST_P(RuleFindingDeepNesting, WellFormedAndValidDoNotFail) {
    const std::string text = test::nested_cdi(GetParam());
    for (const RuleFinding& f : check_rules(text)) {
        if (f.check_id == "cdi.valid" || f.check_id == "cdi.well-formed") {
            EXPECT_NE(f.status, RuleStatus::kFail) << f.check_id << ": " << f.message;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Depths, RuleFindingDeepNesting,
                         ::testing::ValuesIn(test::kValidNestingDepths));

}  // namespace
}  // namespace olcb::cdi
