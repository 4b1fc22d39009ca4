#include "cdi/layout.hpp"

#include <gtest/gtest.h>
#include <malloc.h>

#include <string>
#include <vector>

#include "cdi/cdi_test_util.hpp"
#include "cdi/parser.hpp"

namespace olcb::cdi {
namespace {

using test::all;
using test::first_error;
using test::first_error_text;
using test::kPanelTest;
using test::lay;
using test::Placed;

std::size_t heap_in_use() {
    return mallinfo2().uordblks;
}

TEST(Layout, OffsetsOriginAndNegativeOffsets) {
    auto l = lay(R"(<cdi><segment space="7" origin="100"><name>S</name>
<int size="2" offset="5"><name>a</name></int>
<string size="4" offset="-3"><name>b</name></string>
<eventid><name>c</name></eventid>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_EQ(all(l->layout()),
              (std::vector<Placed>{{"S/a", 7, 105, 2}, {"S/b", 7, 104, 4}, {"S/c", 7, 108, 8}}));
    EXPECT_EQ(l->layout().variable_count(), 3u);
    ASSERT_TRUE(l->layout().extent(7));
    EXPECT_EQ(l->layout().extent(7)->begin, 104u);
    EXPECT_EQ(l->layout().extent(7)->end, 116u);
    EXPECT_FALSE(l->layout().extent(8));
}

TEST(Layout, PanelTestAddressesAndOrder) {
    auto l = lay(kPanelTest);
    ASSERT_TRUE(l->result.layout);
    std::vector<std::uint64_t> addresses;
    for (const Placed& p : all(l->layout())) addresses.push_back(p.address);
    EXPECT_EQ(addresses, (std::vector<std::uint64_t>{153, 158, 167, 182, 179, 188, 197, 209, 206,
                                                     215, 224, 254, 0}));
    const std::vector<Placed> v = all(l->layout());
    EXPECT_EQ(v[3].path, "(space 13)/[1]/(int)");
    EXPECT_EQ(v[5].path, "(space 13)/[1]/[2]/(string)");
    EXPECT_EQ(v[8].path, "(space 13)/[2]/[1]/(string)");
    EXPECT_EQ(v[12].path, "(space 14)/(int)");
    EXPECT_EQ(v[12].space, 14u);
    const auto extents = l->layout().extents();
    ASSERT_EQ(extents.size(), 2u);
    EXPECT_EQ(extents[0].space, 13u);
    EXPECT_EQ(extents[0].begin, 153u);
    EXPECT_EQ(extents[0].end, 256u);
    EXPECT_EQ(extents[1].space, 14u);
    EXPECT_EQ(extents[1].end, 2u);
}

TEST(Layout, NegativeStrideReplication) {
    auto l = lay(
        R"(<cdi><segment space="1" origin="100"><group replication="3"><int offset="-3"/></group></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    std::vector<std::uint64_t> addresses;
    for (const Placed& p : all(l->layout())) addresses.push_back(p.address);
    EXPECT_EQ(addresses, (std::vector<std::uint64_t>{97, 95, 93}));
    Cursor c = l->layout().find(1, 95);
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.replica(0), 1u);
    EXPECT_FALSE(l->layout().find(1, 96).valid());
}

TEST(Layout, ZeroSizeGroupsMoveTheAddressAndEmptyOnesWarn) {
    auto l = lay(R"(<cdi><segment space="1">
<int/>
<group offset="10"/>
<int/>
<group/>
<group><name>Label only</name></group>
<int/>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    std::vector<std::uint64_t> addresses;
    for (const Placed& p : all(l->layout())) addresses.push_back(p.address);
    EXPECT_EQ(addresses, (std::vector<std::uint64_t>{0, 11, 12}));
    ASSERT_EQ(l->result.diagnostics.size(), 1u);  // only the fully empty <group/>
    EXPECT_EQ(l->result.diagnostics[0].severity, Severity::kWarning);
    EXPECT_EQ(l->result.diagnostics[0].line, 5u);
    EXPECT_NE(l->result.diagnostics[0].message.find("empty <group>"), std::string::npos);
}

TEST(Layout, MillionReplicasStayCompact) {
    const std::size_t before = heap_in_use();
    auto l =
        lay(R"(<cdi><segment space="253" origin="128"><group replication="1000000"><name>Port</name>
<repname>Line</repname><int size="2"><name>Mode</name></int><eventid><name>Event</name></eventid>
</group></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_LT(heap_in_use() - before,
              std::size_t{4} << 20);  // the overlap sweep is the largest part
    const Layout& layout = l->layout();
    EXPECT_EQ(layout.variable_count(), 2000000u);
    const std::vector<Placed> first = all(layout, 3);
    EXPECT_EQ(first, (std::vector<Placed>{{"(space 253)/Port[1](Line 1)/Mode", 253, 128, 2},
                                          {"(space 253)/Port[1](Line 1)/Event", 253, 130, 8},
                                          {"(space 253)/Port[2](Line 2)/Mode", 253, 138, 2}}));
    const std::uint64_t last = 128 + 999999ull * 10 + 2;
    Cursor c = layout.find(253, last + 7);
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.address(), last);
    EXPECT_EQ(c.ordinal(), 1999999u);
    EXPECT_EQ(c.path(), "(space 253)/Port[1000000](Line 1000000)/Event");
    EXPECT_FALSE(layout.find(253, last + 8).valid());
    EXPECT_EQ(layout.at(1999999u).address(), last);
    c.next();
    EXPECT_FALSE(c.valid());
    EXPECT_EQ(layout.extent(253)->end, 128 + 10000000u);
}

TEST(Layout, LargestReplicationFitsExactly) {
    auto l = lay(
        R"(<cdi><segment space="1"><group replication="2147483647"><int size="2"/></group></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_EQ(l->layout().variable_count(), 2147483647u);
    Cursor c = l->layout().find(1, 4294967293u);
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.address(), 4294967292u);
    EXPECT_EQ(c.replica(0), 2147483646u);
}

TEST(Layout, AddressOverflowIsAClearErrorWithoutExpansion) {
    const std::size_t before = heap_in_use();
    auto l = lay(R"(<cdi><segment space="253">
<group replication="2147483647">
<group replication="2147483647">
<int size="4"><name>Deep</name></int>
</group></group></segment></cdi>)");
    EXPECT_LT(heap_in_use() - before, std::size_t{1} << 20);
    EXPECT_FALSE(l->result.layout);
    const Diagnostic* e = first_error(l->result.diagnostics);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->line, 4u);
    EXPECT_NE(e->message.find("<int> 'Deep' ends at address"), std::string::npos) << e->message;
    EXPECT_NE(e->message.find("beyond the 32-bit address space"), std::string::npos);

    auto end =
        lay(R"(<cdi><segment space="1" origin="4294967295"><int size="2"/></segment></cdi>)");
    EXPECT_FALSE(end->result.layout);
    ASSERT_NE(first_error(end->result.diagnostics), nullptr);
    EXPECT_NE(first_error(end->result.diagnostics)->message.find("4294967297"), std::string::npos);

    auto below =
        lay("<cdi><segment space='1'>\n<int/>\n<string size='2' offset='-5'/></segment></cdi>");
    EXPECT_FALSE(below->result.layout);
    ASSERT_NE(first_error(below->result.diagnostics), nullptr);
    EXPECT_EQ(first_error(below->result.diagnostics)->line, 3u);
    EXPECT_NE(first_error(below->result.diagnostics)->message.find("starts at address -4, below 0"),
              std::string::npos);

    // A zero-size group start counts as an address too.
    auto group =
        lay("<cdi><segment space='1'><group offset='-1'/><int offset='1'/></segment></cdi>");
    EXPECT_FALSE(group->result.layout);
}

TEST(Layout, VariableCountBeyond63BitsIsRefused) {
    // Zero-stride replicas stack up without moving the address.
    std::string xml = "<cdi><segment space='1' origin='10'>";
    for (int i = 0; i < 3; ++i) xml += "<group replication='2147483647'>";
    xml += "<int offset='-1'/>";
    for (int i = 0; i < 3; ++i) xml += "</group>";
    xml += "</segment></cdi>";
    auto l = lay(xml);
    EXPECT_FALSE(l->result.layout);
    ASSERT_NE(first_error(l->result.diagnostics), nullptr);
    EXPECT_NE(first_error(l->result.diagnostics)->message.find("2^63"), std::string::npos);
}

TEST(Layout, UnsignedOffsetRule) {
    const std::string xml = R"(<cdi><segment space="1" origin="200"><int size="4"/>
<group offset="4294967292"/><int><name>after</name></int></segment></cdi>)";
    auto ignore = lay(xml);
    ASSERT_TRUE(ignore->result.layout);
    EXPECT_EQ(all(ignore->layout())[1].address, 204u);
    ASSERT_EQ(ignore->result.diagnostics.size(), 1u);
    EXPECT_EQ(ignore->result.diagnostics[0].line, 2u);
    EXPECT_NE(ignore->result.diagnostics[0].message.find("-4"), std::string::npos);
    EXPECT_NE(ignore->result.diagnostics[0].message.find("ignored"), std::string::npos);

    auto wrap = lay(xml, LayoutOptions{UnsignedOffsetRule::kWrap32});
    ASSERT_TRUE(wrap->result.layout);
    EXPECT_EQ(all(wrap->layout())[1].address, 200u);
    EXPECT_NE(wrap->result.diagnostics[0].message.find("wrap-around"), std::string::npos);
}

TEST(Layout, Placement) {
    auto l = lay(kPanelTest);
    ASSERT_TRUE(l->result.layout);
    const Element& outer = l->doc.segments[0].children[4];
    auto p = l->layout().placement(outer);
    ASSERT_TRUE(p);
    EXPECT_EQ(p->space, 13u);
    EXPECT_EQ(p->address, 179u);
    EXPECT_EQ(p->stride, 27);
    EXPECT_EQ(p->replication, 2u);
    auto inner = l->layout().placement(outer.children[2].children[0]);
    ASSERT_TRUE(inner);
    EXPECT_EQ(inner->address, 179u);
    EXPECT_EQ(inner->stride, 9);
    Element stranger;
    EXPECT_FALSE(l->layout().placement(stranger));
}

TEST(Layout, EmptyDocumentAndVariableFreeGroups) {
    auto l = lay(
        R"(<cdi><segment space="1"><group replication="1000000000"><name>nothing</name></group></segment><segment space="2"/></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_EQ(l->layout().variable_count(), 0u);
    EXPECT_FALSE(l->layout().begin().valid());
    EXPECT_TRUE(l->layout().extents().empty());
    EXPECT_FALSE(l->layout().find(1, 0).valid());
}

TEST(Layout, HandBuiltDocumentTooDeepIsRefused) {
    Document doc;
    doc.segments.emplace_back();
    Element* e = nullptr;
    std::vector<Element>* level = &doc.segments[0].children;
    for (std::size_t i = 0; i < kMaxGroupDepth + 5; ++i) {
        level->emplace_back();
        e = &level->back();
        e->kind = ElementKind::kGroup;
        e->tag = "group";
        level = &e->children;
    }
    LayoutResult r = build_layout(doc);
    EXPECT_FALSE(r.layout);
    ASSERT_NE(first_error(r.diagnostics), nullptr);
    EXPECT_NE(first_error(r.diagnostics)->message.find("nested deeper"), std::string::npos);
}

// A valid CDI of deeply nested groups lays out like any other: one variable under every level,
// reached by the cursor without recursion (deep nesting, the parser's limit: parser_test.cpp).
class LayoutDeepNesting : public ::testing::TestWithParam<std::size_t> {};

TEST_P(LayoutDeepNesting, LaysOutTheLeafUnderEveryGroup) {
    const std::size_t depth = GetParam();
    ParseResult parsed = parse(test::nested_cdi(depth));
    ASSERT_TRUE(parsed.document) << first_error_text(parsed.diagnostics);
    LayoutResult laid = build_layout(*parsed.document);
    ASSERT_TRUE(laid.layout) << first_error_text(laid.diagnostics);
    EXPECT_EQ(laid.layout->variable_count(), 1u);
    const Cursor c = laid.layout->begin();
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.group_depth(), depth);
    EXPECT_EQ(c.element().name, "Leaf");
    EXPECT_EQ(c.address(), 0u);
    EXPECT_EQ(laid.layout->find(253, 1).ordinal(), 0u);
    EXPECT_NE(c.path().find("L" + std::to_string(depth) + "/Leaf"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Depths, LayoutDeepNesting, ::testing::ValuesIn(test::kValidNestingDepths));

}  // namespace
}  // namespace olcb::cdi
