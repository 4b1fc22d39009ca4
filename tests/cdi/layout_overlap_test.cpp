// Overlap warnings (cdi/layout_overlap.cpp): variables sharing bytes are legal but flagged, once
// per space; beyond LayoutOptions::overlap_budget only replicas overlapping each other are.
#include <gtest/gtest.h>

#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/layout.hpp"

namespace olcb::cdi {
namespace {

using test::count_severity;
using test::lay;

bool mentions(const Diagnostics& d, const std::string& text) {
    for (const Diagnostic& x : d) {
        if (x.message.find(text) != std::string::npos) return true;
    }
    return false;
}

TEST(LayoutOverlap, ZeroStrideReplicasAreBoundedAndWarned) {
    auto l = lay(
        R"(<cdi><segment space="1" origin="10"><group replication="2147483647"><int offset="-1"/></group></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_EQ(l->layout().variable_count(), 2147483647u);
    Cursor c = l->layout().find(1, 9);
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.replica(0), 0u);
    bool replica_warning = false;
    for (const Diagnostic& d : l->result.diagnostics) {
        replica_warning |= d.message.find("replicas of <group> overlap") != std::string::npos;
    }
    EXPECT_TRUE(replica_warning);
}

TEST(LayoutOverlap, OverlapWarningNamesBothVariables) {
    auto l = lay(R"(<cdi><segment space="1"><name>S</name>
<int size="2"><name>word</name></int>
<int offset="-2"><name>high</name></int>
<int><name>low</name></int>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    ASSERT_EQ(l->result.diagnostics.size(), 1u);
    const Diagnostic& d = l->result.diagnostics[0];
    EXPECT_EQ(d.severity, Severity::kWarning);
    EXPECT_EQ(d.line, 3u);
    EXPECT_NE(d.message.find("2 variable(s) overlap"), std::string::npos) << d.message;
    EXPECT_NE(d.message.find("'S.high' at 0 overlaps 'S.word' at 0..2"), std::string::npos)
        << d.message;
}

TEST(LayoutOverlap, OverlapAcrossSegmentsOfOneSpace) {
    auto l = lay(R"(<cdi><segment space="253" origin="1"><int/></segment>
<segment space="253"><int size="2"/></segment><segment space="2"><int/></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    ASSERT_EQ(count_severity(l->result.diagnostics, Severity::kWarning), 1u);
    EXPECT_NE(l->result.diagnostics[0].message.find("space 253"), std::string::npos);
}

TEST(LayoutOverlap, NoWarningWithoutSharedBytes) {
    auto l = lay(R"(<cdi><segment space="1"><int size="2"/><int offset="0"/>
<group replication="3"><eventid/></group></segment><segment space="2"><int size="4"/></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_TRUE(l->result.diagnostics.empty());
}

TEST(LayoutOverlap, OneWarningPerSpaceCountingEveryOverlap) {
    auto l = lay(R"(<cdi><segment space="1"><int size="4"/><int offset="-3"/><int offset="-1"/>
</segment><segment space="2"><int size="2"/><int offset="-1"/></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    ASSERT_EQ(count_severity(l->result.diagnostics, Severity::kWarning), 2u);
    EXPECT_NE(
        l->result.diagnostics[0].message.find("2 variable(s) overlap an earlier one in space 1"),
        std::string::npos)
        << l->result.diagnostics[0].message;
    EXPECT_NE(
        l->result.diagnostics[1].message.find("1 variable(s) overlap an earlier one in space 2"),
        std::string::npos)
        << l->result.diagnostics[1].message;
}

TEST(LayoutOverlap, BeyondTheBudgetOnlyReplicaSelfOverlapIsWarned) {
    // Replicas 2 bytes wide at a stride of 1 overlap each other; the two plain ints overlap too.
    const std::string xml = R"(<cdi><segment space="1"><int size="2"/><int offset="-1"/>
<group replication="4" offset="10"><name>Ports</name><int size="2"/><group offset="-1"/></group>
</segment></cdi>)";
    auto swept = lay(xml);
    ASSERT_TRUE(swept->result.layout);
    EXPECT_TRUE(mentions(swept->result.diagnostics, "overlap an earlier one in space 1"));
    EXPECT_FALSE(mentions(swept->result.diagnostics, "replicas of <group>"));

    LayoutOptions options;
    options.overlap_budget = 1;
    auto budgeted = lay(xml, options);
    ASSERT_TRUE(budgeted->result.layout);
    EXPECT_FALSE(mentions(budgeted->result.diagnostics, "overlap an earlier one"));
    ASSERT_TRUE(mentions(budgeted->result.diagnostics,
                         "replicas of <group> 'Ports' overlap each other: one replica spans 2 "
                         "bytes but the stride is 1"));
}

}  // namespace
}  // namespace olcb::cdi
