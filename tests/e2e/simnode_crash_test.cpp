// Crash safety of the simnode program: kill -9 during a stream of writes, 100 times; after every
// restart each acknowledged write is there and no 64-byte record is torn.
#include <gtest/gtest.h>

#include <array>
#include <random>

#include "e2e/e2e_util.hpp"

namespace olcb::e2e {
namespace {

using memory::Space;

constexpr NodeId kDefaultNode{0x05'01'01'01'22'00ull};
constexpr int kKills = 100;
constexpr std::size_t kBlocks = 2;  // two 64-byte records at 0 and 64 of space 253
constexpr std::uint8_t kRecordSize = 64;

// A record: the sequence number (big-endian) then bytes derived from it, so any mix of two
// records (a torn write) is detected.
std::vector<std::uint8_t> record(std::uint32_t seq) {
    std::vector<std::uint8_t> r(kRecordSize);
    r[0] = static_cast<std::uint8_t>(seq >> 24);
    r[1] = static_cast<std::uint8_t>(seq >> 16);
    r[2] = static_cast<std::uint8_t>(seq >> 8);
    r[3] = static_cast<std::uint8_t>(seq);
    for (std::size_t i = 4; i < r.size(); ++i) {
        r[i] = static_cast<std::uint8_t>(std::size_t{seq} * 7 + i * 13);
    }
    return r;
}

std::optional<std::uint32_t> record_seq(const std::vector<std::uint8_t>& data) {
    if (data.size() != kRecordSize) return std::nullopt;
    const std::uint32_t seq = std::uint32_t{data[0]} << 24 | std::uint32_t{data[1]} << 16 |
                              std::uint32_t{data[2]} << 8 | data[3];
    if (seq == 0 || data != record(seq)) return std::nullopt;
    return seq;
}

std::uint32_t block_address(std::size_t block) {
    return static_cast<std::uint32_t>(block * kRecordSize);
}

// What the rounds so far have sent and seen acknowledged, per block and in total.
struct WriteLog {
    std::array<std::uint32_t, kBlocks> acked{};  // newest acknowledged seq per block
    std::array<std::uint32_t, kBlocks> sent{};   // newest seq sent per block
    std::array<std::vector<std::uint8_t>, kBlocks> initial;
    std::uint32_t seq = 0;
    int total_acked = 0;
    int unacked_landed = 0;
};

// Every block holds the newest acknowledged record or a newer one that was sent, whole; round 0,
// before any write, learns what the blocks hold initially.
void check_blocks(ToolNode& tool, std::uint16_t node, int round, WriteLog& log) {
    for (std::size_t b = 0; b < kBlocks; ++b) {
        const auto data = tool.read(node, Space::kConfig, block_address(b), kRecordSize);
        ASSERT_TRUE(data) << "round " << round << " block " << b;
        if (round == 0) {
            log.initial[b] = *data;
            continue;
        }
        const auto got = record_seq(*data);
        if (!got) {
            ASSERT_EQ(log.acked[b], 0u)
                << "round " << round << " block " << b << ": torn or lost record";
            ASSERT_EQ(*data, log.initial[b]) << "round " << round << " block " << b;
            continue;
        }
        ASSERT_GE(*got, log.acked[b])
            << "round " << round << " block " << b << ": acknowledged write lost";
        ASSERT_LE(*got, log.sent[b]) << "round " << round << " block " << b;
        if (*got > log.acked[b]) ++log.unacked_landed;
        log.acked[b] = *got;  // it is on disk now: later rounds must keep at least this
    }
}

// Streams writes; kill -9 at kill_at while they run. Only a write cut by the kill may fail.
void write_until_killed(ToolNode& tool, Child& child, std::uint16_t node,
                        std::chrono::steady_clock::time_point kill_at, int round, WriteLog& log) {
    bool killed = false;
    tool.set_abort([&] {
        if (!killed && std::chrono::steady_clock::now() >= kill_at) {
            child.signal(SIGKILL);
            killed = true;
        }
        return killed && !tool.client().connected();
    });
    while (!killed || tool.client().connected()) {
        const std::uint32_t seq = ++log.seq;
        const std::size_t b = seq % kBlocks;
        log.sent[b] = seq;
        const bool ok =
            tool.write(node, Space::kConfig, block_address(b), record(seq), milliseconds(3000));
        if (ok) {
            log.acked[b] = seq;
            ++log.total_acked;
        } else {
            ASSERT_TRUE(killed) << "round " << round << ": write " << seq << " failed";
            break;
        }
    }
    tool.set_abort({});
}

TEST(SimnodeCrash, AcknowledgedWritesSurviveKill9) {
#ifndef SIMNODE_PATH
    GTEST_SKIP() << "simnode is not built";
#else
    TempDir images("simnode-crash");
    std::mt19937 rng(20240607);
    WriteLog log;

    for (int round = 0; round <= kKills; ++round) {
        auto child =
            Child::spawn(SIMNODE_PATH, {"--scenario", source_path("scenarios/default.ini").string(),
                                        "--listen", "127.0.0.1:0", "--image-dir", images.str()});
        ASSERT_TRUE(child);
        const auto port = child->wait_listening();
        ASSERT_TRUE(port) << "round " << round << ": " << child->output();
        ToolNode tool(*port);
        ASSERT_TRUE(tool.wait_ready()) << "round " << round;
        const auto node = tool.find(kDefaultNode);
        ASSERT_TRUE(node) << "round " << round;

        ASSERT_NO_FATAL_FAILURE(check_blocks(tool, *node, round, log));
        if (round == kKills) break;

        const auto kill_at =
            std::chrono::steady_clock::now() + std::chrono::microseconds(rng() % 120000 + 2000);
        ASSERT_NO_FATAL_FAILURE(write_until_killed(tool, *child, *node, kill_at, round, log));
        EXPECT_EQ(child->wait(), -SIGKILL);
    }
    std::cout << "[ crash    ] " << kKills << " kills, " << log.seq << " writes sent, "
              << log.total_acked << " acknowledged, " << log.unacked_landed
              << " unacknowledged found on disk\n";
    EXPECT_GT(log.total_acked, kKills);
#endif
}

}  // namespace
}  // namespace olcb::e2e
