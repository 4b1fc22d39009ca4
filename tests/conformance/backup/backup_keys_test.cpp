// The JMRI backup keys: OpenLCB_Java's names for every variable a CDI lays out.
#include "conformance/backup/backup_keys.hpp"

#include <gtest/gtest.h>

#include "conformance/backup_test_util.hpp"

namespace olcb::conform {
namespace {

using testing::Cdi;
using testing::ConfigBackupTest;
using testing::FakeMemory;

TEST_F(ConfigBackupTest, UnnamedElementsAreNumberedByTheirContentNodeIndex) {
    // Main's children: "\n  ", <name>, "\n  ", Enabled, ... so the unnamed int is node 13;
    // <cdi>'s: "\n", <segment>, "\n", <segment>, so the unnamed segment is seg3.
    const std::vector<std::string> expected = {"Main.Enabled",
                                               "Main.Trim",
                                               "Main.Label",
                                               "Main.Event",
                                               "Main.Gain",
                                               "Main.child13",
                                               "Main.Port(0).Line(0).Mode",
                                               "Main.Port(0).Line(1).Mode",
                                               "Main.Port(0).Line(2).Mode",
                                               "Main.Port(0).child4",
                                               "Main.Port(1).Line(0).Mode",
                                               "Main.Port(1).Line(1).Mode",
                                               "Main.Port(1).Line(2).Mode",
                                               "Main.Port(1).child4",
                                               "seg3.child0"};
    EXPECT_EQ(keys(), expected);  // the action and the bit are left out, as OpenLCB_Java does
}

}  // namespace
}  // namespace olcb::conform
