#include "cdi/fdi_parser.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/parser.hpp"

namespace olcb::cdi {
namespace {

using test::fdi_function;
using test::fdi_text;
using test::listing;
using ::testing::HasSubstr;

TEST(FdiParser, ReadsFunctionsGroupsAndTheirTexts) {
    const std::string text = fdi_text(
        "<name>Seg</name><description> All of them </description>\n"  // line 4
        "<function kind=\"momentary\" size=\"1\">\n"                  // line 5
        "  <name> Horn </name><icon>12</icon><number>2</number>\n"
        "</function>\n"
        "<group><name>Lights</name><description>Front</description>\n"  // line 8
        "<function><number>0</number></function>\n"                     // line 9
        "<group><name>Cab</name>\n"                                     // line 10
        "<function kind=\"analog\"><name>Dim</name><number>16777215</number>"
        "<min>-3</min><max>70000</max></function>\n"  // line 11
        "</group></group>\n");
    const FdiParseResult r = parse_fdi(text);
    ASSERT_TRUE(r.document);
    EXPECT_TRUE(r.diagnostics.empty()) << listing(r.diagnostics);
    const FdiDocument& doc = *r.document;
    EXPECT_EQ(doc.schema_location, "https://openlcb.org/schema/fdi/1/1/fdi.xsd");
    EXPECT_EQ(doc.name, "Seg");
    EXPECT_EQ(doc.description, "All of them");
    EXPECT_FALSE(doc.space_given);
    EXPECT_EQ(doc.segment_line, 3U);
    ASSERT_EQ(doc.functions.size(), 3U);
    const FdiFunction& horn = doc.functions[0];
    EXPECT_EQ(horn.number, 2U);
    EXPECT_EQ(horn.name, "Horn");
    EXPECT_TRUE(horn.momentary());
    EXPECT_EQ(horn.icon, 12);
    EXPECT_TRUE(horn.size_given);
    EXPECT_EQ(horn.group, std::nullopt);
    EXPECT_EQ(horn.line, 5U);
    const FdiFunction& unnamed = doc.functions[1];
    EXPECT_EQ(unnamed.number, 0U);
    EXPECT_EQ(unnamed.name, "");
    EXPECT_TRUE(unnamed.latching());  // kind defaults to binary
    EXPECT_EQ(unnamed.group, 0U);
    EXPECT_EQ(unnamed.line, 9U);
    const FdiFunction& dim = doc.functions[2];
    EXPECT_EQ(dim.number, kMaxFunctionNumber);
    EXPECT_EQ(dim.kind, FunctionKind::kAnalog);
    EXPECT_EQ(dim.min, -3);
    EXPECT_EQ(dim.max, 70000);
    EXPECT_EQ(dim.group, 1U);
    ASSERT_EQ(doc.groups.size(), 2U);
    EXPECT_EQ(doc.groups[0].name, "Lights");
    EXPECT_EQ(doc.groups[0].description, "Front");
    EXPECT_EQ(doc.groups[0].parent, std::nullopt);
    EXPECT_EQ(doc.groups[0].depth, 1U);
    EXPECT_EQ(doc.groups[0].first_function, 1U);
    EXPECT_EQ(doc.groups[0].line, 8U);
    EXPECT_EQ(doc.groups[1].parent, 0U);
    EXPECT_EQ(doc.groups[1].depth, 2U);
    EXPECT_EQ(doc.groups[1].line, 10U);
}

TEST(FdiParser, ReservedSegmentAttributesAndTrailingNuls) {
    const FdiParseResult r = parse_fdi(std::string("<fdi><segment space='249' origin='0'>") +
                                       fdi_function(1) + "</segment></fdi>" + '\0' + '\0');
    ASSERT_TRUE(r.document);
    EXPECT_TRUE(r.document->space_given);
    EXPECT_TRUE(r.document->origin_given);
    EXPECT_EQ(r.document->schema_location, "");
    EXPECT_EQ(r.document->functions.size(), 1U);
}

TEST(FdiParser, AFunctionWithoutAUsableNumberIsLeftOutWithAnError) {
    const FdiParseResult r = parse_fdi(fdi_text(
        "<function><name>none</name></function>\n"                                 // line 4
        "<function><number>16777216</number></function>\n"                         // line 5
        "<function><number>0x10</number></function>\n"                             // line 6
        "<function><number>-1</number></function>\n"                               // line 7
        "<function kind=\"toggle\" size=\"2\"><number> +7 </number></function>\n"  // line 8
        "<function><number>3</number><min>1.5</min></function>\n"));               // line 9
    ASSERT_TRUE(r.document);
    ASSERT_EQ(r.document->functions.size(), 2U);
    EXPECT_EQ(r.document->functions[0].number, 7U);
    EXPECT_EQ(r.document->functions[0].kind, FunctionKind::kBinary);
    EXPECT_EQ(r.document->functions[1].min, std::nullopt);
    const std::string all = listing(r.diagnostics);
    EXPECT_THAT(all, HasSubstr("cdi:4: error: <function> has no <number>; it shall contain one "
                               "(§5.1.4)"));
    EXPECT_THAT(all, HasSubstr("cdi:5: error: <number> '16777216' is not a decimal integer in "
                               "0..16777215 (§5.1.4)"));
    EXPECT_THAT(all, HasSubstr("cdi:6: error: <number> '0x10'"));
    EXPECT_THAT(all, HasSubstr("cdi:7: error: <number> '-1'"));
    EXPECT_THAT(all, HasSubstr("cdi:8: error: <function> kind 'toggle' is not binary, momentary "
                               "or analog (§5.1.4)"));
    EXPECT_THAT(all, HasSubstr("cdi:8: error: <function> size '2' is not 1 (§5.1.4"));
    EXPECT_THAT(all, HasSubstr("cdi:9: error: <min> '1.5' is not a decimal integer"));
}

TEST(FdiParser, SegmentRules) {
    FdiParseResult none = parse_fdi("<?xml version=\"1.0\"?>\n<fdi>\n</fdi>\n");
    ASSERT_TRUE(none.document);
    EXPECT_THAT(
        listing(none.diagnostics),
        HasSubstr("cdi:2: error: <fdi> has no <segment>; it contains exactly one (§5.1.1)"));
    FdiParseResult two = parse_fdi("<fdi><segment>" + fdi_function(1) + "</segment>\n<segment>" +
                                   fdi_function(2) + "</segment></fdi>");
    ASSERT_TRUE(two.document);
    ASSERT_EQ(two.document->functions.size(), 1U);
    EXPECT_EQ(two.document->functions[0].number, 1U);
    EXPECT_THAT(listing(two.diagnostics), HasSubstr("cdi:3: error: a second <segment>, ignored"));
}

TEST(FdiParser, TextsThatAreNoFdi) {
    struct Case {
        std::string text;
        const char* message;
    };
    const Case cases[] = {
        {"", "error: the FDI is empty"},
        {" \n\t", "error: the FDI is empty"},
        {"<fdi><segment>", "error: malformed XML"},
        {"<cdi><segment space=\"253\"/></cdi>", "root element is <cdi>, expected <fdi>"},
        {"<!DOCTYPE fdi [<!ENTITY a \"b\">]>\n<fdi><segment/></fdi>",
         "DOCTYPE/DTD (and entity declarations) are not allowed in an FDI"},
        {std::string("<fdi><segment>") + '\0' + "</segment></fdi>",
         "cdi:1: error: NUL byte inside"},
    };
    for (const Case& c : cases) {
        const FdiParseResult r = parse_fdi(c.text);
        EXPECT_FALSE(r.document) << c.text;
        EXPECT_THAT(listing(r.diagnostics), HasSubstr(c.message)) << c.text;
    }
}

TEST(FdiParser, HostileNestingIsRefusedByLevelWithoutRecursion) {
    for (const std::size_t depth : test::kHostileNestingDepths) {
        std::string text = "<fdi><segment>";
        for (std::size_t i = 0; i < depth; ++i) text += "<group>";
        text += fdi_function(5);
        for (std::size_t i = 0; i < depth; ++i) text += "</group>";
        text += "</segment></fdi>";
        const FdiParseResult r = parse_fdi(text);
        ASSERT_TRUE(r.document);
        EXPECT_EQ(r.document->groups.size(), kMaxGroupDepth);
        EXPECT_TRUE(r.document->functions.empty());
        ASSERT_EQ(r.diagnostics.size(), 1U) << listing(r.diagnostics);
        EXPECT_THAT(r.diagnostics[0].message, HasSubstr("groups nested deeper than 1024 levels"));
    }
}

TEST(FdiParser, ErrorsAreBounded) {
    std::string body;
    for (int i = 0; i < 5000; ++i) body += "<function/>";
    const FdiParseResult r = parse_fdi(fdi_text(body));
    ASSERT_EQ(r.diagnostics.size(), 1001U);
    EXPECT_EQ(r.diagnostics.back().message, "4000 further errors suppressed");
}

TEST(FdiParser, IsFdiTextLooksAtTheRootElementOnly) {
    EXPECT_TRUE(is_fdi_text("<fdi/>"));
    EXPECT_TRUE(is_fdi_text("<fdi>"));
    EXPECT_TRUE(is_fdi_text("<fdi"));
    EXPECT_TRUE(
        is_fdi_text("\xEF\xBB\xBF<?xml version=\"1.0\"?>\n<?xml-stylesheet href='x'?>\n"
                    "<!-- <cdi> -->\n<!DOCTYPE fdi [<!ENTITY a \"<cdi>\">]>\n"
                    "<fdi\txmlns:xsi='x'>"));
    EXPECT_TRUE(is_fdi_text(fdi_text(fdi_function(0))));
    EXPECT_FALSE(is_fdi_text("<cdi><segment/></cdi>"));
    EXPECT_FALSE(is_fdi_text("<fdix/>"));
    EXPECT_FALSE(is_fdi_text("<x:fdi/>"));
    EXPECT_FALSE(is_fdi_text("<!-- <fdi> -->"));
    EXPECT_FALSE(is_fdi_text("<!-- unterminated <fdi>"));
    EXPECT_FALSE(is_fdi_text("<?xml version=\"1.0\""));
    EXPECT_FALSE(is_fdi_text("text <fdi/>"));
    EXPECT_FALSE(is_fdi_text(""));
}

}  // namespace
}  // namespace olcb::cdi
