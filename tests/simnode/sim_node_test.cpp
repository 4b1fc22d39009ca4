// SimNode: with faults on, each datagram is decoded once and each reply encoded once (the faults
// change the typed request and reply; see decide()); and the good node follows the rules
// OlcbChecker's cd40, mc10, fr40/fr50/fr60, me50 and the event checks test (ACDI version byte,
// writes crossing an end, the highest address, Write Under Mask, Update Complete, event
// identification after a write, duplicate node ID, frame format edge cases, alias collision),
// which the faults of tests/simnode/faults/ break.
#include "simnode/sim_node.hpp"

#include <gtest/gtest.h>

#include "memory/memory_config_codec.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode {
namespace {

class SimNodeDecodeTest : public test::SimNodeTest {
protected:
    // Runs one exchange and returns how many payloads were decoded and encoded meanwhile.
    memory::CodecCounts counted(const std::vector<std::uint8_t>& request, test::Answer& answer) {
        const memory::CodecCounts before = memory::codec_counts();
        answer = exchange(request);
        const memory::CodecCounts after = memory::codec_counts();
        return {after.decoded - before.decoded, after.encoded - before.encoded};
    }
};

TEST_F(SimNodeDecodeTest, EveryMemoryFaultOnOneDecodeAndOneEncodePerDatagram) {
    start_with({"read-past-end", "space-info-short", "reply-form", "field-reads-only",
                "highest-unreadable", "write-past-end-grows", "readonly-0x1041",
                "unknown-space-0x1041", "lock-rejected", "reset-rejected"});
    test::Answer a;
    memory::CodecCounts n = counted({0x20, 0x41, 0, 0, 0, 0, 8}, a);  // short-form read of 0xFD
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x50) << "reply-form answered in the byte-6 form";
    EXPECT_EQ(n.decoded, 1u);
    EXPECT_EQ(n.encoded, 1u);
    n = counted({0x20, 0x84, 0xFD}, a);  // Space Info, changed by two faults
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(n.decoded, 1u);
    EXPECT_EQ(n.encoded, 1u);
    n = counted({0x20, 0x41, 0xFF, 0xFF, 0xFF, 0x00, 4}, a);  // past the end: filled
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(n.decoded, 1u);
    EXPECT_EQ(n.encoded, 1u);
    n = counted({0x20, 0x88, 2, 1, 0x0D, 0, 0, 1}, a);  // Lock, rejected before the server
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(n.decoded, 1u);
    EXPECT_EQ(n.encoded, 0u);
}

TEST_F(SimNodeDecodeTest, MaskIgnoredDecodesTheWriteUnderMaskOnce) {
    start_with({"mask-ignored=1"});
    test::Answer a;
    const memory::CodecCounts n = counted({0x20, 0x09, 0, 0, 0, 0, 0x5A, 0x0F}, a);
    EXPECT_TRUE(a.ok);
    EXPECT_EQ(n.decoded, 1u);
}

}  // namespace
}  // namespace olcb::simnode

namespace olcb::simnode::test {
namespace {

// ConfigurationDescriptionInformationS §5.1.2 lists 251, its version byte included, as read and
// write, and MemoryConfigurationS §4.1 makes no space partly read-only: the byte is written.
TEST_F(SimNodeRulesTest, AcdiVersionByteIsWritableLikeTheRestOf251) {
    start(default_config());
    ASSERT_EQ(read(0xFB, 0, 4), (std::vector<std::uint8_t>{2, 'T', 'e', 's'}));
    write_ok(0xFB, 0, {2, 'R'});
    EXPECT_EQ(read(0xFB, 0, 4), (std::vector<std::uint8_t>{2, 'R', 'e', 's'}));
    // Write Under Mask including byte 0, with an empty mask for it.
    EXPECT_TRUE(exchange({0x20, 0x08, 0, 0, 0, 0, 0xFB, 0x00, 0x07, 0xFF, 'X'}).ok);
    EXPECT_EQ(read(0xFB, 0, 4), (std::vector<std::uint8_t>{2, 'X', 'e', 's'}));
}

// A CDI laying a variable over 251 byte 0 (a CDI bug of some real devices, which the cdi checks
// report) makes that byte the variable's: written as the CDI says.
TEST_F(SimNodeRulesTest, AcdiVersionByteWritableWhenTheCdiLaysAVariableOverIt) {
    NodeConfig c = default_config();
    const auto at = c.cdi.find("<segment space=\"251\" origin=\"1\">");
    ASSERT_NE(at, std::string::npos);
    c.cdi.replace(at, 32, "<segment space=\"251\" origin=\"0\">");
    start(std::move(c));
    write_ok(0xFB, 0, bytes_of("Zed"));
    EXPECT_EQ(read(0xFB, 0, 3), bytes_of("Zed"));
}

TEST_F(SimNodeRulesTest, AnyWriteOfSpace252Rejected1083) {
    start(default_config());
    const auto before = read(0xFC, 0, 8);
    for (const std::uint32_t at : {0u, 1u, 124u}) {
        const Answer a = exchange(write_cmd(0xFC, at, {4}));
        EXPECT_TRUE(a.rejected) << at;
        EXPECT_EQ(a.code, 0x1083) << at;
    }
    EXPECT_EQ(read(0xFC, 0, 8), before);
}

TEST_F(SimNodeRulesTest, WriteCrossingTheEndFails1082AndStoresNothing) {
    start(default_config());
    const auto tail = read(0xFD, kConfigSize - 4, 4);
    Answer a = exchange(write_cmd(0xFD, kConfigSize - 4, {9, 9, 9, 9, 9}));
    EXPECT_TRUE(a.ok);
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x19) << "Write Reply Fail, short form of 0xFD";
    EXPECT_EQ(fail_code(a), 0x1082);
    EXPECT_EQ(read(0xFD, kConfigSize - 4, 4), tail);
    a = exchange(write_cmd(0xFD, kConfigSize, {9}));
    EXPECT_EQ(fail_code(a), 0x1082);

    const auto user_tail = read(0xFB, kUserSize - 2, 2);
    const auto config_head = read(0xFD, 0, 4);
    a = exchange(write_cmd(0xFB, kUserSize - 2, {'a', 'b', 'c', 'd'}));
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x18) << "Write Reply Fail, byte-6 form";
    EXPECT_EQ(fail_code(a), 0x1082);
    EXPECT_EQ(read(0xFB, kUserSize - 2, 2), user_tail);
    EXPECT_EQ(read(0xFD, 0, 4), config_head) << "nothing spills into 253";
    EXPECT_EQ(fail_code(exchange(write_cmd(0xFB, kUserSize, {'a'}))), 0x1082);
}

TEST_F(SimNodeRulesTest, ReadAtHighestSucceedsAndPastItFails1082InEverySpace) {
    start(default_config());
    const std::vector<std::pair<std::uint8_t, std::uint32_t>> spaces = {
        {0xFF, static_cast<std::uint32_t>(default_cdi().size())},
        {0xFD, kConfigSize - 1},
        {0xFC, 124},
        {0xFB, kUserSize - 1}};
    for (const auto& [space, expected] : spaces) {
        SCOPED_TRACE(space);
        const std::uint32_t h = highest(space);
        EXPECT_EQ(h, expected);
        EXPECT_EQ(read(space, h, 1).size(), 1u);
        EXPECT_EQ(read(space, h, 64).size(), 1u) << "a read running past the end is cut short";
        for (const std::uint32_t past : {h + 1, h + 0x100}) {
            const Answer a = exchange(read_cmd(space, past, 1));
            ASSERT_TRUE(a.reply);
            EXPECT_EQ((*a.reply)[1] & 0xFC, 0x58) << "Read Reply Fail";
            EXPECT_EQ(fail_code(a), 0x1082);
        }
    }
}

TEST_F(SimNodeRulesTest, WriteUnderMaskAdvertisedAndServed) {
    start(default_config());
    const Answer options = exchange({0x20, 0x80});
    ASSERT_TRUE(options.reply);
    ASSERT_GE(options.reply->size(), 7u);
    EXPECT_EQ((*options.reply)[2] & 0x80, 0x80) << "0x8000 write under mask";
    EXPECT_EQ((*options.reply)[4], 0xE2) << "write-lengths byte";

    ASSERT_EQ(read(0xFD, kDelay, 4), (std::vector<std::uint8_t>{0, 0, 0, 0xFA}));  // 250
    // byte 3: mask FF value 12; byte 4: mask 0F value 35 (0x00 -> 0x05).
    const Answer a = exchange({0x20, 0x09, 0, 0, 0, kDelay, 0xFF, 0x12, 0x0F, 0x35});
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x11) << "Write Reply OK";
    EXPECT_EQ(read(0xFD, kDelay, 4), (std::vector<std::uint8_t>{0x12, 0x05, 0, 0xFA}));

    const auto tail = read(0xFD, kConfigSize - 1, 1);
    EXPECT_EQ(fail_code(exchange({0x20, 0x09, 0, 0, 0, kConfigSize - 1, 0xFF, 1, 0xFF, 1})),
              0x1082);
    EXPECT_EQ(read(0xFD, kConfigSize - 1, 1), tail);
    const Answer ro = exchange({0x20, 0x0B, 0, 0, 0, 0, 0xFF, 0x20});
    EXPECT_TRUE(ro.rejected);
    EXPECT_EQ(ro.code, 0x1083);
}

TEST_F(SimNodeRulesTest, IdentifyAnswersEveryEventIdOfTheCdi) {
    start(default_config());
    auto frames = identify_events_global();
    ASSERT_EQ(frames.size(), 8u);
    for (std::uint8_t i = 0; i < 8; ++i)
        EXPECT_EQ(frames[i], consumer_identified(default_event(i)));
    take();
    send_addressed(0x968);
    net_.run_for(10ms);
    EXPECT_EQ(take(), frames) << "Identify Events addressed";
    EXPECT_EQ(identify(default_event(3)),
              std::vector<std::string>{consumer_identified(default_event(3))});
    EXPECT_TRUE(identify(default_event(3), true).empty()) << "consumed only";
    EXPECT_TRUE(identify(default_event(9)).empty()) << "not ours";
}

TEST_F(SimNodeRulesTest, WrittenEventIdIsIdentifiedAndTheOldOneNoLonger) {
    start(default_config());
    take();
    write_ok(0xFD, kPort0On, kNewEvent);
    EXPECT_EQ(count_prefix(take(), consumer_identified(kNewEvent)), 1u) << "advertised at once";
    EXPECT_EQ(identify(kNewEvent), std::vector<std::string>{consumer_identified(kNewEvent)});
    EXPECT_TRUE(identify(default_event(0)).empty());
    auto frames = identify_events_global();
    EXPECT_EQ(count_prefix(frames, consumer_identified(kNewEvent)), 1u);
    EXPECT_EQ(count_prefix(frames, consumer_identified(default_event(0))), 0u);

    // Update Complete: plain Datagram Received OK, no reply; the memory is what counts.
    const Answer done = exchange({0x20, 0xA8});
    EXPECT_TRUE(done.ok);
    EXPECT_EQ(done.ok_flags & 0x80, 0) << "no Reply Pending";
    EXPECT_FALSE(done.reply);
    EXPECT_EQ(identify(kNewEvent).size(), 1u);
    reboot();
    EXPECT_EQ(identify(kNewEvent).size(), 1u) << "still after a restart";
}

TEST_F(SimNodeRulesTest, DuplicateNodeIdSendsOnePcerPerSecondAndKeepsWorking) {
    start(default_config());
    const std::string pcer = ":X195B4343N0101000000000201;";
    take();
    send_text(":X19170456N050101012200;");  // Verified Node ID with our ID from another alias
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{pcer});
    for (int i = 0; i < 20; ++i) send_text(":X10701457N050101012200;");  // AMD flood
    net_.run_for(500ms);
    EXPECT_TRUE(take().empty()) << "rate-limited";
    send_addressed(0x488);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"}) << "not silent";
    net_.run_for(500ms);
    send_text(":X10701457N050101012200;");
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{pcer}) << "again after 1 s";
    EXPECT_TRUE(node_->stack().initialized());
    EXPECT_EQ(alias(), 0x343);
    send_text(":X19170456N020304050607;");  // another node's ID: nothing
    net_.run_for(2s);
    EXPECT_TRUE(take().empty());
}

TEST_F(SimNodeRulesTest, FramesWithBit28ClearAreTakenAsIfItWereSet) {
    start(default_config());
    take();
    send_text(":X0070212CN;");  // AME, bit 28 clear
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X10701343N050101012200;"});
    send_text(":X0948812CN0343;");  // addressed Verify Node ID, bit 28 clear
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"});
}

TEST_F(SimNodeRulesTest, StandardFramesAreIgnored) {
    start(default_config());
    take();
    for (std::uint32_t id = 0; id < 0x800; ++id) {
        CanFrame f;
        f.id = id;
        f.extended = false;
        f.len = 2;
        f.data[0] = 0x03;
        f.data[1] = 0x43;
        port_.send(f);
    }
    net_.run_for(100ms);
    EXPECT_TRUE(take().empty());
    EXPECT_TRUE(node_->stack().initialized());
}

TEST_F(SimNodeRulesTest, BurstsOfFramesDoNotHideAnAddressedVerify) {
    start(default_config());
    take();
    // Identify Consumer for events of nobody.
    verify_in_burst(300, [&](std::size_t) { send_global(0x8F4, {9, 9, 9, 9, 9, 9, 9, 9}); });
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"});
    // Two-frame addressed messages (SNIP request framing) to another node.
    verify_in_burst(300, [&](std::size_t i) {
        send_text(i % 2 == 0 ? ":X19DE812CN1999;" : ":X19DE812CN2999;");
    });
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"});
    // Global Verify Node ID from other aliases: each answered, the addressed one too.
    verify_in_burst(300, [&](std::size_t i) {
        port_.send(can::make_frame(
            can::message_header(0x490, static_cast<std::uint16_t>(0x200 + i % 0x100))));
    });
    net_.run_for(10ms);
    EXPECT_EQ(count_prefix(take(), ":X19170343N050101012200"), 301u);
}

TEST_F(SimNodeRulesTest, AliasCollisionSendsAmrAndMovesToANewAlias) {
    start(default_config());
    take();
    send_text(":X10701343N020304050607;");  // another node's AMD with our alias
    net_.run_for(10ms);
    auto frames = take();
    ASSERT_FALSE(frames.empty());
    EXPECT_EQ(frames[0], ":X10703343N050101012200;") << "AMR";
    net_.run_for(300ms);
    const std::uint16_t now_alias = alias();
    EXPECT_NE(now_alias, 0x343);
    EXPECT_TRUE(node_->stack().initialized());
    frames = take();
    char amd[40];
    std::snprintf(amd, sizeof amd, ":X10701%03XN050101012200;", now_alias);
    EXPECT_EQ(count_prefix(frames, amd), 1u);
    send_addressed(0x488);  // to the new alias
    net_.run_for(10ms);
    char verified[40];
    std::snprintf(verified, sizeof verified, ":X19170%03XN050101012200;", now_alias);
    EXPECT_EQ(take(), std::vector<std::string>{verified});
    // A burst (made-up senders, foreign node ID) after the move: the new alias still answers.
    verify_in_burst(300, [&](std::size_t i) {
        port_.send(can::make_node_id_frame(
            can::message_header(0x490, static_cast<std::uint16_t>(0xA5A + i % 3)),
            NodeId{0x020112FE0002ull}));
    });
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{verified});
}

}  // namespace
}  // namespace olcb::simnode::test
