// The one name of a variable, its JMRI backup key, and the replica names shown beside it
// (cdi/variable_name.cpp). Byte-exactness against OpenLCB_Java's files is held by the backup
// tests (tests/conformance/jmri_backup_corpus_test.cpp), which build their keys from it.
#include "cdi/variable_name.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cdi/cdi_test_util.hpp"

namespace olcb::cdi {
namespace {

using test::lay;

struct Named {
    std::string name;
    std::string replicas;
    bool operator==(const Named&) const = default;
};

std::ostream& operator<<(std::ostream& os, const Named& n) {
    return os << n.name << " [" << n.replicas << "]";
}

std::vector<Named> names_of(const Layout& layout) {
    std::vector<Named> out;
    layout.visit([&](const Cursor& c) {
        out.push_back({variable_name(layout, c), replica_names(c)});
        return true;
    });
    return out;
}

TEST(VariableName, NamesJoinedByDotsReplicasZeroBasedRepnamesBeside) {
    auto l = lay(R"(<cdi><segment space="253"><name>Seg</name>
<group replication="2"><name>Port</name><repname>Port</repname><int><name>Mode</name></int>
<group replication="2"><name>Pin</name><int><name>Level</name></int></group></group>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_EQ(names_of(l->layout()), (std::vector<Named>{
                                         {"Seg.Port(0).Mode", "Port 1"},
                                         {"Seg.Port(0).Pin(0).Level", "Port 1"},
                                         {"Seg.Port(0).Pin(1).Level", "Port 1"},
                                         {"Seg.Port(1).Mode", "Port 2"},
                                         {"Seg.Port(1).Pin(0).Level", "Port 2"},
                                         {"Seg.Port(1).Pin(1).Level", "Port 2"},
                                     }));
}

TEST(VariableName, UnnamedPartsCountXmlContentNodesAsJmriDoes) {
    // seg<N> and child<N>: N counts every content node of the parent, whitespace text included.
    auto l = lay(R"(<cdi><segment space="251"><group><name>G</name><eventid/></group>
<int/></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_EQ(names_of(l->layout()),
              (std::vector<Named>{{"seg0.G.child1", ""}, {"seg0.child2", ""}}));
}

TEST(VariableName, NamesAreEscapedAsInABackupLine) {
    EXPECT_EQ(escape_backup_text("a=b\\c\td"), "a\\x003db\\x005cc\\x0009d");
    EXPECT_EQ(escape_backup_text("Gr\xC3\xBC\xC3\x9F"), "Gr\xC3\xBC\xC3\x9F");  // UTF-8 kept
    EXPECT_EQ(escape_backup_text("\xFF"), "\\x00ff");  // not UTF-8: the byte's code point
    auto l = lay(R"(<cdi><segment space="253"><name>A=B</name><int><name>x</name></int>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    EXPECT_EQ(variable_name(l->layout(), l->layout().begin()), "A\\x003dB.x");
}

TEST(VariableName, AVariableIsFoundByItsNameOrTheOlderSlashPath) {
    auto l = lay(R"(<cdi><segment space="253"><name>Seg</name>
<group replication="2"><name>Port</name><repname>Port</repname><int><name>Mode</name></int></group>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    const Cursor second = l->layout().at(1);
    EXPECT_TRUE(names_variable(l->layout(), second, "Seg.Port(1).Mode"));
    EXPECT_TRUE(names_variable(l->layout(), second, "Seg/Port[2](Port 2)/Mode"));
    EXPECT_FALSE(names_variable(l->layout(), second, "Seg.Port(0).Mode"));
}

}  // namespace
}  // namespace olcb::cdi
