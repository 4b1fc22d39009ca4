// The safety promise end to end, programs run as a user would over GridConnect TCP: against the
// OpenMRN-like node (Version in "Internal data", abort-on-value, factory-reset-on-version-change)
// a full --reboot run neither kills nor resets it; a node that restarts mid-run is reported with
// the variable written last; a node that never comes back leaves a backup whose printed restore
// command works afterwards; the image files are byte-identical whenever the run says so.
#include <gtest/gtest.h>

#include <sstream>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

namespace fs = std::filesystem;
constexpr const char* kNode = "05.01.01.01.22.00";

std::vector<std::string> run_args(const Simnode& n, const TempDir& out,
                                  std::vector<std::string> extra = {},
                                  const std::string& node = kNode) {
    std::vector<std::string> args = {
        "--connect", n.connect(), "--node", node, "--backup", (out.path() / "safety.txt").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

std::string status_of(const std::string& text, const std::string& id) {
    for (const auto& [status, check] : check_lines(text)) {
        if (check == id) return status;
    }
    return "";
}

TEST(LccConformSafety, OpenMrnLikeNodeSurvivesAFullRebootRunUnchanged) {
    Simnode n(source_path("scenarios/faults/openmrn-like.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out, {"--reboot"}));
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(status_of(text, "encoding.persist-after-reboot"), "PASS") << text;
    EXPECT_NE(text.find("SKIP  encoding.protected  seg7.Internal data.Version"), std::string::npos)
        << text;
    EXPECT_EQ(text.find("node."), std::string::npos) << text;  // never died, never restarted
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

TEST(LccConformSafety, WriteProtectedProbesInternalDataAndTheNodeStillSurvives) {
    Simnode n(source_path("scenarios/faults/openmrn-like.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out, {"--reboot", "--write-protected"}));
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(status_of(text, "encoding.protected"), "") << text;
    EXPECT_EQ(text.find("node."), std::string::npos) << text;
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

TEST(LccConformSafety, ARestartMidRunNamesTheVariableAndTheMemoryEndsIdentical) {
    // The 7th stored write: write-under-mask makes 2 before the encoding checks, whose 5th write
    // is the original going back into the first variable after its 4 test values.
    Simnode n(source_path("scenarios/default.ini"), {"--fault", "reboot-on-write=7"});
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out));
    EXPECT_EQ(code, 1) << text;
    EXPECT_EQ(status_of(text, "node.rebooted"), "FAIL") << text;
    EXPECT_NE(text.find("restoring Node identity.User Name"), std::string::npos) << text;
    EXPECT_NE(text.find("last test value written"), std::string::npos) << text;
    EXPECT_EQ(status_of(text, "encoding.restore"), "PASS") << text;
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

// The "run: lcc-conform ... restore FILE" command the report printed, as arguments.
std::vector<std::string> printed_restore(const std::string& text) {
    const auto at = text.find("run: lcc-conform ");
    if (at == std::string::npos) return {};
    std::istringstream words(text.substr(at + 17, text.find('\n', at) - at - 17));
    std::vector<std::string> args;
    for (std::string w; words >> w;) args.push_back(w);
    return args;
}

TEST(LccConformSafety, ANodeThatNeverComesBackLeavesAWorkingRestoreCommand) {
    Simnode n(source_path("scenarios/default.ini"),
              {"--fault", "abort-on-value=12000", "--watch-variable", "Node identity/User Name"});
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out, {"--write-protected", "--node-wait", "1"}));
    EXPECT_EQ(code, 2) << text;
    EXPECT_EQ(status_of(text, "node.stopped-answering"), "FAIL") << text;
    EXPECT_EQ(status_of(text, "encoding.restore"), "FAIL") << text;
    const auto command = printed_restore(text);
    ASSERT_GE(command.size(), 4u) << text;
    EXPECT_EQ(command.back(), fs::absolute(out.path() / "safety.txt").string());
    EXPECT_TRUE(fs::exists(command.back()));
    EXPECT_NE(snapshot_images(n.images.path()), before);  // the test name is still in the node

    // Once the node is back (12 s of silence), the printed command puts everything back.
    int restored = -1;
    std::string restore_text;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (restored != 0 && std::chrono::steady_clock::now() < deadline) {
        std::tie(restored, restore_text) = conform(command);
    }
    EXPECT_EQ(restored, 0) << restore_text;
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

TEST(LccConformSafety, OneLineCdiHasACorrectXmlDeclaration) {
    Simnode n(source_path("scenarios/one-line.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto [code, text] = conform(run_args(n, out));
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(status_of(text, "cdi.xml-declaration"), "PASS") << text;
}

TEST(LccConformSafety, IoBoardScenarioHasNoFalseFailure) {
    Simnode n(source_path("scenarios/io-board.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out, {"--reboot"}, "05.01.01.01.22.10"));
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

}  // namespace
}  // namespace olcb::e2e

#endif  // SIMNODE_PATH && LCC_CONFORM_PATH
