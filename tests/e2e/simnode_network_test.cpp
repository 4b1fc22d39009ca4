// Many nodes in one simnode process: scenarios/network-1000.ini brings up 1,000 nodes whose
// aliases are all distinct, and each answers a global Verify Node ID.
#include <gtest/gtest.h>

#include <set>

#include "e2e/e2e_util.hpp"

namespace olcb::e2e {
namespace {

constexpr std::size_t kNodes = 1000;

TEST(SimnodeNetwork, ThousandNodesHaveDistinctAliases) {
#ifndef SIMNODE_PATH
    GTEST_SKIP() << "simnode is not built";
#else
    // Creating 3,000 fresh image files costs one fsync each; on a RAM disk when there is one,
    // as the subject here is alias allocation.
    std::error_code ec;
    TempDir images("simnode-network",
                   std::filesystem::is_directory("/dev/shm", ec) ? "/dev/shm" : "");
    auto child = Child::spawn(
        SIMNODE_PATH, {"--scenario", source_path("scenarios/network-1000.ini").string(), "--listen",
                       "127.0.0.1:0", "--image-dir", images.str()});
    ASSERT_TRUE(child);
    const auto port = child->wait_listening(milliseconds(120000));
    ASSERT_TRUE(port) << child->output();
    // The tool keeps reading the segment while the nodes start (a hub drops a client that
    // stops reading).
    ToolNode tool(*port);
    std::optional<std::string> started;
    tool.run_until(
        [&] {
            if (!started)
                started = child->wait_line("simnode: 1000 node(s) initialized", milliseconds(0));
            return started && tool.stack().initialized();
        },
        milliseconds(60000));
    ASSERT_TRUE(started) << child->output();
    ASSERT_TRUE(tool.stack().initialized());
    std::cout << "[ network  ] " << *started << "\n";

    std::set<std::uint64_t> expected;
    for (std::uint64_t i = 0; i < 600; ++i) expected.insert(0x05'01'01'01'30'00ull + i);
    for (std::uint64_t i = 0; i < 400; ++i) expected.insert(0x05'01'01'01'40'00ull + i);

    // Global Verify Node ID, resent every 2 s until every node has answered.
    std::map<std::uint64_t, std::uint16_t> alias_of;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (alias_of.size() < kNodes && std::chrono::steady_clock::now() < deadline) {
        tool.messages().clear();
        tool.send(Mti::kVerifyNodeIdGlobal);
        tool.run_until(
            [&] {
                for (const auto& m : tool.messages()) {
                    if (m.mti != Mti::kVerifiedNodeId && m.mti != Mti::kVerifiedNodeIdSimple) {
                        continue;
                    }
                    const auto id = NodeId::from_bytes(m.payload);
                    if (id) alias_of[id->value()] = m.source.alias;
                }
                tool.messages().clear();
                return alias_of.size() >= kNodes;
            },
            milliseconds(2000));
    }
    ASSERT_EQ(alias_of.size(), kNodes);
    std::set<std::uint16_t> aliases;
    for (const auto& [id, alias] : alias_of) {
        EXPECT_TRUE(expected.contains(id)) << NodeId(id).to_string();
        EXPECT_NE(alias, 0);
        aliases.insert(alias);
    }
    EXPECT_EQ(aliases.size(), kNodes) << "duplicate aliases";
    EXPECT_TRUE(std::filesystem::is_directory(images.path() / "05.01.01.01.32.57"));
#endif
}

}  // namespace
}  // namespace olcb::e2e
