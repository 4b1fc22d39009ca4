// Making a JMRI-format configuration backup of a node: one line per variable as OpenLCB_Java
// writes it, and read failures listed with the variable left out.
#include "conformance/run/config_backup.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "conformance/backup_test_util.hpp"
#include "conformance/sim_bench.hpp"
#include "support/temp_files.hpp"

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

// `lcc-conform backup FILE` opened FILE with O_TRUNC: a link planted at FILE had its target
// overwritten. Now the file is replaced (base::write_file): links at FILE or at FILE.tmp are
// never written through.
TEST(RunConfigBackup, PlantedLinksAtTheFileAndItsTemporaryNameAreNotWrittenThrough) {
    namespace fs = std::filesystem;
    test_support::TempDir dir("config-backup-links");
    const fs::path outside = dir.path() / "outside.txt";
    testing::SimBench bench;
    ASSERT_TRUE(bench.start());
    for (const std::string name : {"at-path.txt", "at-tmp.txt"}) {
        { std::ofstream(outside, std::ios::binary) << "precious\n"; }
        const fs::path file = dir.path() / name;
        fs::create_symlink(outside,
                           name == "at-path.txt" ? file : fs::path(file.string() + ".tmp"));
        std::ostringstream out, err;
        EXPECT_EQ(run_config_backup(*bench.session, {"", file.string(), false}, out, err), 0)
            << err.str();
        EXPECT_EQ(test_support::read_text(outside), "precious\n") << name;
        EXPECT_FALSE(fs::is_symlink(file)) << name;
        EXPECT_NE(test_support::read_text(file).find("\nNode identity.User Name=simnode default\n"),
                  std::string::npos)
            << test_support::read_text(file);
    }
}

}  // namespace
}  // namespace olcb::conform
