// Making a JMRI-format configuration backup of a node: one line per variable as OpenLCB_Java
// writes it, and read failures listed with the variable left out.
#include "conformance/run/config_backup.hpp"

#include <gtest/gtest.h>

#include "conformance/backup_test_util.hpp"

namespace olcb::conform {
namespace {

using testing::ConfigBackupTest;

TEST_F(ConfigBackupTest, WritesOneLinePerVariableAsOpenLcbJavaDoes) {
    memory_.spaces[253][1] = 0xFF;  // Trim = -5 (signed, big-endian): written unsigned
    memory_.spaces[253][2] = 0xFB;
    const std::string label = "a=b";
    std::copy(label.begin(), label.end(), memory_.spaces[253].begin() + 3);
    for (int i = 0; i < 8; ++i) memory_.spaces[253][11 + i] = static_cast<std::uint8_t>(i + 1);
    const std::string text = backup();
    EXPECT_EQ(text.find("\n\n"), std::string::npos);
    EXPECT_EQ(text.rfind("# ", 0), 0u);
    EXPECT_NE(text.find("\nMain.Trim=65531\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\nMain.Label=a\\x003db\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\nMain.Event=01.02.03.04.05.06.07.08\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\nMain.Gain=0\n"), std::string::npos) << text;
    EXPECT_EQ(config_backup_node(text), "05.01.01.01.22.00");
    EXPECT_EQ(memory_.writes, 0u);
}

TEST_F(ConfigBackupTest, ReadFailuresAreListedAndTheVariableLeftOut) {
    memory_.spaces.erase(251);
    std::vector<std::string> errors;
    const std::string text = make_config_backup(*cdi_.layout, memory_, "05.01.01.01.22.00", errors);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("seg3.child0"), std::string::npos);
    EXPECT_EQ(text.find("seg3.child0="), std::string::npos);
    EXPECT_NE(text.find("Main.Enabled=0"), std::string::npos);
}

}  // namespace
}  // namespace olcb::conform
