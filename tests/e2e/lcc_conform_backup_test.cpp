// lcc-conform's configuration backups as a user runs them against the simnode program over
// GridConnect TCP: restore --dry-run, diff of two files and of a node against a file, the CSV
// form both ways, files for another node type or with unknown keys, and JMRI files that name
// no node (docs/backup.md).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

namespace fs = std::filesystem;
constexpr const char* kNode = "05.01.01.01.22.00";

// lcc-conform with args, its stderr merged into the output (the verdicts users read are there).
std::pair<int, std::string> conform_all(const std::vector<std::string>& args) {
    std::vector<std::string> all = {"-c", "exec \"$0\" \"$@\" 2>&1", LCC_CONFORM_PATH};
    all.insert(all.end(), args.begin(), args.end());
    return run_program("/bin/sh", all, milliseconds(60000));
}

void write_text(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
}

// text with the first occurrence of from replaced by to.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// The lines of a backup that are not '#' comments: what JMRI writes.
std::string without_comments(const std::string& text) {
    std::istringstream in(text);
    std::string out;
    for (std::string line; std::getline(in, line);) {
        if (!line.starts_with("#")) out += line + "\n";
    }
    return out;
}

class LccConformBackup : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_NE(sim_.port, 0) << "simnode did not start";
        base_ = out_.path() / "base.txt";
        const auto [code, text] = run({"backup", "--node", kNode, base_.string()});
        ASSERT_EQ(code, 0) << text;
        saved_ = read_text(base_);
        ASSERT_NE(saved_.find("\nSettings.Trim=65531\n"), std::string::npos) << saved_;
    }
    std::pair<int, std::string> run(std::vector<std::string> args) {
        args.insert(args.begin(), {"--connect", sim_.connect()});
        return conform_all(args);
    }
    fs::path file(const std::string& name, const std::string& text) {
        fs::path p = out_.path() / name;
        write_text(p, text);
        return p;
    }
    // The node's configuration as a fresh backup.
    std::string current() {
        const fs::path p = out_.path() / "current.txt";
        const auto [code, text] = run({"backup", "--node", kNode, p.string()});
        EXPECT_EQ(code, 0) << text;
        return read_text(p);
    }

    Simnode sim_{source_path("scenarios/default.ini")};
    TempDir out_{"lcc-conform-backup-e2e"};
    fs::path base_;
    std::string saved_;
};

TEST_F(LccConformBackup, DryRunAndDiffShowWhatARestoreWouldChange) {
    const std::string edited_text =
        replaced(replaced(saved_, "Settings.Trim=65531", "Settings.Trim=7"),
                 "Node identity.User Name=simnode default", "Node identity.User Name=a\\x003db");
    const fs::path edited = file("edited.txt", edited_text);
    const auto images = snapshot_images(sim_.images.path());

    auto [code, text] = run({"restore", "--dry-run", edited.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("restore --dry-run: 2 change(s) to node 05.01.01.01.22.00"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("nothing written"), std::string::npos) << text;
    EXPECT_NE(text.find("change     Settings.Trim: node \"65531\" -> file \"7\""),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("Node identity.User Name: node \"simnode default\" -> file \"a\\x003db\""),
              std::string::npos)
        << text;
    EXPECT_EQ(snapshot_images(sim_.images.path()), images);
    EXPECT_EQ(current(), saved_);

    std::tie(code, text) = run({"diff", "--node", kNode, edited.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("2 change(s) a restore would write"), std::string::npos) << text;
    EXPECT_NE(text.find("change     Settings.Trim: node \"65531\" -> file \"7\""),
              std::string::npos)
        << text;
    std::tie(code, text) = run({"diff", "--node", kNode, base_.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("0 change(s) a restore would write"), std::string::npos) << text;

    std::tie(code, text) = conform_all({"diff", base_.string(), edited.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("changed    Settings.Trim: \"65531\" -> \"7\""), std::string::npos) << text;
    EXPECT_NE(text.find("diff: 2 difference(s)"), std::string::npos) << text;
    std::tie(code, text) = conform_all({"diff", base_.string(), base_.string()});
    EXPECT_EQ(code, 0) << text;

    std::tie(code, text) = run({"restore", edited.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("restore: 2 variable(s) written to node 05.01.01.01.22.00"),
              std::string::npos)
        << text;
    EXPECT_EQ(current(), edited_text);
}

TEST_F(LccConformBackup, CsvBackupRestoresAndDiffsLikeTheKeyValueForm) {
    const fs::path csv = out_.path() / "config.csv";
    auto [code, text] = run({"backup", "--csv", "--node", kNode, csv.string()});
    ASSERT_EQ(code, 0) << text;
    const std::string rows = read_text(csv);
    ASSERT_EQ(rows.rfind("key,value,type,space,address,size\r\n", 0), 0u) << rows;
    EXPECT_NE(rows.find("\r\nSettings.Trim,65531,int,253,"), std::string::npos) << rows;
    std::tie(code, text) = conform_all({"diff", csv.string(), base_.string()});
    EXPECT_EQ(code, 0) << text;

    const fs::path edited =
        file("edited.csv", replaced(rows, "Settings.Trim,65531,", "Settings.Trim,-9,"));
    std::tie(code, text) = run({"restore", "--node", kNode, edited.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("restore: 1 variable(s) written"), std::string::npos) << text;
    EXPECT_EQ(current(), replaced(saved_, "Settings.Trim=65531", "Settings.Trim=65527"));
}

TEST_F(LccConformBackup, AFileForAnotherNodeTypeExits1AndWritesNothing) {
    const fs::path other =
        file("other.txt", "seg5.User Name=x\nseg7.Internal data.Version=3\nSettings.Trim=1\n");
    const auto images = snapshot_images(sim_.images.path());
    const auto [code, text] = run({"restore", "--node", kNode, other.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("is for another node type: it matches 1 of the"), std::string::npos)
        << text;
    EXPECT_NE(text.find("nothing written"), std::string::npos) << text;
    EXPECT_NE(text.find("unknown    line 1: seg5.User Name"), std::string::npos) << text;
    EXPECT_EQ(snapshot_images(sim_.images.path()), images);
    EXPECT_EQ(current(), saved_);
}

TEST_F(LccConformBackup, UnknownKeysAndBadValuesExit1UnlessAllowed) {
    const std::string extra =
        replaced(saved_, "Settings.Trim=65531\n", "Settings.Trim=70000\nNo.Such=1\n");
    const fs::path f = file("extra.txt", extra);
    auto [code, text] = run({"restore", f.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("unknown    line "), std::string::npos) << text;
    EXPECT_NE(text.find(": No.Such"), std::string::npos) << text;
    EXPECT_NE(text.find("bad value  line "), std::string::npos) << text;
    EXPECT_NE(text.find("out of range"), std::string::npos) << text;
    EXPECT_NE(text.find("--allow-unknown accepts them"), std::string::npos) << text;
    std::tie(code, text) = run({"restore", "--allow-unknown", f.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(current(), saved_);  // the bad value was not written
}

TEST_F(LccConformBackup, AJmriFileWithoutNodeLineUsesTheOnlyNode) {
    const fs::path jmri = file(
        "jmri.txt", without_comments(replaced(saved_, "Settings.Trim=65531", "Settings.Trim=3")));
    const auto [code, text] = run({"restore", jmri.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("using node 05.01.01.01.22.00, the only node on the bus"),
              std::string::npos)
        << text;
    EXPECT_NE(current().find("\nSettings.Trim=3\n"), std::string::npos);
}

TEST(LccConformBackupNodes, SeveralNodesAreListedAndNoneIsChosen) {
    TempDir dir("lcc-conform-backup-two");
    const fs::path ini = dir.path() / "two.ini";
    write_text(ini, "[node.pair]\nnode-id = 05.01.01.01.22.10\ncount = 2\ncdi = " +
                        source_path("scenarios/default.xml").string() + "\n");
    Simnode sim(ini);
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    const fs::path f = dir.path() / "jmri.txt";
    write_text(f, "Settings.Trim=3\n");
    const auto [code, text] = conform_all({"--connect", sim.connect(), "restore", f.string()});
    EXPECT_EQ(code, 2) << text;
    EXPECT_NE(text.find("2 nodes answer; say which with --node ID"), std::string::npos) << text;
    EXPECT_NE(text.find("05.01.01.01.22.10"), std::string::npos) << text;
    EXPECT_NE(text.find("05.01.01.01.22.11"), std::string::npos) << text;
}

TEST(LccConformBackupUsage, TheUsageShowsNodeDryRunCsvAndDiff) {
    const auto [code, text] = conform_all({"--help"});
    EXPECT_EQ(code, 0);
    for (const char* s : {"restore [--node ID]", "--dry-run", "--allow-unknown", "--csv",
                          "diff A B", "diff [--node ID] FILE"}) {
        EXPECT_NE(text.find(s), std::string::npos) << s << "\n" << text;
    }
}

}  // namespace
}  // namespace olcb::e2e

#endif
