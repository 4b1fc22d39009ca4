#include "cdi/fdi_semantic_rules.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/fdi_parser.hpp"

namespace olcb::cdi {
namespace {

using test::fdi_function;
using test::fdi_text;
using test::listing;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

Diagnostics check(const std::string& body, FdiSchemaVersion schema = FdiSchemaVersion::kV1_1,
                  const std::string& segment_attributes = "") {
    std::string text = fdi_text(body);
    if (!segment_attributes.empty())
        text.replace(text.find("<segment>"), 9, "<segment " + segment_attributes + ">");
    const FdiParseResult parsed = parse_fdi(text);
    EXPECT_TRUE(parsed.document);
    EXPECT_THAT(parsed.diagnostics, IsEmpty()) << listing(parsed.diagnostics);
    return parsed.document ? check_fdi_semantics(*parsed.document, schema) : Diagnostics{};
}

TEST(FdiSemanticRules, ACleanFdiHasNoFinding) {
    const Diagnostics d =
        check(fdi_function(0, "Light") + fdi_function(1, "Horn", "momentary") +
              "<function kind=\"analog\"><name>Volume</name><number>2</number><min>0</min>"
              "<max>65535</max></function>\n");
    EXPECT_THAT(d, IsEmpty()) << listing(d);
}

TEST(FdiSemanticRules, ReservedSegmentAttributesShouldBeOmitted) {
    for (const char* attributes : {"space=\"249\"", "origin=\"0\"", "space=\"249\" origin=\"0\""}) {
        const Diagnostics d = check(fdi_function(0), FdiSchemaVersion::kV1_1, attributes);
        ASSERT_EQ(d.size(), 1U) << attributes;
        EXPECT_EQ(d[0].severity, Severity::kWarning);
        EXPECT_EQ(d[0].line, 3U);
        EXPECT_THAT(d[0].message, HasSubstr("new implementations should omit them "
                                            "(FunctionDescriptionInformationS §5.1.2)"));
    }
}

TEST(FdiSemanticRules, NumbersDescribedTwiceAreAdvice) {
    const Diagnostics d = check(fdi_function(0, "A") + fdi_function(3, "B") + fdi_function(0, "C") +
                                fdi_function(0, "D"));
    ASSERT_EQ(d.size(), 2U) << listing(d);
    EXPECT_EQ(d[0].severity, Severity::kWarning);
    EXPECT_EQ(d[0].line, 6U);
    EXPECT_EQ(d[0].message,
              "<function> F0 \"C\": number 0 is also described at line 4: a throttle would show "
              "two buttons for one function (advice: no clause forbids it)");
    EXPECT_EQ(d[1].line, 7U);
}

TEST(FdiSemanticRules, AnalogRanges) {
    const auto analog = [](const std::string& limits) {
        return "<function kind=\"analog\"><number>9</number>" + limits + "</function>\n";
    };
    EXPECT_THAT(listing(check(analog("<min>-1</min>"))),
                HasSubstr("cdi:4: warning: <function> F9: range -1..255 is negative; an analog "
                          "function takes unsigned integer values "
                          "(FunctionDescriptionInformationS §5.1.4)"));
    EXPECT_THAT(listing(check(analog("<min>300</min>"))),
                HasSubstr("range 300..255 accepts no value"));
    EXPECT_THAT(listing(check(analog("<min>5</min><max>4</max>"))),
                HasSubstr("range 5..4 accepts no value"));
    EXPECT_THAT(listing(check(analog("<max>65536</max>"))),
                HasSubstr("<max> 65536 is above 65535, the largest value Train Control's Set "
                          "Function carries (FunctionDescriptionInformationTN §3.1)"));
    EXPECT_THAT(check(analog("<min>0</min><max>0</max>")), IsEmpty());
}

TEST(FdiSemanticRules, MinMaxOnAnOnOffFunctionAreIgnored) {
    const Diagnostics d =
        check("<function kind=\"momentary\"><number>1</number><max>5</max></function>\n");
    ASSERT_EQ(d.size(), 1U);
    EXPECT_THAT(d[0].message, HasSubstr("<min>/<max> are used only when kind is analog"));
    EXPECT_THAT(d[0].message, HasSubstr("a momentary function ignores them"));
}

TEST(FdiSemanticRules, IconsGetOneWarningUnderFdi11) {
    const std::string body =
        "<function><name>Bell</name><icon>5</icon><number>1</number></function>\n"
        "<function><name>Horn</name><icon>6</icon><number>2</number></function>\n";
    const Diagnostics d = check(body);
    ASSERT_EQ(d.size(), 1U) << listing(d);
    EXPECT_EQ(d[0].line, 4U);
    EXPECT_THAT(d[0].message,
                HasSubstr("<icon> (2 function(s) have one) is defined by "
                          "FunctionDescriptionInformationS §5.1.4 and Appendix A but missing from "
                          "the published schema/fdi/1/1/fdi.xsd"));
    // Under FDI 1.0 the schema refuses the element itself: no second finding.
    EXPECT_THAT(check(body, FdiSchemaVersion::kV1_0), IsEmpty());
}

}  // namespace
}  // namespace olcb::cdi
