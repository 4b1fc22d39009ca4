// The Memory Configuration Protocol of a SimNode end to end: CDI download, space information,
// reads and writes in both forms, masks, refusals, lock, reboot, factory reset, SNIP updates,
// defaults from the CDI and malformed requests.
#include <gtest/gtest.h>

#include <cstring>
#include <span>

#include "cdi/float_codec.hpp"
#include "memory/snip.hpp"
#include "sim_node_test_util.hpp"

namespace olcb::simnode::test {
namespace {

class MemoryConfigTest : public SimNodeTest {
protected:
    void SetUp() override { start(default_config()); }

    std::vector<std::uint8_t> read_all(std::uint8_t space, std::uint32_t size) {
        std::vector<std::uint8_t> all;
        for (std::uint32_t a = 0; a < size; a += 64) {
            auto part =
                read(space, a, static_cast<std::uint8_t>(std::min<std::uint32_t>(64, size - a)));
            all.insert(all.end(), part.begin(), part.end());
        }
        return all;
    }
};

// Settings segment of scenarios/default.xml (space 253, origin 0).
constexpr std::uint32_t kEnabled = 0, kTrim = 1, kDelay = 3, kCounter = 7, kMode = 15, kGain = 16,
                        kRatio = 18, kScale = 22, kLabel = 30, kPort0 = 46, kPortStride = 33,
                        kAction = 178, kConfigSize = 179;

TEST_F(MemoryConfigTest, WholeCdiIn64ByteReads) {
    const std::string& cdi = default_cdi();
    std::vector<std::uint8_t> got;
    std::size_t last = 64;
    std::uint32_t address = 0;
    while (last == 64) {
        auto part = read(0xFF, address, 64);
        ASSERT_FALSE(part.empty()) << "read failed at " << address;
        last = part.size();
        got.insert(got.end(), part.begin(), part.end());
        address += 64;
    }
    ASSERT_EQ(got.size(), cdi.size() + 1) << "CDI plus exactly one NUL";
    EXPECT_EQ(got.back(), 0);
    EXPECT_EQ(std::string(got.begin(), got.end() - 1), cdi);
    EXPECT_LT(last, 64u) << "last read is cut short at the NUL";

    // A read starting at the end: Read Reply Fail 0x1082 after a Reply Pending OK.
    const auto end = static_cast<std::uint32_t>(cdi.size() + 1);
    const Answer a = exchange(read_cmd(0xFF, end, 64));
    ASSERT_TRUE(a.ok);
    EXPECT_EQ(a.ok_flags & 0x80, 0x80);
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x5B, addr(end, 0), addr(end, 1),
                                                   addr(end, 2), addr(end, 3), 0x10, 0x82}));
}

TEST_F(MemoryConfigTest, ReadIsAcknowledgedWithReplyPendingBeforeTheReply) {
    take();
    const Answer a = exchange(read_cmd(0xFF, 0, 64));
    ASSERT_TRUE(a.ok);
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(a.ok_flags, 0x80);
    EXPECT_LT(a.ok_index, a.reply_index);
    EXPECT_EQ(a.reply->size(), 70u);
    EXPECT_LE(a.reply_at - a.ok_at, std::chrono::milliseconds(750));
}

TEST_F(MemoryConfigTest, SpaceInformation) {
    const auto info = [&](std::uint8_t space) { return exchange({0x20, 0x84, space}).reply; };
    const auto cdi_end = static_cast<std::uint32_t>(default_cdi().size());
    EXPECT_EQ(info(0xFF),
              (std::vector<std::uint8_t>{0x20, 0x87, 0xFF, addr(cdi_end, 0), addr(cdi_end, 1),
                                         addr(cdi_end, 2), addr(cdi_end, 3), 0x01}));
    EXPECT_EQ(info(0xFD),
              (std::vector<std::uint8_t>{0x20, 0x87, 0xFD, 0, 0, 0, kConfigSize - 1, 0x00}));
    EXPECT_EQ(info(0xFC), (std::vector<std::uint8_t>{0x20, 0x87, 0xFC, 0, 0, 0, 124, 0x01}));
    EXPECT_EQ(info(0xFB), (std::vector<std::uint8_t>{0x20, 0x87, 0xFB, 0, 0, 0, 127, 0x00}));
    EXPECT_EQ(info(0x10), (std::vector<std::uint8_t>{0x20, 0x86, 0x10}));
}

TEST_F(MemoryConfigTest, ConfigurationOptions) {
    const Answer a = exchange({0x20, 0x80});
    ASSERT_TRUE(a.reply);
    // 0x1000 = stream reads (on by default, as OpenMRN sends it).
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x82, 0xFE, 0x00, 0xE2, 0xFF, 0xFB}));
}

TEST_F(MemoryConfigTest, WriteAndReadInShortAndByte6Forms) {
    // Short form write 20 01 -> Write Reply 20 11; byte-6 read 20 40 .. FD -> 20 50 .. FD.
    Answer a = exchange({0x20, 0x01, 0, 0, 0, kDelay, 0x00, 0x00, 0x01, 0x2C});
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x11, 0, 0, 0, kDelay}));
    a = exchange({0x20, 0x40, 0, 0, 0, kDelay, 0xFD, 4});
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply,
              (std::vector<std::uint8_t>{0x20, 0x50, 0, 0, 0, kDelay, 0xFD, 0, 0, 1, 0x2C}));
    // Byte-6 write 20 00 .. FD -> 20 10 .. FD; short read 20 41 -> 20 51.
    a = exchange({0x20, 0x00, 0, 0, 0, kMode, 0xFD, 3});
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x10, 0, 0, 0, kMode, 0xFD}));
    a = exchange({0x20, 0x41, 0, 0, 0, kMode, 1});
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x51, 0, 0, 0, kMode, 3}));
}

TEST_F(MemoryConfigTest, WriteUnderMask) {
    write_ok(0xFD, kCounter, {0xF0, 0x0F});
    // mask 0x3C, data 0xFF on the first byte; mask 0xFF, data 0x00 on the second.
    const Answer a = exchange({0x20, 0x09, 0, 0, 0, kCounter, 0x3C, 0xFF, 0xFF, 0x00});
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x11);
    EXPECT_EQ(read(0xFD, kCounter, 2), (std::vector<std::uint8_t>{0xFC, 0x00}));
}

TEST_F(MemoryConfigTest, ReadOnlyAndUnknownSpacesAreRejected) {
    Answer a = exchange(write_cmd(0xFF, 0, {'x'}));
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1083);
    a = exchange(write_cmd(0xFC, 1, {'x'}));
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1083);
    a = exchange(read_cmd(0x10, 0, 8));
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1081);
    EXPECT_FALSE(a.reply);
    // Writing past the end of a space: Write Reply Fail 0x1082, nothing written.
    a = exchange(write_cmd(0xFD, kConfigSize - 1, {1, 2}));
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x19);
    EXPECT_EQ((*a.reply)[6], 0x10);
    EXPECT_EQ((*a.reply)[7], 0x82);
}

TEST_F(MemoryConfigTest, LockIsTestAndSet) {
    const std::vector<std::uint8_t> me{0x02, 0x01, 0x0D, 0x00, 0x00, 0x01};
    std::vector<std::uint8_t> cmd{0x20, 0x88};
    cmd.insert(cmd.end(), me.begin(), me.end());
    Answer a = exchange(cmd);
    ASSERT_TRUE(a.reply);
    std::vector<std::uint8_t> expect{0x20, 0x8A};
    expect.insert(expect.end(), me.begin(), me.end());
    EXPECT_EQ(*a.reply, expect);
    a = exchange({0x20, 0x88, 9, 9, 9, 9, 9, 9});  // someone else: still held by us
    EXPECT_EQ(*a.reply, expect);
    a = exchange({0x20, 0x88, 0, 0, 0, 0, 0, 0});
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x8A, 0, 0, 0, 0, 0, 0}));
}

TEST_F(MemoryConfigTest, UpdateCompleteIsPlainOk) {
    const Answer a = exchange({0x20, 0xA8});
    EXPECT_TRUE(a.ok);
    EXPECT_EQ(a.ok_flags, 0);
    EXPECT_FALSE(a.reply);
}

TEST_F(MemoryConfigTest, UniqueIdsNeverRepeatDefaultEvents) {
    const Answer a = exchange({0x20, 0x8C, 2});
    ASSERT_TRUE(a.reply);
    // 8 default event IDs use suffixes 0..7.
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x8D, 5, 1, 1, 1, 0x22, 0, 0, 8, 5, 1, 1,
                                                   1, 0x22, 0, 0, 9}));
}

TEST_F(MemoryConfigTest, RebootRunsStartUpAgain) {
    take();
    const Answer a = exchange({0x20, 0xA9});
    EXPECT_TRUE(a.ok);
    net_.run_for(1s);
    const auto frames = take();
    EXPECT_EQ(count_prefix(frames, ":X17050343N"), 1u);
    EXPECT_EQ(count_prefix(frames, ":X19100343N050101012200"), 1u);
    EXPECT_EQ(count_prefix(frames, ":X194C7343N"), 8u);
    EXPECT_EQ(node_->reboot_count(), 1u);
    EXPECT_TRUE(node_->stack().initialized());
    EXPECT_EQ(read(0xFD, kMode, 1), (std::vector<std::uint8_t>{2}));
}

TEST_F(MemoryConfigTest, FactoryResetChecksNodeIdAndRestoresDefaults) {
    write_ok(0xFD, kMode, {3});
    write_ok(0xFB, 1, bytes_of("Renamed"));
    Answer a = exchange({0x20, 0xAA, 5, 1, 1, 1, 0x22, 0x01});
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1080);
    EXPECT_EQ(read(0xFD, kMode, 1), (std::vector<std::uint8_t>{3}));
    a = exchange({0x20, 0xAA, 5, 1, 1, 1, 0x22, 0x00});
    EXPECT_TRUE(a.ok);
    net_.run_for(1s);
    EXPECT_TRUE(node_->stack().initialized());
    EXPECT_EQ(node_->counters().factory_resets, 1u);
    EXPECT_EQ(read(0xFD, kMode, 1), (std::vector<std::uint8_t>{2}));
    EXPECT_EQ(memory::decode_snip(request_snip()).user_name, "Test node");
}

TEST_F(MemoryConfigTest, WriteToUserSpaceChangesSnipAndReinitializes) {
    take();
    write_ok(0xFB, 1, {'N', 'e', 'w', 0});
    net_.run_for(10ms);
    const auto frames = take();
    EXPECT_EQ(count_prefix(frames, ":X19100343N050101012200"), 1u);
    EXPECT_EQ(count_prefix(frames, ":X17050343N"), 0u) << "same alias, no new allocation";
    EXPECT_EQ(memory::decode_snip(request_snip()).user_name, "New");
    EXPECT_EQ(node_->snip().user_name, "New");
}

TEST_F(MemoryConfigTest, RewritingAnEventIdAdvertisesIt) {
    take();
    write_ok(0xFD, kPort0 + 16, {1, 2, 3, 4, 5, 6, 7, 8});
    net_.run_for(10ms);
    EXPECT_EQ(count_prefix(take(), ":X194C7343N0102030405060708"), 1u);
    write_ok(0xFD, kMode, {1});  // not an event: nothing advertised
    net_.run_for(10ms);
    EXPECT_EQ(count_prefix(take(), ":X194C7"), 0u);
}

TEST_F(MemoryConfigTest, DefaultsComeFromTheCdi) {
    const auto mem = read_all(0xFD, kConfigSize);
    ASSERT_EQ(mem.size(), kConfigSize);
    EXPECT_EQ(mem[kEnabled], 1);
    EXPECT_EQ(mem[kTrim], 0xFF);  // -5, two's complement big-endian
    EXPECT_EQ(mem[kTrim + 1], 0xFB);
    EXPECT_EQ(std::vector<std::uint8_t>(mem.begin() + kDelay, mem.begin() + kDelay + 4),
              (std::vector<std::uint8_t>{0, 0, 0, 250}));
    EXPECT_EQ(std::vector<std::uint8_t>(mem.begin() + kCounter, mem.begin() + kCounter + 8),
              std::vector<std::uint8_t>(8, 0));
    EXPECT_EQ(mem[kMode], 2);
    EXPECT_EQ(mem[kGain], 0x3E);  // 1.5 as a half
    EXPECT_EQ(mem[kGain + 1], 0x00);
    EXPECT_EQ(std::vector<std::uint8_t>(mem.begin() + kRatio, mem.begin() + kRatio + 4),
              (std::vector<std::uint8_t>{0x3E, 0x80, 0, 0}));
    EXPECT_EQ(std::vector<std::uint8_t>(mem.begin() + kScale, mem.begin() + kScale + 8),
              (std::vector<std::uint8_t>{0x3F, 0xF0, 0, 0, 0, 0, 0, 0}));
    EXPECT_EQ(mem[kLabel], 0);
    for (std::uint32_t port = 0; port < 4; ++port) {
        const std::uint32_t base = kPort0 + port * kPortStride;
        for (std::uint32_t k = 0; k < 2; ++k) {
            const std::uint8_t suffix = static_cast<std::uint8_t>(port * 2 + k);
            const auto event = std::span(mem).subspan(base + 16 + 8 * k, 8);
            EXPECT_EQ(std::vector<std::uint8_t>(event.begin(), event.end()),
                      (std::vector<std::uint8_t>{5, 1, 1, 1, 0x22, 0, 0, suffix}));
        }
        EXPECT_EQ(mem[base + 32], 0);
    }
    EXPECT_EQ(mem[kAction], 0);
}

TEST_F(MemoryConfigTest, MalformedDatagramsGetTheRightRejectCode) {
    const auto code = [&](const std::vector<std::uint8_t>& p) {
        const Answer a = exchange(p);
        EXPECT_TRUE(a.rejected) << "payload size " << p.size();
        return a.code;
    };
    EXPECT_EQ(code({0x20, 0x41, 0, 0}), 0x1080);              // truncated address
    EXPECT_EQ(code({0x20, 0x41, 0, 0, 0, 0, 0}), 0x1080);     // read count 0
    EXPECT_EQ(code({0x20, 0x41, 0, 0, 0, 0, 65}), 0x1080);    // read count > 64
    EXPECT_EQ(code({0x20, 0x40, 0, 0, 0, 0}), 0x1080);        // byte-6 form without space
    EXPECT_EQ(code({0x20, 0x01, 0, 0, 0, 0}), 0x1080);        // write without data
    EXPECT_EQ(code({0x20, 0x09, 0, 0, 0, 0, 0xFF}), 0x1080);  // odd mask/data bytes
    EXPECT_EQ(code({0x20, 0xFF}), 0x1041);                    // unknown command
    EXPECT_EQ(code({0x20, 0x21, 0, 0, 0, 0, 1}), 0x1041);     // stream write
    EXPECT_EQ(code({0x30, 0x01}), 0x1042);                    // other datagram type
    EXPECT_EQ(code({0x20}), 0x1080);                          // command missing
    // Still serving afterwards.
    EXPECT_EQ(read(0xFD, kMode, 1), (std::vector<std::uint8_t>{2}));
    // 72 bytes of garbage: rejected, no crash.
    std::vector<std::uint8_t> junk(72, 0xA5);
    junk[0] = 0x20;
    EXPECT_TRUE(exchange(junk).rejected);
}

}  // namespace
}  // namespace olcb::simnode::test
