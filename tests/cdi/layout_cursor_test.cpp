// Traversal and lookup over a Layout (cdi/layout_cursor.cpp): iteration in document order,
// at(ordinal) and find(space, address), all by arithmetic on the replicas' strides.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "cdi/cdi_test_util.hpp"
#include "cdi/layout.hpp"

namespace olcb::cdi {
namespace {

using test::count_severity;
using test::kPanelTest;
using test::lay;

TEST(LayoutCursor, CursorReportsGroupsAndReplicas) {
    auto l = lay(kPanelTest);
    ASSERT_TRUE(l->result.layout);
    Cursor c = l->layout().at(8);  // second outer replica, first inner replica
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.address(), 206u);
    EXPECT_EQ(c.segment_index(), 0u);
    EXPECT_EQ(c.ordinal(), 8u);
    EXPECT_EQ(c.element().kind, ElementKind::kString);
    ASSERT_EQ(c.group_depth(), 2u);
    EXPECT_EQ(c.group(0).replication, 2u);
    EXPECT_EQ(c.group(1).replication, 3u);
    EXPECT_EQ(c.replica(0), 1u);
    EXPECT_EQ(c.replica(1), 0u);
    c.next();
    EXPECT_EQ(c.address(), 215u);
    EXPECT_EQ(c.ordinal(), 9u);
    EXPECT_FALSE(l->layout().at(13).valid());
}

TEST(LayoutCursor, AtAgreesWithIteration) {
    auto l = lay(kPanelTest);
    ASSERT_TRUE(l->result.layout);
    std::uint64_t expected = 0;
    l->layout().visit([&](const Cursor& c) {
        EXPECT_EQ(c.ordinal(), expected);
        Cursor a = l->layout().at(expected);
        EXPECT_EQ(a.address(), c.address());
        EXPECT_EQ(a.path(), c.path());
        ++expected;
    });
    EXPECT_EQ(expected, 13u);
}

TEST(LayoutCursor, FindHitsAndMisses) {
    auto l = lay(kPanelTest);
    ASSERT_TRUE(l->result.layout);
    const Layout& layout = l->layout();
    Cursor c = layout.find(13, 154);
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.address(), 153u);
    EXPECT_EQ(c.size(), 2u);
    EXPECT_EQ(c.ordinal(), 0u);
    EXPECT_FALSE(layout.find(13, 155).valid());  // gap before the eventid at 158
    EXPECT_FALSE(layout.find(13, 152).valid());
    c = layout.find(13, 165);
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.address(), 158u);
    // 182 holds the int of replica 1 and the string at 179: the int comes first in the document.
    c = layout.find(13, 182);
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.element().kind, ElementKind::kInt);
    EXPECT_EQ(c.address(), 182u);
    EXPECT_EQ(c.ordinal(), 3u);
    c = layout.find(13, 180);
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.address(), 179u);
    EXPECT_EQ(c.path(), "(space 13)/[1]/[1]/(string)");
    c = layout.find(13, 230);
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.address(), 224u);
    EXPECT_EQ(c.replica(0), 1u);
    EXPECT_EQ(c.replica(1), 2u);
    EXPECT_EQ(c.ordinal(), 10u);
    c.next();  // a found cursor continues in document order
    EXPECT_EQ(c.address(), 254u);
    EXPECT_EQ(layout.find(13, 255).address(), 254u);
    EXPECT_FALSE(layout.find(13, 256).valid());
    EXPECT_TRUE(layout.find(14, 1).valid());
    EXPECT_FALSE(layout.find(14, 2).valid());
    EXPECT_FALSE(layout.find(15, 0).valid());
    EXPECT_FALSE(layout.find(13, std::uint64_t{1} << 40).valid());
}

TEST(LayoutCursor, FindEveryByteOfANonOverlappingLayout) {
    auto l = lay(R"(<cdi><segment space="253" origin="128">
<group replication="4"><int size="2"/><group replication="3" offset="1"><eventid/><string size="5" offset="2"/></group></group>
<group replication="2" offset="3"><int size="1"/></group>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_EQ(count_severity(l->result.diagnostics, Severity::kWarning), 0u);
    const Layout& layout = l->layout();
    std::vector<std::int64_t> owner(400, -1);
    layout.visit([&](const Cursor& c) {
        for (std::uint64_t a = c.address(); a < c.address() + c.size(); ++a) {
            owner[a] = static_cast<std::int64_t>(c.ordinal());
        }
    });
    for (std::uint64_t a = 0; a < owner.size(); ++a) {
        Cursor c = layout.find(253, a);
        if (owner[a] < 0) {
            EXPECT_FALSE(c.valid()) << a;
        } else {
            ASSERT_TRUE(c.valid()) << a;
            EXPECT_EQ(static_cast<std::int64_t>(c.ordinal()), owner[a]) << a;
            EXPECT_EQ(c.address(), layout.at(c.ordinal()).address());
        }
    }
}

TEST(LayoutCursor, NextWalksReplicasInOrderAndEndsInvalid) {
    auto l = lay(R"(<cdi><segment space="5" origin="10">
<group replication="2"><int size="1"/><group replication="2"><int size="2"/></group></group>
</segment><segment space="6"><eventid/></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    std::vector<std::uint64_t> addresses;
    std::vector<std::uint32_t> spaces;
    Cursor c = l->layout().begin();
    for (; c.valid(); c.next()) {
        addresses.push_back(c.address());
        spaces.push_back(c.space());
    }
    EXPECT_EQ(addresses, (std::vector<std::uint64_t>{10, 11, 13, 15, 16, 18, 0}));
    EXPECT_EQ(spaces, (std::vector<std::uint32_t>{5, 5, 5, 5, 5, 5, 6}));
    EXPECT_FALSE(l->layout().at(7).valid());
    const Cursor last = l->layout().at(6);
    ASSERT_TRUE(last.valid());
    EXPECT_EQ(last.segment_index(), 1u);
    EXPECT_EQ(last.group_depth(), 0u);
    EXPECT_EQ(last.size(), 8u);
}

TEST(LayoutCursor, VisitStopsWhenTheCallbackReturnsFalse) {
    auto l = lay(kPanelTest);
    ASSERT_TRUE(l->result.layout);
    std::uint64_t seen = 0;
    l->layout().visit([&](const Cursor&) { return ++seen < 4; });
    EXPECT_EQ(seen, 4u);
    seen = 0;
    l->layout().visit([&](const Cursor&) { ++seen; });  // void: every variable
    EXPECT_EQ(seen, l->layout().variable_count());
}

}  // namespace
}  // namespace olcb::cdi
