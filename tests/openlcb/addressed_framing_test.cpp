#include "openlcb/addressed_framing.hpp"

#include <gtest/gtest.h>

#include <numeric>

#include "openlcb/gc_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;

Message msg(Mti mti, std::uint16_t src, std::optional<std::uint16_t> dst,
            std::vector<std::uint8_t> payload) {
    return test::make_message(mti, src, dst, std::move(payload));
}

std::vector<std::uint8_t> counting(std::size_t n) {
    std::vector<std::uint8_t> v(n);
    std::iota(v.begin(), v.end(), std::uint8_t{1});
    return v;
}

Strings encode(const Message& m) {
    std::vector<CanFrame> frames;
    EXPECT_EQ(encode_message(m, frames), FramingError::kNone);
    return texts(frames);
}

FramingError encode_error(const Message& m) {
    std::vector<CanFrame> frames;
    const auto err = encode_message(m, frames);
    EXPECT_TRUE(frames.empty());
    return err;
}

TEST(Framing, GlobalMessageOneFrame) {
    EXPECT_EQ(encode(msg(Mti::kVerifyNodeIdGlobal, 0x12C, std::nullopt, {})),
              (Strings{":X1949012CN;"}));
    EXPECT_EQ(encode(msg(Mti::kVerifiedNodeId, 0x343, std::nullopt,
                         {0x05, 0x01, 0x01, 0x01, 0x22, 0x00})),
              (Strings{":X19170343N050101012200;"}));
    EXPECT_EQ(encode_error(msg(Mti::kEventReport, 0x343, std::nullopt, counting(9))),
              FramingError::kBadPayloadLength);
}

TEST(Framing, AddressedEmptyPayloadCarriesOnlyDestination) {
    EXPECT_EQ(encode(msg(Mti::kSnipRequest, 0x12C, 0x343, {})), (Strings{":X19DE812CN0343;"}));
}

TEST(Framing, AddressedSplitsSixBytesPerFrame) {
    EXPECT_EQ(encode(msg(Mti::kProtocolSupportReply, 0x343, 0x12C, counting(6))),
              (Strings{":X19668343N012C010203040506;"}));
    EXPECT_EQ(encode(msg(Mti::kProtocolSupportReply, 0x343, 0x12C, counting(7))),
              (Strings{":X19668343N112C010203040506;", ":X19668343N212C07;"}));
    EXPECT_EQ(encode(msg(Mti::kProtocolSupportReply, 0x343, 0xA2C, counting(13))),
              (Strings{":X19668343N1A2C010203040506;", ":X19668343N3A2C0708090A0B0C;",
                       ":X19668343N2A2C0D;"}));
}

TEST(Framing, DatagramFormats) {
    EXPECT_EQ(encode(msg(Mti::kDatagram, 0x12C, 0x343, {})), (Strings{":X1A34312CN;"}));
    EXPECT_EQ(encode(msg(Mti::kDatagram, 0x12C, 0x343, counting(8))),
              (Strings{":X1A34312CN0102030405060708;"}));
    EXPECT_EQ(encode(msg(Mti::kDatagram, 0x12C, 0x343, counting(9))),
              (Strings{":X1B34312CN0102030405060708;", ":X1D34312CN09;"}));
    const auto full = encode(msg(Mti::kDatagram, 0x12C, 0x343, counting(72)));
    ASSERT_EQ(full.size(), 9u);
    EXPECT_EQ(full.front().substr(0, 4), ":X1B");
    for (std::size_t i = 1; i < 8; ++i) EXPECT_EQ(full[i].substr(0, 4), ":X1C");
    EXPECT_EQ(full.back(), ":X1D34312CN4142434445464748;");
    EXPECT_EQ(encode_error(msg(Mti::kDatagram, 0x12C, 0x343, counting(73))),
              FramingError::kBadPayloadLength);
}

TEST(Framing, StreamDataFormatSeven) {
    EXPECT_EQ(encode(msg(Mti::kStreamDataSend, 0x343, 0x12C, {0x04, 0xAA})),
              (Strings{":X1F12C343N04AA;"}));
    EXPECT_EQ(encode_error(msg(Mti::kStreamDataSend, 0x343, 0x12C, counting(9))),
              FramingError::kBadPayloadLength);
}

TEST(Framing, MissingAliasesRejected) {
    EXPECT_EQ(encode_error(msg(Mti::kVerifyNodeIdGlobal, 0, std::nullopt, {})),
              FramingError::kMissingSourceAlias);
    EXPECT_EQ(encode_error(msg(Mti::kSnipRequest, 0x12C, std::nullopt, {})),
              FramingError::kMissingDestinationAlias);
    EXPECT_EQ(encode_error(msg(Mti::kDatagram, 0x12C, 0, {})),
              FramingError::kMissingDestinationAlias);
    EXPECT_EQ(encode_error(msg(Mti::kSnipRequest, 0x12C, 0x1000, {})),
              FramingError::kMissingDestinationAlias);
    EXPECT_FALSE(framing_error_text(FramingError::kBadPayloadLength).empty());
}

TEST(Framing, EventReportWithPayloadRoundTrip) {
    const auto payload = counting(20);
    const auto frames = encode(msg(Mti::kEventReportWithPayload, 0x343, std::nullopt, payload));
    EXPECT_EQ(frames, (Strings{":X19F16343N0102030405060708;", ":X19F15343N090A0B0C0D0E0F10;",
                               ":X19F14343N11121314;"}));
    MessageAssembler as;
    std::optional<Message> got;
    for (const auto& f : frames) got = as.on_frame(gc(f), t0);
    ASSERT_TRUE(got);
    EXPECT_EQ(got->mti, Mti::kEventReportWithPayload);
    EXPECT_EQ(got->payload, payload);
    EXPECT_FALSE(got->destination);
    EXPECT_EQ(encode_error(msg(Mti::kEventReportWithPayload, 0x343, std::nullopt, counting(8))),
              FramingError::kBadPayloadLength);
}

TEST(Assembler, GlobalAndOnlyFramesCompleteAtOnce) {
    MessageAssembler as;
    auto m = as.on_frame(gc(":X19170343N050101012200;"), t0);
    ASSERT_TRUE(m);
    EXPECT_EQ(m->mti, Mti::kVerifiedNodeId);
    EXPECT_EQ(m->source.alias, 0x343);
    EXPECT_FALSE(m->destination);
    EXPECT_EQ(m->payload.size(), 6u);

    m = as.on_frame(gc(":X19DE812CN0343;"), t0);
    ASSERT_TRUE(m);
    EXPECT_EQ(m->mti, Mti::kSnipRequest);
    ASSERT_TRUE(m->destination);
    EXPECT_EQ(m->destination->alias, 0x343);
    EXPECT_TRUE(m->payload.empty());
}

TEST(Assembler, IgnoresControlRemoteAndDatagramFramesByDefault) {
    MessageAssembler as;
    EXPECT_FALSE(as.on_frame(gc(":X10701343N050101012200;"), t0));
    EXPECT_FALSE(as.on_frame(gc(":X19490343R;"), t0));
    EXPECT_FALSE(as.on_frame(gc(":X1A34312CN2043;"), t0));
    EXPECT_EQ(as.errors(), 0u);
}

TEST(Assembler, InterleavedSourcesReassembleIndependently) {
    MessageAssembler as;
    EXPECT_FALSE(as.on_frame(gc(":X19A08343N112C0102030405FF;"), t0));
    EXPECT_FALSE(as.on_frame(gc(":X19A08344N112C0A0B0C0D0E0F;"), t0));
    EXPECT_EQ(as.in_progress(), 2u);
    auto a = as.on_frame(gc(":X19A08343N212C06;"), t0);
    auto b = as.on_frame(gc(":X19A08344N212C10;"), t0);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->payload, (std::vector<std::uint8_t>{1, 2, 3, 4, 5, 0xFF, 6}));
    EXPECT_EQ(b->payload, (std::vector<std::uint8_t>{10, 11, 12, 13, 14, 15, 16}));
    EXPECT_EQ(as.in_progress(), 0u);
}

TEST(Assembler, MiddleOrLastWithoutFirstDropped) {
    MessageAssembler as;
    EXPECT_FALSE(as.on_frame(gc(":X19A08343N312C0102030405FF;"), t0));
    EXPECT_FALSE(as.on_frame(gc(":X19A08343N212C06;"), t0));
    EXPECT_EQ(as.errors(), 2u);
    EXPECT_EQ(as.in_progress(), 0u);
}

TEST(Assembler, NewFirstRestartsMessage) {
    MessageAssembler as;
    as.on_frame(gc(":X19A08343N112C010101010101;"), t0);
    as.on_frame(gc(":X19A08343N112C020202020202;"), t0);
    auto m = as.on_frame(gc(":X19A08343N212C03;"), t0);
    ASSERT_TRUE(m);
    EXPECT_EQ(m->payload, (std::vector<std::uint8_t>{2, 2, 2, 2, 2, 2, 3}));
    EXPECT_EQ(as.errors(), 1u);
}

TEST(Assembler, TooShortAddressedFrameIsAnError) {
    MessageAssembler as;
    EXPECT_FALSE(as.on_frame(gc(":X19DE812CN03;"), t0));
    EXPECT_EQ(as.errors(), 1u);
}

TEST(Assembler, OverlongMessageDropped) {
    MessageAssembler as({.max_payload = 12});
    as.on_frame(gc(":X19A08343N112C010101010101;"), t0);
    as.on_frame(gc(":X19A08343N312C020202020202;"), t0);
    EXPECT_FALSE(as.on_frame(gc(":X19A08343N212C03;"), t0));
    EXPECT_EQ(as.in_progress(), 0u);
    EXPECT_EQ(as.errors(), 1u);
}

TEST(Assembler, InProgressBoundedOldestEvicted) {
    MessageAssembler as({.max_in_progress = 2});
    as.on_frame(gc(":X19A08001N112C010101010101;"), t0);
    as.on_frame(gc(":X19A08002N112C010101010101;"), t0 + 1ms);
    as.on_frame(gc(":X19A08003N112C010101010101;"), t0 + 2ms);
    EXPECT_EQ(as.in_progress(), 2u);
    EXPECT_FALSE(as.on_frame(gc(":X19A08001N212C01;"), t0 + 3ms)) << "oldest was evicted";
    EXPECT_TRUE(as.on_frame(gc(":X19A08003N212C01;"), t0 + 3ms));
}

TEST(Assembler, StalePartialDroppedByPoll) {
    MessageAssembler as({.timeout = 3s});
    as.on_frame(gc(":X19A08343N112C010101010101;"), t0);
    EXPECT_EQ(as.next_deadline(), t0 + 3s);
    as.poll(t0 + 2999ms);
    EXPECT_EQ(as.in_progress(), 1u);
    as.poll(t0 + 3s);
    EXPECT_EQ(as.in_progress(), 0u);
    EXPECT_FALSE(as.next_deadline());
}

TEST(Assembler, DatagramsWhenEnabledCappedAt72) {
    MessageAssembler as({.datagrams = true});
    std::optional<Message> m;
    for (const auto& f : encode(msg(Mti::kDatagram, 0x12C, 0x343, counting(72)))) {
        m = as.on_frame(gc(f), t0);
    }
    ASSERT_TRUE(m);
    EXPECT_EQ(m->mti, Mti::kDatagram);
    EXPECT_EQ(m->payload, counting(72));
    EXPECT_EQ(m->destination->alias, 0x343);
    // 9 full frames + 1 more byte: dropped.
    auto frames = encode(msg(Mti::kDatagram, 0x12C, 0x343, counting(72)));
    frames.back()[3] = 'C';
    for (const auto& f : frames) EXPECT_FALSE(as.on_frame(gc(f), t0));
    EXPECT_FALSE(as.on_frame(gc(":X1D34312CN01;"), t0));
    EXPECT_GE(as.errors(), 1u);
}

}  // namespace
}  // namespace olcb
