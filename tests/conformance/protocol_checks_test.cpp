// The protocol checks against the simulated node: no false failure on the default node, and each
// fault of docs/faults.md (J1's share) caught with its category.
#include <gtest/gtest.h>
#include <algorithm>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "conformance/conform_test_util.hpp"
#include "conformance/link.hpp"
#include "conformance/protocol_checks.hpp"
#include "conformance/session.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/faults.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::conform {
namespace {

struct Bench {
    SimNetwork net;
    std::unique_ptr<simnode::SimNode> dut;
    std::unique_ptr<Link> link;
    std::unique_ptr<Session> session;

    explicit Bench(const std::vector<std::string>& faults = {}) {
        std::string error;
        simnode::NodeConfig cfg;
        cfg.node_id = kDut;
        cfg.cdi = read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios/default.xml");
        cfg.user_name = "simnode default";
        auto fs = simnode::parse_faults(faults, error);
        EXPECT_TRUE(fs) << error;
        if (fs) cfg.faults = *fs;
        dut = simnode::SimNode::create(cfg, error);
        EXPECT_TRUE(dut) << error;
        net.add_stack(dut->stack());
        dut->stack().start(net.now());
        link = make_sim_link(net, kTool);
        session = std::make_unique<Session>(*link);
    }

    std::vector<CheckResult> run(CheckContext& ctx) {
        EXPECT_TRUE(session->start());
        auto node = session->find_node(kDut);
        EXPECT_TRUE(node);
        if (!node) return {};
        return run_protocol_checks(*session, *node, ProtocolOptions{}, ctx);
    }
};

std::string dump(const std::vector<CheckResult>& results) {
    std::string s;
    for (const auto& r : results) {
        s += std::string(status_name(r.status)) + " " + r.id + " [" +
             std::string(category_name(r.category)) + "] " + r.message;
        if (r.status == Status::kFail) s += " expected=" + r.expected + " seen=" + r.seen;
        s += "\n";
    }
    return s;
}

TEST(SessionTest, DiscoversAndReadsTheSimNode) {
    Bench b;
    ASSERT_TRUE(b.session->start());
    auto nodes = b.session->discover(std::chrono::milliseconds(200));
    ASSERT_EQ(nodes.size(), 1u);
    EXPECT_EQ(nodes[0].id, kDut);
    EXPECT_EQ(nodes[0].alias, b.dut->stack().alias());
    auto pip = b.session->protocol_support(nodes[0]);
    ASSERT_TRUE(pip);
    EXPECT_TRUE(pip->has(Protocol::kMemoryConfiguration));
    MemResult r = b.session->read(nodes[0], memory::Space::kCdi, 0, 5);
    ASSERT_TRUE(r.ok);
    EXPECT_EQ(std::string(r.data.begin(), r.data.end()), "<?xml");
    EXPECT_TRUE(r.datagram_ok_seen);
    EXPECT_TRUE(r.reply_pending);
    MemResult bad = b.session->read(nodes[0], static_cast<memory::Space>(0x51), 0, 5);
    EXPECT_FALSE(bad.ok);
    EXPECT_EQ(bad.error, 0x1081);
}

TEST(ProtocolChecksTest, DefaultNodeHasNoFailure) {
    Bench b;
    CheckContext ctx;
    auto results = b.run(ctx);
    ASSERT_GT(results.size(), 25u);
    for (const auto& r : results) EXPECT_NE(r.status, Status::kFail) << dump(results);
    EXPECT_TRUE(ctx.layout.has_value());
    EXPECT_TRUE(ctx.cdi_nul_found);
    EXPECT_TRUE(ctx.snip.has_value());
}

struct FaultCase {
    const char* fault;
    Category category;
};

class FaultTest : public ::testing::TestWithParam<FaultCase> {};

TEST_P(FaultTest, FailsWithTheFaultsCategory) {
    Bench b({GetParam().fault});
    CheckContext ctx;
    auto results = b.run(ctx);
    const bool caught = std::any_of(results.begin(), results.end(), [](const CheckResult& r) {
        return r.status == Status::kFail && r.category == GetParam().category;
    });
    EXPECT_TRUE(caught) << GetParam().fault << "\n" << dump(results);
}

INSTANTIATE_TEST_SUITE_P(Faults, FaultTest,
                         ::testing::Values(FaultCase{"snip-mismatch", Category::kSnip},
                                           FaultCase{"acdi-version", Category::kAcdi},
                                           FaultCase{"pip-missing-bit", Category::kPip},
                                           FaultCase{"cdi-unterminated", Category::kCdi},
                                           FaultCase{"cdi-padding", Category::kCdi},
                                           FaultCase{"cdi-invalid", Category::kCdi},
                                           FaultCase{"readonly-writable", Category::kMemory},
                                           FaultCase{"read-past-end", Category::kMemory},
                                           FaultCase{"space-info-short", Category::kMemory},
                                           FaultCase{"reply-form", Category::kMemory},
                                           FaultCase{"no-datagram-ack", Category::kDatagram},
                                           FaultCase{"slow-reply", Category::kMemory},
                                           FaultCase{"alias-conflict-ignored", Category::kFrame},
                                           FaultCase{"unsolicited-traffic", Category::kMessage}),
                         [](const auto& info) {
                             std::string n = info.param.fault;
                             for (char& c : n)
                                 if (c == '-') c = '_';
                             return n;
                         });

TEST(FaultTest, TemporaryRejectsAreRetriedAndPass) {
    Bench b({"reject-temporary=3"});
    CheckContext ctx;
    auto results = b.run(ctx);
    for (const auto& r : results) EXPECT_NE(r.status, Status::kFail) << dump(results);
    EXPECT_EQ(ctx.temporary_rejects, 3u);
    auto it = std::find_if(results.begin(), results.end(),
                           [](const auto& r) { return r.id == "datagram.temporary-rejects"; });
    ASSERT_NE(it, results.end());
    EXPECT_EQ(it->status, Status::kWarn);
}

TEST(Utf8Test, AcceptsValidRejectsInvalid) {
    const std::vector<std::uint8_t> good = {'a',  0xC3, 0xA9, 0xE2, 0x82,
                                            0xAC, 0xF0, 0x9F, 0x98, 0x80};
    EXPECT_TRUE(is_valid_utf8(good));
    EXPECT_FALSE(is_valid_utf8(std::vector<std::uint8_t>{0xC0, 0xAF}));        // overlong
    EXPECT_FALSE(is_valid_utf8(std::vector<std::uint8_t>{0xED, 0xA0, 0x80}));  // surrogate
    EXPECT_FALSE(is_valid_utf8(std::vector<std::uint8_t>{0xE2, 0x82}));        // truncated
    EXPECT_FALSE(is_valid_utf8(std::vector<std::uint8_t>{0xFF}));
}

}  // namespace
}  // namespace olcb::conform
