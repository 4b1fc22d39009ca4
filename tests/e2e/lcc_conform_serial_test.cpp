// lcc-conform and simnode over a serial line, as with a USB-CAN adapter: two pseudo-terminals
// joined like a null-modem cable (tests/support/pty_relay.hpp). The default scenario passes,
// --list works, and unplugging lcc-conform's side mid-run ends in a clear error and a restore:
// at once when the adapter comes back, or later with the command the report names.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "e2e/conform_util.hpp"
#include "support/pty_relay.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

using test::PtyRelay;
constexpr const char* kNode = "05.01.01.01.22.00";

/// The default scenario on side A of a relay (its TCP hub on an ephemeral port, unused).
struct SerialSimnode {
    TempDir dir{"lcc-conform-serial"};
    TempDir images{"lcc-conform-serial-img"};
    PtyRelay relay{dir.path()};
    std::unique_ptr<Child> child;
    bool ready = false;

    SerialSimnode() {
        child =
            Child::spawn(SIMNODE_PATH, {"--scenario", source_path("scenarios/default.ini").string(),
                                        "--listen", "127.0.0.1:0", "--image-dir", images.str(),
                                        "--serial", relay.path(PtyRelay::Side::A).string()});
        ready = child && child->wait_line("simnode: serial ") &&
                child->wait_line("simnode: 1 node(s) initialized");
    }
    std::string tool_side() const { return relay.path(PtyRelay::Side::B).string(); }
};

// Waits (bounded) until `file` exists or the child ended; true when it exists.
bool wait_for_file(const fs::path& file, Child& run) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!fs::exists(file) && std::chrono::steady_clock::now() < deadline &&
           !run.wait_for(milliseconds(2))) {
    }
    return fs::exists(file);
}

// Starts a full run on the tool side and unplugs its adapter once the safety backup exists
// (just before the first write: the encoding checks are under way); nullptr when the backup
// never appeared.
std::unique_ptr<Child> run_and_unplug_mid_run(SerialSimnode& sim, const fs::path& backup,
                                              const std::string& link_wait) {
    auto run =
        Child::spawn(LCC_CONFORM_PATH, {"--serial", sim.tool_side(), "--node", kNode, "--backup",
                                        backup.string(), "--link-wait", link_wait});
    if (!run || !wait_for_file(backup, *run)) return nullptr;
    sim.relay.unplug(PtyRelay::Side::B);
    return run;
}

// Waits (bounded) for the run to end and reads the rest of its output; false on timeout.
bool finish(Child& run) {
    if (!run.wait_for(milliseconds(60000))) return false;
    run.wait_line("\x01never", milliseconds(2000));
    return true;
}

bool has_line(const std::vector<std::pair<std::string, std::string>>& lines,
              const std::string& status, const std::string& id) {
    for (const auto& [s, i] : lines) {
        if (s == status && i == id) return true;
    }
    return false;
}

TEST(LccConformSerial, DefaultScenarioPassesOverSerial) {
    SerialSimnode sim;
    ASSERT_TRUE(sim.ready) << "simnode did not start on the serial line:\n"
                           << (sim.child ? sim.child->output() : "");
    TempDir out("lcc-conform-serial-out");
    const auto before = snapshot_images(sim.images.path());
    const auto [code, text] = conform({"--serial", sim.tool_side(), "--node", kNode, "--backup",
                                       (out.path() / "safety.txt").string()});
    EXPECT_EQ(code, 0) << text;
    const auto lines = check_lines(text);
    EXPECT_GT(lines.size(), 40u) << text;
    for (const auto& [status, id] : lines) EXPECT_NE(status, "FAIL") << id;
    EXPECT_TRUE(has_line(lines, "PASS", "encoding.restore")) << text;
    EXPECT_EQ(settled_images(sim.images.path(), before), before);
    EXPECT_GT(sim.relay.bytes_relayed(), 10000u) << "the run did not go over the serial line";
}

TEST(LccConformSerial, ListOverSerial) {
    SerialSimnode sim;
    ASSERT_TRUE(sim.ready);
    const auto [code, text] = conform({"--serial", sim.tool_side(), "--list"});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find(kNode), std::string::npos) << text;
    EXPECT_NE(text.find("simnode default"), std::string::npos) << text;
}

TEST(LccConformSerial, MissingDeviceIsAUsageError) {
    TempDir dir("lcc-conform-serial");
    const auto missing = (dir.path() / "ttyACM9").string();
    auto run = Child::spawn(LCC_CONFORM_PATH, {"--serial", missing, "--list"});
    ASSERT_TRUE(run);
    ASSERT_TRUE(run->wait_for(milliseconds(10000)));
    EXPECT_EQ(run->wait(), 2);
}

TEST(LccConformSerial, SimnodeSurvivesItsAdapterBeingUnplugged) {
    SerialSimnode sim;
    ASSERT_TRUE(sim.ready);
    sim.relay.unplug(PtyRelay::Side::A);
    // Reported, then reopened once the adapter is back under the same path.
    EXPECT_FALSE(sim.child->wait_for(milliseconds(300))) << "simnode exited on a lost adapter";
    sim.relay.replug(PtyRelay::Side::A);
    ASSERT_TRUE(sim.child->wait_line("simnode: serial ", milliseconds(10000)))
        << sim.child->output();
    const auto [code, text] = conform({"--serial", sim.tool_side(), "--list"});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find(kNode), std::string::npos) << text;
}

TEST(LccConformSerial, UnplugMidRunRestoresWhenTheAdapterReturns) {
    SerialSimnode sim;
    ASSERT_TRUE(sim.ready);
    TempDir out("lcc-conform-serial-out");
    const auto before = snapshot_images(sim.images.path());
    const fs::path backup = out.path() / "safety.txt";
    auto run = run_and_unplug_mid_run(sim, backup, "20");
    ASSERT_TRUE(run) << "the safety backup file never appeared";
    // Down long enough for lcc-conform to notice, then the adapter is back under the same path.
    EXPECT_FALSE(run->wait_for(milliseconds(500))) << "lcc-conform gave up at once";
    sim.relay.replug(PtyRelay::Side::B);
    ASSERT_TRUE(finish(*run)) << "lcc-conform did not finish";
    EXPECT_EQ(run->wait(), 2) << run->output();
    const auto lines = check_lines(run->output());
    EXPECT_TRUE(has_line(lines, "FAIL", "link.lost")) << run->output();
    EXPECT_TRUE(has_line(lines, "PASS", "encoding.restore")) << run->output();
    for (const auto& [status, id] : lines) {
        if (id.starts_with("encoding.") && id != "encoding.restore") {
            EXPECT_EQ(status, "SKIP") << id << " is judged although the link went down";
        }
    }
    EXPECT_EQ(settled_images(sim.images.path(), before), before);
    EXPECT_FALSE(fs::exists(backup)) << "a verified restore removes the backup";
}

TEST(LccConformSerial, UnplugWithoutReturnLeavesTheBackupAndTheCommand) {
    SerialSimnode sim;
    ASSERT_TRUE(sim.ready);
    TempDir out("lcc-conform-serial-out");
    const auto before = snapshot_images(sim.images.path());
    const fs::path backup = out.path() / "safety.txt";
    auto run = run_and_unplug_mid_run(sim, backup, "1");
    ASSERT_TRUE(run) << "the safety backup file never appeared";
    ASSERT_TRUE(finish(*run)) << "lcc-conform did not finish";
    EXPECT_EQ(run->wait(), 2) << run->output();
    const auto lines = check_lines(run->output());
    EXPECT_TRUE(has_line(lines, "FAIL", "link.lost")) << run->output();
    EXPECT_TRUE(has_line(lines, "FAIL", "encoding.restore")) << run->output();
    ASSERT_TRUE(fs::exists(backup)) << "the backup must stay when nothing could be restored";
    const std::string command =
        "lcc-conform --serial " + sim.tool_side() + " restore " + backup.string();
    EXPECT_NE(run->output().find(command), std::string::npos)
        << "the report must name the restore command:\n"
        << run->output();

    // The adapter is back: the named command puts the node back as it was.
    sim.relay.replug(PtyRelay::Side::B);
    const auto [code, text] = conform({"--serial", sim.tool_side(), "restore", backup.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(settled_images(sim.images.path(), before), before);
}

}  // namespace
}  // namespace olcb::e2e

#endif
