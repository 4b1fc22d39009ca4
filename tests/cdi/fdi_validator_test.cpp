#include "cdi/fdi_validator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "cdi/cdi_test_util.hpp"

namespace olcb::cdi {
namespace {

using test::fdi_function;
using test::fdi_text;
using test::first_error_text;
using test::listing;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

TEST(ValidateFdi, AValidFdiGivesItsFunctionsAndNoFinding) {
    const ValidatedFdi v = validate_fdi(
        fdi_text(fdi_function(0, "Light") + fdi_function(1, "Horn", "momentary")) + '\0');
    EXPECT_TRUE(v.ok());
    EXPECT_THAT(v.diagnostics, IsEmpty()) << listing(v.diagnostics);
    EXPECT_TRUE(v.schema.declared);
    EXPECT_TRUE(v.schema.well_formed);
    EXPECT_EQ(v.schema.version, FdiSchemaVersion::kV1_1);
    ASSERT_TRUE(v.document);
    ASSERT_EQ(v.document->functions.size(), 2U);
    EXPECT_EQ(v.document->functions[1].name, "Horn");
    EXPECT_TRUE(v.document->functions[1].momentary());
}

TEST(ValidateFdi, TheDeclaredVersionChoosesTheSchema) {
    const ValidatedFdi v10 = validate_fdi(fdi_text(fdi_function(0), 0));
    EXPECT_TRUE(v10.ok()) << listing(v10.diagnostics);
    EXPECT_EQ(v10.schema.version, FdiSchemaVersion::kV1_0);
    EXPECT_TRUE(v10.schema.declared);

    const ValidatedFdi none = validate_fdi(fdi_text(fdi_function(0), -1));
    EXPECT_TRUE(none.ok());
    EXPECT_FALSE(none.schema.declared);
    EXPECT_EQ(none.schema.version, kNewestFdiSchema);
    EXPECT_THAT(listing(none.diagnostics),
                HasSubstr("cdi:2: warning: no schema version declared; validated against FDI 1.1"));
}

TEST(ValidateFdi, IconIsAnErrorUnderFdi10AndAWarningUnderFdi11) {
    const std::string body =
        "<function><name>Bell</name><icon>5</icon><number>1</number></function>\n";
    const ValidatedFdi v10 = validate_fdi(fdi_text(body, 0));
    EXPECT_FALSE(v10.ok());
    EXPECT_THAT(first_error_text(v10.diagnostics),
                HasSubstr("FDI 1.0 schema: Element 'icon': This element is not expected."));
    const ValidatedFdi v11 = validate_fdi(fdi_text(body, 1));
    EXPECT_TRUE(v11.ok()) << listing(v11.diagnostics);
    EXPECT_THAT(listing(v11.diagnostics), HasSubstr("warning: <function> F1 \"Bell\": <icon>"));
    ASSERT_TRUE(v11.document);
    EXPECT_EQ(v11.document->functions[0].icon, 5);
}

// Each "shall" of §5.1 the schema states, broken once: the schema's error (at its line) is the
// finding, and the model parser's restatement of it is not added.
TEST(ValidateFdi, CraftedInvalidFdisFailOnTheSchemaClause) {
    struct Case {
        std::string body;
        std::uint32_t line;
        const char* error;
    };
    const Case cases[] = {
        {"<function><name>x</name></function>\n", 4,
         "Element 'function': Missing child element(s). Expected is one of ( icon, number )"},
        {fdi_function(16777216), 4,
         "Element 'number': [facet 'maxInclusive'] The value '16777216' is greater than the "
         "maximum value allowed ('16777215')"},
        {"<function kind=\"toggle\"><number>1</number></function>\n", 4,
         "attribute 'kind': [facet 'enumeration'] The value 'toggle' is not an element of the set"},
        {"<function size=\"2\"><number>1</number></function>\n", 4,
         "attribute 'size': [facet 'enumeration'] The value '2'"},
        {"<function><number>0x1</number></function>\n", 4, "'0x1' is not a valid value"},
        {"<group replication=\"2\"/>\n", 4, "The attribute 'replication' is not allowed"},
        {"<int size=\"1\"/>\n", 4, "Element 'int': This element is not expected"},
    };
    for (const Case& c : cases) {
        const ValidatedFdi v = validate_fdi(fdi_text(c.body));
        EXPECT_FALSE(v.ok()) << c.body;
        const Diagnostic* first = test::first_error(v.diagnostics);
        ASSERT_NE(first, nullptr) << c.body;
        EXPECT_EQ(first->line, c.line) << c.body;
        EXPECT_THAT(first->message, HasSubstr("FDI 1.1 schema: ")) << c.body;
        EXPECT_THAT(first->message, HasSubstr(c.error)) << listing(v.diagnostics);
        EXPECT_EQ(test::count_severity(v.diagnostics, Severity::kError), 1U)
            << listing(v.diagnostics);
    }
}

TEST(ValidateFdi, SegmentCountIsTheSchemasFinding) {
    const ValidatedFdi none = validate_fdi("<?xml version=\"1.0\"?>\n<fdi>\n</fdi>\n");
    EXPECT_FALSE(none.ok());
    EXPECT_THAT(first_error_text(none.diagnostics),
                HasSubstr("Element 'fdi': Missing child element(s). Expected is ( segment )"));
    EXPECT_THAT(listing(none.diagnostics), Not(HasSubstr("has no <segment>")));
    ASSERT_TRUE(none.document);
    EXPECT_THAT(none.document->functions, IsEmpty());

    const ValidatedFdi two =
        validate_fdi(fdi_text(fdi_function(1) + "</segment>\n<segment>\n" + fdi_function(2)));
    EXPECT_FALSE(two.ok());
    const Diagnostic* first = test::first_error(two.diagnostics);
    ASSERT_NE(first, nullptr);
    EXPECT_EQ(first->line, 6U);
    EXPECT_THAT(first->message, HasSubstr("Element 'segment': This element is not expected"));
    EXPECT_THAT(listing(two.diagnostics), Not(HasSubstr("a second <segment>")));
    ASSERT_TRUE(two.document);
    EXPECT_EQ(two.document->functions.size(), 1U);
}

TEST(ValidateFdi, ModelErrorsTheSchemaMissesAreReported) {
    // Nesting past kMaxGroupDepth is schema-valid; the model refuses it.
    std::string body;
    for (int i = 0; i < 1100; ++i) body += "<group>";
    body += fdi_function(3);
    for (int i = 0; i < 1100; ++i) body += "</group>";
    const ValidatedFdi v = validate_fdi(fdi_text(body + "\n"));
    EXPECT_FALSE(v.ok());
    EXPECT_THAT(first_error_text(v.diagnostics), HasSubstr("groups nested deeper than 1024"));
}

TEST(ValidateFdi, TextThatIsNotAnFdi) {
    const ValidatedFdi cdi = validate_fdi("<?xml version=\"1.0\"?>\n<cdi/>\n");
    EXPECT_FALSE(cdi.ok());
    EXPECT_FALSE(cdi.document);
    EXPECT_THAT(first_error_text(cdi.diagnostics),
                HasSubstr("FDI 1.1 schema: Element 'cdi': No matching global declaration"));

    const ValidatedFdi broken = validate_fdi("<fdi><segment></fdi>");
    EXPECT_FALSE(broken.ok());
    EXPECT_FALSE(broken.schema.well_formed);
    EXPECT_THAT(first_error_text(broken.diagnostics), HasSubstr("XML parse error: "));
    EXPECT_THAT(listing(broken.diagnostics), Not(HasSubstr("malformed XML")));

    const ValidatedFdi doctype = validate_fdi("<!DOCTYPE fdi [<!ENTITY a \"b\">]><fdi/>");
    EXPECT_THAT(first_error_text(doctype.diagnostics),
                HasSubstr("a DOCTYPE is not allowed in an FDI"));

    const ValidatedFdi large = validate_fdi(std::string(kMaxCdiBytes + 1, ' '));
    EXPECT_THAT(first_error_text(large.diagnostics),
                HasSubstr("FDI is 16777217 bytes; refusing more than 16777216"));
}

}  // namespace
}  // namespace olcb::cdi
