// The write faults: writes dropped, not persisted, to read-only spaces, past the end, under a
// mask ignored, and a reboot at the Nth write, against a good node that keeps them.
#include <gtest/gtest.h>

#include "simnode/faults/fault_test_util.hpp"
#include "support/temp_files.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(FaultTest, WriteDropped) {
    start_with({"write-dropped"});
    write_ok(0xFD, 15, {3});
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{2}));
}

TEST_F(FaultTest, WriteNotPersisted) {
    TempDir dir;
    NodeConfig c = default_config();
    c.image_dir = dir.path();
    c.faults = faults_of({"write-not-persisted"});
    start(c);
    write_ok(0xFD, 15, {3});
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{3}));
    EXPECT_TRUE(exchange({0x20, 0xA9}).ok);
    net_.run_for(1s);
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{2})) << "lost on reboot";
}

TEST_F(FaultTest, ReadonlyWritable) {
    start_with({"readonly-writable"});
    write_ok(0xFF, 0, bytes_of("<!--"));
    EXPECT_EQ(read(0xFF, 0, 4), bytes_of("<!--"));
    write_ok(0xFC, 1, bytes_of("Evil"));
    EXPECT_EQ(read(0xFC, 1, 4), bytes_of("Evil"));
}

TEST_F(SimNodeRulesTest, WritePastEndSpills) {
    start_with({"write-past-end-spills"});
    const auto start_of_253 = read(0xFD, 0, 3);
    const Answer a = exchange(write_cmd(0xFB, kUserSize - 2, {'a', 'b', 'c', 'd', 'e'}));
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x10) << "Write Reply OK";
    EXPECT_EQ(read(0xFB, kUserSize - 2, 2), bytes_of("ab"));
    EXPECT_EQ(read(0xFD, kUserSize, 3), bytes_of("cde"))
        << "the rest lands in 253 past its first 128 bytes, as in OpenMRN's shared file";
    EXPECT_EQ(read(0xFD, 0, 3), start_of_253) << "253's start is untouched";
    write_ok(0xFD, kConfigSize - 2, {7, 7, 7, 7});
    EXPECT_EQ(read(0xFD, kConfigSize - 2, 4), (std::vector<std::uint8_t>{7, 7}));
    EXPECT_EQ(fail_code(exchange(write_cmd(0xFD, kConfigSize, {1}))), 0x1082)
        << "a write starting at the end still fails";
}

TEST_F(SimNodeRulesTest, WritePastEndGrowsKeepsTheBytesWhereNoReadReaches) {
    start_with({"write-past-end-grows"});
    const Answer a = exchange(write_cmd(0xFD, kConfigSize - 1, {9, 8, 7}));
    ASSERT_TRUE(a.ok || a.reply) << "accepted";
    EXPECT_EQ(read(0xFD, kConfigSize - 1, 1), std::vector<std::uint8_t>{9});
    EXPECT_EQ(node_->memory().past_end(0xFD), (std::vector<std::uint8_t>{8, 7}))
        << "kept past the end, as OpenMRN's config file grows";
    EXPECT_EQ(fail_code(exchange(read_cmd(0xFD, kConfigSize, 1))), 0x1082)
        << "and no read reaches it";
    EXPECT_EQ(highest(0xFD), kConfigSize - 1) << "Space Info unchanged";
}

TEST_F(SimNodeRulesTest, MaskIgnoredStoresTheDataWholeThenGoesSilentAndRestarts) {
    start_with({"mask-ignored=5000"});
    const auto before = read(0xFD, 0, 1);
    const std::uint8_t data = static_cast<std::uint8_t>(~before[0]);
    const Answer a = exchange({0x20, 0x09, 0, 0, 0, 0, 0x00, data});  // mask 0: change nothing
    EXPECT_TRUE(a.ok || a.reply) << "acknowledged";
    net_.run_for(1s);
    EXPECT_FALSE(node_->stack().initialized()) << "silent after the write";
    net_.run_for(5s);
    ASSERT_TRUE(node_->stack().initialized()) << "back after the silence";
    EXPECT_EQ(read(0xFD, 0, 1), std::vector<std::uint8_t>{data}) << "the mask was ignored";
}

TEST_F(RestartFaultTest, GoodNodeDoesNotRestartOnWrites) {
    start(default_config());
    for (std::uint8_t i = 0; i < 4; ++i) write_ok(0xFD, kDelay, {0, 0, 0, i});
    EXPECT_EQ(node_->stack().initializations(), 1u);
}

TEST_F(RestartFaultTest, RebootOnWriteRestartsAtTheNthWriteOnce) {
    start_with({"reboot-on-write=2"});
    write_ok(0xFD, kDelay, {0, 0, 0, 1});
    take();
    const Answer a = exchange(write_cmd(0xFD, kDelay, {0, 0, 0, 2}), 500ms);
    EXPECT_TRUE(a.ok);
    EXPECT_EQ(a.ok_flags & 0x80, 0x80) << "Reply Pending";
    EXPECT_FALSE(a.reply) << "the Write Reply is dropped";
    EXPECT_FALSE(a.rejected);
    const auto frames = take();
    ASSERT_FALSE(frames.empty());
    EXPECT_EQ(frames[0], ":X19A28343N012C80;");
    expect_startup(frames, 0x343, 1);
    EXPECT_EQ(node_->stack().initializations(), 2u);
    EXPECT_EQ(node_->counters().write_reboots, 1u);
    EXPECT_EQ(read(0xFD, kDelay, 4), (std::vector<std::uint8_t>{0, 0, 0, 2})) << "stored";
    write_ok(0xFD, kDelay, {0, 0, 0, 3});
    write_ok(0xFD, kDelay, {0, 0, 0, 4});  // the 2N-th
    EXPECT_EQ(node_->stack().initializations(), 2u) << "once per process";
}

TEST_F(RestartFaultTest, RebootOnWriteCountsOnlyStoredWrites) {
    start_with({"reboot-on-write"});
    EXPECT_TRUE(exchange(write_cmd(0xFF, 0, {'x'})).rejected);
    EXPECT_TRUE(exchange(read_cmd(0xFD, 0, 1)).reply);
    EXPECT_EQ(node_->stack().initializations(), 1u);
    const Answer a = exchange(write_cmd(0xFD, kDelay, {0, 0, 0, 9}), 500ms);
    EXPECT_TRUE(a.ok);
    EXPECT_FALSE(a.reply);
    EXPECT_EQ(node_->stack().initializations(), 2u);
}

}  // namespace
}  // namespace olcb::simnode::test
