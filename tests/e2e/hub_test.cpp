// Several simnode processes on one segment: one runs the GridConnect hub, two join it with
// --connect (as simnodes on other machines join JMRI's or OpenMRN's hub), and lcc-conform,
// joining the same hub, finds and checks all three nodes.
#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

const std::vector<std::string> kNodes = {"05.01.01.01.22.00", "05.01.01.01.22.01",
                                         "05.01.01.01.22.02"};

struct ThreeProcessSegment {
    TempDir images{"hub-e2e-img"};
    std::unique_ptr<Child> hub;
    std::vector<std::unique_ptr<Child>> clients;
    std::uint16_t port = 0;
    bool ready = false;

    ThreeProcessSegment() {
        hub =
            Child::spawn(SIMNODE_PATH, {"--scenario", source_path("scenarios/default.ini").string(),
                                        "--listen", "127.0.0.1:0", "--image-dir", images.str()});
        if (!hub) return;
        if (auto p = hub->wait_listening()) port = *p;
        if (port == 0 || !hub->wait_line("simnode: 1 node(s) initialized")) return;
        const std::string where = "127.0.0.1:" + std::to_string(port);
        const std::string cdis[] = {"scenarios/default.xml", "scenarios/io-board.xml"};
        for (std::size_t i = 1; i < kNodes.size(); ++i) {
            auto c = Child::spawn(
                SIMNODE_PATH,
                {"--node-id", kNodes[i], "--cdi", source_path(cdis[i - 1]).string(), "--connect",
                 where, "--image-dir", images.str(), "--user-name", "joined " + std::to_string(i)});
            if (!c || !c->wait_line("simnode: connected to hub") ||
                !c->wait_line("simnode: 1 node(s) initialized")) {
                return;
            }
            clients.push_back(std::move(c));
        }
        ready = true;
    }
    std::string connect() const { return "127.0.0.1:" + std::to_string(port); }
};

TEST(HubE2e, ListShowsTheHubNodeAndBothJoinedNodes) {
    ThreeProcessSegment seg;
    ASSERT_TRUE(seg.ready) << "the three simnodes did not come up";
    const auto [code, text] = conform({"--connect", seg.connect(), "--list"});
    EXPECT_EQ(code, 0) << text;
    for (const auto& id : kNodes) EXPECT_NE(text.find(id), std::string::npos) << id << "\n" << text;
    EXPECT_NE(text.find("joined 1"), std::string::npos) << text;
    EXPECT_NE(text.find("joined 2"), std::string::npos) << text;
}

TEST(HubE2e, ChecksAllThreeNodesAndRestoresThem) {
    ThreeProcessSegment seg;
    ASSERT_TRUE(seg.ready) << "the three simnodes did not come up";
    TempDir out("hub-e2e-out");
    const auto before = snapshot_images(seg.images.path());
    const auto [code, text] =
        conform({"--connect", seg.connect(), "--backup", (out.path() / "safety.txt").string()},
                milliseconds(120000));
    EXPECT_EQ(code, 0) << text;
    std::size_t restores = 0;
    for (const auto& [status, id] : check_lines(text)) {
        EXPECT_NE(status, "FAIL") << id;
        if (id == "encoding.restore" && status == "PASS") ++restores;
    }
    EXPECT_EQ(restores, kNodes.size()) << text;
    for (const auto& id : kNodes) EXPECT_NE(text.find(id), std::string::npos) << id;
    EXPECT_EQ(settled_images(seg.images.path(), before), before);
}

}  // namespace
}  // namespace olcb::e2e

#endif
