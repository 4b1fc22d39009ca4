// The human-readable tree of a laid-out CDI (cdi/render.cpp, lcc-cdi render): identification,
// segments, each element at its address with its type, constraints, hints and maps; replicated
// groups once, with their count and stride.
#include "cdi/render.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cdi/cdi_test_util.hpp"

namespace olcb::cdi {
namespace {

using test::first_error_text;
using test::lay;

std::vector<std::string> rendered_lines(const Layout& layout) {
    std::ostringstream out;
    render(layout, out);
    std::vector<std::string> lines;
    std::istringstream in(out.str());
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

constexpr const char* kAcdiLine =
    "ACDI (fixed 4, var 2): space 252 manufacturer data, space 251 user name and description";

TEST(Render, IdentificationAcdiAndSegments) {
    auto l = lay(R"(<cdi><identification><manufacturer>Acme</manufacturer><model>M1</model>
<hardwareVersion>hw1</hardwareVersion><softwareVersion>sw2</softwareVersion>
<link ref="https://example.com">home</link>
<map><relation><property>Size</property><value>Big</value></relation></map></identification>
<acdi fixed="4" var="2"/>
<segment space="253" origin="16"><name>Settings</name><description>All of them.</description>
<link ref="https://example.com/s">more</link><int size="1"/></segment>
<segment space="1"><int size="1"/></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_EQ(rendered_lines(l->layout()), (std::vector<std::string>{
                                               "Identification",
                                               "  manufacturer: Acme",
                                               "  model: M1",
                                               "  hardware version: hw1",
                                               "  software version: sw2",
                                               "  link: home <https://example.com>",
                                               "  map:",
                                               "    Size = Big",
                                               kAcdiLine,
                                               "Segment \"Settings\", space 253, origin 16",
                                               "  | All of them.",
                                               "  link: more <https://example.com/s>",
                                               "  @0x00000010 int(1) (unnamed)",
                                               "Segment (unnamed), space 1, origin 0",
                                               "  @0x00000000 int(1) (unnamed)",
                                           }));
}

TEST(Render, VariablesShowTypeConstraintsHintsAndMaps) {
    auto l = lay(R"(<cdi><segment space="253">
<int size="2"><name>Trim</name><description>Signed.</description><min>-10</min><max>10</max>
<default>-5</default><hints><slider tickSpacing="5" immediate="yes" showValue="yes"/></hints></int>
<float size="4"><name>Ratio</name><min>-1</min><max>1</max><default>0.25</default></float>
<string size="8"><name>Label</name><default>hi</default></string>
<action size="1"><name>Go</name><buttonText>Press</buttonText><dialogText>Sure?</dialogText>
<value>1</value></action>
<blob size="4" mode="read"><name>Raw</name></blob>
<int size="1"><map><name>Modes</name><relation><property>0</property><value>Off</value></relation>
</map><hints><radiobutton/></hints></int>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout) << first_error_text(l->result.diagnostics);
    const std::vector<std::string> lines = rendered_lines(l->layout());
    EXPECT_EQ(lines, (std::vector<std::string>{
                         "Segment (unnamed), space 253, origin 0",
                         "  @0x00000000 int(2) \"Trim\" signed min -10 max 10 default -5",
                         "    | Signed.",
                         "    hints: slider(tickSpacing 5, immediate, showValue)",
                         "  @0x00000002 float(4) \"Ratio\" min -1 max 1 default 0.25",
                         "  @0x00000006 string(8) \"Label\" default \"hi\"",
                         "  @0x0000000E action(1) \"Go\" value 1 button \"Press\"",
                         "    dialog: Sure?",
                         "  @0x0000000F blob(4) \"Raw\" mode read",
                         "  @0x00000013 int(1) (unnamed)",
                         "    hints: radiobutton",
                         "    map \"Modes\":",
                         "      0 = Off",
                     }));
}

TEST(Render, ReplicatedGroupsAreShownOnceWithCountStrideAndRepnames) {
    auto l = lay(R"(<cdi><segment space="253" origin="100">
<group replication="3" offset="4"><name>Port</name><repname>P</repname><repname>Q</repname>
<eventid><name>On</name></eventid><int size="2"/></group>
<group><name>Hidden</name><hints><visibility hideable="yes" hidden="yes"/><readOnly/></hints>
<int size="1"><name>x</name><hints><checkbox/></hints></int></group>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout) << first_error_text(l->result.diagnostics);
    EXPECT_EQ(rendered_lines(l->layout()),
              (std::vector<std::string>{
                  "Segment (unnamed), space 253, origin 100",
                  "  @0x00000068 group \"Port\" x3, stride 10 bytes, repname \"P\" \"Q\"",
                  "    @0x00000068 eventid(8) \"On\"",
                  "    @0x00000070 int(2) (unnamed)",
                  "  @0x00000086 group \"Hidden\"",
                  "    hints: visibility(hideable, hidden), readOnly",
                  "    @0x00000086 int(1) \"x\"",
                  "      hints: checkbox",
              }));
}

// A variable under 200 or 1,000 nested groups is rendered like any other, without recursion
// (deep nesting: parser_test.cpp).
class RenderDeepNesting : public ::testing::TestWithParam<std::size_t> {};

TEST_P(RenderDeepNesting, ShowsTheLeaf) {
    auto laid = lay(test::nested_cdi(GetParam()));
    ASSERT_TRUE(laid->result.layout) << first_error_text(laid->result.diagnostics);
    std::ostringstream rendered;
    render(laid->layout(), rendered);
    EXPECT_NE(rendered.str().find("\"Leaf\""), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Depths, RenderDeepNesting, ::testing::ValuesIn(test::kValidNestingDepths));

}  // namespace
}  // namespace olcb::cdi
