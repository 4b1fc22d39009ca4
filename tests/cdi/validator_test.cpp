// The whole check of a CDI (cdi/validator.cpp): schema, model parser, semantic rules and layout
// merged into one report sorted by line, and the model kept for rules judged on it.
#include "cdi/validator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "cdi/cdi_test_util.hpp"

namespace olcb::cdi {
namespace {

using test::first_error_text;
using test::listing;

const char* const kHeader =
    "<?xml version=\"1.0\"?>\n"
    "<cdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
    "xsi:noNamespaceSchemaLocation=\"http://openlcb.org/schema/cdi/1/4/cdi.xsd\">\n";

TEST(CombinedValidator, CleanCdiHasNoFindings) {
    const std::string text = std::string(kHeader) +
                             "<segment space=\"253\"><int size=\"2\"><name>A</name><min>1</min>"
                             "<max>9</max><default>3</default></int></segment>\n</cdi>\n";
    const ValidationReport report = validate(text + '\0');
    EXPECT_THAT(report.diagnostics, ::testing::IsEmpty()) << listing(report.diagnostics);
    EXPECT_TRUE(report.ok());
    EXPECT_TRUE(report.parsed);
    EXPECT_EQ(report.schema.version, SchemaVersion::kV1_4);
    EXPECT_TRUE(report.schema.declared);
}

TEST(CombinedValidator, MergesSchemaAndSemanticFindingsByLine) {
    const std::string text = std::string(kHeader) +
                             "<segment space=\"253\">\n"                           // 3
                             "<int size=\"1\"><default>300</default></int>\n"      // 4
                             "<int size=\"3\"/>\n"                                 // 5
                             "<int size=\"1\"><hints><checkbox/></hints></int>\n"  // 6
                             "</segment>\n</cdi>\n";
    const ValidationReport report = validate(text);
    ASSERT_TRUE(report.parsed) << listing(report.diagnostics);
    std::vector<std::uint32_t> lines;
    for (const Diagnostic& d : report.diagnostics) lines.push_back(d.line);
    EXPECT_TRUE(std::is_sorted(lines.begin(), lines.end()));
    const auto has = [&](std::uint32_t line, const char* text) {
        return std::any_of(report.diagnostics.begin(), report.diagnostics.end(),
                           [&](const Diagnostic& d) {
                               return d.line == line && d.severity == Severity::kError &&
                                      d.message.find(text) != std::string::npos;
                           });
    };
    EXPECT_TRUE(has(4, "default 300 does not fit")) << listing(report.diagnostics);
    EXPECT_TRUE(has(5, "CDI 1.4 schema:")) << listing(report.diagnostics);
    EXPECT_TRUE(has(5, "int size must be 1, 2, 4, or 8")) << listing(report.diagnostics);
    EXPECT_TRUE(has(6, "checkbox")) << listing(report.diagnostics);
}

TEST(CombinedValidator, MalformedXmlIsReportedOnceByLibxml2) {
    const ValidationReport report =
        validate(std::string(kHeader) + "<segment space=\"1\">\n</cdi>");
    EXPECT_FALSE(report.parsed);
    EXPECT_FALSE(report.schema.well_formed);
    ASSERT_FALSE(report.diagnostics.empty());
    for (const Diagnostic& d : report.diagnostics) {
        EXPECT_EQ(d.message.rfind("XML parse error: ", 0), 0u) << d.message;
    }
}

TEST(CombinedValidator, DoctypeIsRefused) {
    const ValidationReport report =
        validate("<?xml version=\"1.0\"?>\n<!DOCTYPE cdi [<!ENTITY a \"b\">]>\n<cdi/>\n");
    EXPECT_FALSE(report.ok());
    EXPECT_TRUE(std::any_of(
        report.diagnostics.begin(), report.diagnostics.end(),
        [](const Diagnostic& d) { return d.message.find("DOCTYPE") != std::string::npos; }));
}

TEST(CombinedValidator, WarningsAloneLeaveTheReportOk) {
    // No schemaLocation: validated against the newest schema, with a warning on the root's line.
    const ValidationReport report = validate(
        "<?xml version=\"1.0\"?>\n<cdi>\n<segment space=\"253\"><int size=\"1\"/></segment>\n"
        "</cdi>\n");
    EXPECT_TRUE(report.ok()) << listing(report.diagnostics);
    EXPECT_TRUE(report.parsed);
    EXPECT_FALSE(report.schema.declared);
    EXPECT_EQ(report.schema.version, kNewestSchema);
    ASSERT_FALSE(report.diagnostics.empty());
    EXPECT_TRUE(std::all_of(report.diagnostics.begin(), report.diagnostics.end(),
                            [](const Diagnostic& d) { return d.severity == Severity::kWarning; }));
    EXPECT_THAT(report.diagnostics,
                ::testing::Contains(::testing::Field(
                    &Diagnostic::message, ::testing::HasSubstr("no schema version declared"))));
}

TEST(ValidateModel, KeepsTheDocumentAndItsLayout) {
    const ValidatedCdi checked =
        validate_model(std::string(kHeader) +
                       "<segment space=\"253\" origin=\"16\"><int size=\"2\"><name>A</name></int>"
                       "<eventid><name>B</name></eventid></segment>\n</cdi>\n");
    EXPECT_TRUE(checked.report.ok()) << listing(checked.report.diagnostics);
    ASSERT_TRUE(checked.document);
    ASSERT_EQ(checked.document->segments.size(), 1u);
    ASSERT_TRUE(checked.layout);
    EXPECT_EQ(checked.layout->variable_count(), 2u);
    EXPECT_EQ(&checked.layout->document(), checked.document.get());
    EXPECT_EQ(checked.layout->at(1).address(), 18u);
    EXPECT_EQ(checked.layout->at(1).path(), "(space 253)/B");
}

TEST(ValidateModel, ALayoutErrorKeepsTheDocumentButNoLayout) {
    const ValidatedCdi checked =
        validate_model(std::string(kHeader) +
                       "<segment space=\"253\" origin=\"4294967295\">\n<int size=\"2\"/>\n"
                       "</segment>\n</cdi>\n");
    EXPECT_FALSE(checked.report.ok());
    EXPECT_TRUE(checked.report.parsed);
    EXPECT_TRUE(checked.document);
    EXPECT_FALSE(checked.layout);
    EXPECT_THAT(checked.report.diagnostics,
                ::testing::Contains(::testing::AllOf(
                    ::testing::Field(&Diagnostic::line, 4u),
                    ::testing::Field(&Diagnostic::message, ::testing::HasSubstr("4294967297")))))
        << listing(checked.report.diagnostics);
}

TEST(ValidateModel, TextThatIsNotXmlHasNeitherDocumentNorLayout) {
    const ValidatedCdi checked = validate_model("<cdi><segment space=\"253\">");
    EXPECT_FALSE(checked.report.ok());
    EXPECT_FALSE(checked.report.parsed);
    EXPECT_FALSE(checked.report.schema.well_formed);
    EXPECT_FALSE(checked.document);
    EXPECT_FALSE(checked.layout);
}

// Deep nesting: a valid CDI of 200 or 1,000 nested groups validates like any other; nesting
// beyond the parser's limit is refused (the parser's side: parser_test.cpp).
class ValidatorDeepNesting : public ::testing::TestWithParam<std::size_t> {};

TEST_P(ValidatorDeepNesting, ValidatesWithoutErrors) {
    const ValidationReport report = validate(test::nested_cdi(GetParam()));
    EXPECT_TRUE(report.ok()) << first_error_text(report.diagnostics);
    EXPECT_TRUE(report.schema.well_formed);
    EXPECT_TRUE(report.parsed);
}

INSTANTIATE_TEST_SUITE_P(Depths, ValidatorDeepNesting,
                         ::testing::ValuesIn(test::kValidNestingDepths));

TEST(ValidatorDeepNestingLimit, GroupsBeyondTheLimitAreRefused) {
    const ValidationReport report = validate(test::nested_cdi(kMaxGroupDepth + 1));
    EXPECT_FALSE(report.ok());
    EXPECT_FALSE(report.parsed);
}

class ValidatorHostileNesting : public ::testing::TestWithParam<std::size_t> {};

TEST_P(ValidatorHostileNesting, IsRefusedQuicklyWithADiagnostic) {
    const std::string text = test::hostile_cdi(GetParam());
    ASSERT_LE(text.size(), kMaxCdiBytes);
    const auto start = std::chrono::steady_clock::now();
    const ValidationReport report = validate(text);
    EXPECT_FALSE(report.ok());
    EXPECT_FALSE(report.parsed);
    EXPECT_NE(first_error_text(report.diagnostics).find("nested deeper"), std::string::npos);
    // Generous for sanitizer builds on a loaded machine; linear work takes well under a second.
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
}

INSTANTIATE_TEST_SUITE_P(Depths, ValidatorHostileNesting,
                         ::testing::ValuesIn(test::kHostileNestingDepths));

}  // namespace
}  // namespace olcb::cdi
