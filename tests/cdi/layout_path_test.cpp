// Paths of laid-out variables ("Segment/Group[3](repname)/Variable") and the names of replicas
// (cdi/layout_path.cpp; docs/layout-rules.md).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cdi/cdi_test_util.hpp"
#include "cdi/layout.hpp"

namespace olcb::cdi {
namespace {

using test::all;
using test::lay;
using test::Placed;

// A group with the given repnames.
Element group_named(std::vector<std::string> repnames) {
    Element g;
    g.kind = ElementKind::kGroup;
    g.replication = 5;
    g.repnames = std::move(repnames);
    return g;
}

TEST(LayoutPath, RepnamePaths) {
    auto l = lay(R"(<cdi><segment space="1"><name>Seg</name>
<group replication="3"><name>G</name><repname>A</repname><repname>B</repname><int><name>v</name></int></group>
<group replication="2"><repname>Input</repname><int/></group>
<group><name>Plain</name><group><string size="1"/></group></group>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    std::vector<std::string> paths;
    for (const Placed& p : all(l->layout())) paths.push_back(p.path);
    EXPECT_EQ(paths, (std::vector<std::string>{"Seg/G[1](A)/v", "Seg/G[2](B)/v", "Seg/G[3](B 3)/v",
                                               "Seg/[1](Input 1)/(int)", "Seg/[2](Input 2)/(int)",
                                               "Seg/Plain/(group)/(string)"}));
    Element g;
    EXPECT_EQ(replica_name(g, 0), "");
}

TEST(LayoutPath, OneRepnameIsATemplateNumberedFromOne) {
    const Element g = group_named({"Port"});
    EXPECT_EQ(replica_name(g, 0), "Port 1");
    EXPECT_EQ(replica_name(g, 4), "Port 5");
    EXPECT_EQ(replica_name(g, 999999), "Port 1000000");
}

TEST(LayoutPath, SeveralRepnamesNameReplicasOneByOneThenNumberTheLast) {
    const Element g = group_named({"Left", "Right", "Spare"});
    EXPECT_EQ(replica_name(g, 0), "Left");
    EXPECT_EQ(replica_name(g, 1), "Right");
    EXPECT_EQ(replica_name(g, 2), "Spare");
    EXPECT_EQ(replica_name(g, 3), "Spare 4");
    EXPECT_EQ(replica_name(g, 9), "Spare 10");
}

TEST(LayoutPath, UnnamedSegmentsAndElementsShowTheirSpaceAndTag) {
    auto l = lay(R"(<cdi><segment space="251"><group><name>G</name><eventid/>
<group replication="2"><name>R</name><blob size="3" mode="read"/></group></group>
<int><name>top</name></int></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    std::vector<std::string> paths;
    for (const Placed& p : all(l->layout())) paths.push_back(p.path);
    EXPECT_EQ(paths,
              (std::vector<std::string>{"(space 251)/G/(eventid)", "(space 251)/G/R[1]/(blob)",
                                        "(space 251)/G/R[2]/(blob)", "(space 251)/top"}));
    // The path of a cursor found by address is the one iteration gives.
    EXPECT_EQ(l->layout().find(251, 9).path(), "(space 251)/G/R[1]/(blob)");
    EXPECT_EQ(l->layout().at(2).path(), "(space 251)/G/R[2]/(blob)");
}

}  // namespace
}  // namespace olcb::cdi
