// The schema check is fed events (from pugixml's tree, or while libxml2 parses), never a DOM:
// what that changes at the edges — how the schema is chosen before the root is validated, which
// line a finding gets, and what is kept when the text turns out not to be XML.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "cdi/schema_validator.hpp"

namespace olcb::cdi {
namespace {

using ::testing::AllOf;
using ::testing::Contains;
using ::testing::Each;
using ::testing::Field;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

constexpr const char* kXsi = "http://www.w3.org/2001/XMLSchema-instance";

std::string root_with(const std::string& attributes) {
    return "<cdi " + attributes +
           ">\n<segment space=\"253\">\n<int size=\"1\"/>\n</segment>\n</cdi>\n";
}

TEST(SchemaStream, AnyPrefixBoundToTheInstanceNamespaceDeclaresTheVersion) {
    SchemaChoice choice;
    const Diagnostics d = validate_schema(
        root_with(std::string("xmlns:q=\"") + kXsi +
                  "\" q:noNamespaceSchemaLocation=\"http://openlcb.org/schema/cdi/1/1/cdi.xsd\""),
        &choice);
    EXPECT_THAT(d, IsEmpty());
    EXPECT_TRUE(choice.declared);
    EXPECT_EQ(choice.version, SchemaVersion::kV1_1);
}

TEST(SchemaStream, TheLocalNameInAnotherNamespaceDeclaresNothing) {
    SchemaChoice choice;
    const Diagnostics d = validate_schema(
        root_with("xmlns:q=\"urn:other\" "
                  "q:noNamespaceSchemaLocation=\"http://openlcb.org/schema/cdi/1/1/cdi.xsd\""),
        &choice);
    EXPECT_FALSE(choice.declared);
    EXPECT_EQ(choice.version, kNewestSchema);
    EXPECT_THAT(d, Contains(Field(&Diagnostic::message, HasSubstr("no schema version declared"))));
}

TEST(SchemaStream, CommentsAndInstructionsBeforeTheRootDoNotHideTheDeclaration) {
    SchemaChoice choice;
    const std::string text =
        "<?xml version=\"1.0\"?>\n<!-- generated -->\n<?xml-stylesheet href=\"x.xsl\"?>\n" +
        root_with(std::string("xmlns:xsi=\"") + kXsi +
                  "\" xsi:noNamespaceSchemaLocation=\"http://openlcb.org/schema/cdi/1/0/cdi.xsd\"");
    EXPECT_THAT(validate_schema(text, &choice), IsEmpty());
    EXPECT_TRUE(choice.declared);
    EXPECT_EQ(choice.version, SchemaVersion::kV1_0);
}

TEST(SchemaStream, FindingsMadeBeforeTheTextStopsBeingXmlAreDropped) {
    // <bogus> breaks the schema on line 3; the text then ends inside <segment>.
    const std::string text = "<cdi>\n<segment space=\"253\">\n<bogus/>\n";
    SchemaChoice choice;
    const Diagnostics d = validate_schema(text, &choice);
    EXPECT_FALSE(choice.well_formed);
    EXPECT_THAT(d, Contains(Field(&Diagnostic::message, HasSubstr("XML parse error"))));
    EXPECT_THAT(d, Each(Field(&Diagnostic::message, Not(HasSubstr("schema")))));
}

TEST(SchemaStream, AStartTagFindingIsOnItsLineAndMissingContentOnTheEndTag) {
    const std::string text =
        "<cdi>\n"                             // 1
        "<segment space=\"253\">\n"           // 2
        "<int size=\"1\" colour=\"red\">\n"   // 3: an attribute the schema does not allow
        "<map>\n"                             // 4
        "<relation><property>1</property>\n"  // 5: a relation needs a <value>
        "</relation>\n"                       // 6
        "</map>\n</int>\n</segment>\n</cdi>\n";
    const Diagnostics d = validate_schema_as(text, SchemaVersion::kV1_4);
    EXPECT_THAT(d, Contains(AllOf(Field(&Diagnostic::line, 3u),
                                  Field(&Diagnostic::message, HasSubstr("colour")))));
    EXPECT_THAT(d, Contains(AllOf(Field(&Diagnostic::line, 6u),
                                  Field(&Diagnostic::message, HasSubstr("relation")))));
}

}  // namespace
}  // namespace olcb::cdi
