// MTI table, error codes, PIP flags and datagram constants: the wire constants headers.
#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "openlcb/datagram_defs.hpp"
#include "openlcb/mti.hpp"
#include "openlcb/pip.hpp"

namespace olcb {
namespace {

TEST(Mti, BitHelpers) {
    EXPECT_TRUE(is_addressed(Mti::kVerifyNodeIdAddressed));
    EXPECT_FALSE(is_addressed(Mti::kVerifyNodeIdGlobal));
    EXPECT_TRUE(is_addressed(Mti::kSnipRequest));
    EXPECT_TRUE(is_addressed(Mti::kDatagram));
    EXPECT_TRUE(has_event_id(Mti::kEventReport));
    EXPECT_TRUE(has_event_id(Mti::kProducerIdentifiedUnknown));
    EXPECT_TRUE(has_event_id(Mti::kIdentifyConsumer));
    EXPECT_FALSE(has_event_id(Mti::kVerifiedNodeId));
    EXPECT_TRUE(is_simple(Mti::kVerifiedNodeId));
    EXPECT_TRUE(is_simple(Mti::kVerifyNodeIdGlobal));
    EXPECT_TRUE(is_stream_or_datagram(Mti::kDatagram));
    EXPECT_TRUE(is_stream_or_datagram(Mti::kStreamDataSend));
    EXPECT_FALSE(is_stream_or_datagram(Mti::kDatagramReceivedOk));
    EXPECT_TRUE(is_datagram(Mti::kDatagram));
    EXPECT_TRUE(is_stream_data(Mti::kStreamDataSend));
    EXPECT_EQ(priority(Mti::kInitializationComplete), 0u);
    EXPECT_EQ(priority(Mti::kSnipRequest), 3u);
    EXPECT_EQ(priority(Mti::kVerifyNodeIdGlobal), 1u);
}

TEST(Mti, EveryNameKnownAndDistinct) {
    const std::vector<std::uint16_t> all = {
        0x0100, 0x0101, 0x0488, 0x0490, 0x0170, 0x0171, 0x0068, 0x00A8, 0x0828, 0x0668,
        0x08F4, 0x04A4, 0x04C4, 0x04C5, 0x04C6, 0x04C7, 0x0914, 0x0524, 0x0544, 0x0545,
        0x0546, 0x0547, 0x0968, 0x0970, 0x0594, 0x05B4, 0x0F14, 0x0DE8, 0x0A08, 0x1C48,
        0x0A28, 0x0A48, 0x0CC8, 0x0868, 0x1F88, 0x0888, 0x08A8, 0x05EB, 0x01E9};
    std::set<std::string_view> names;
    for (auto raw : all) {
        EXPECT_FALSE(mti_name(raw).empty()) << std::hex << raw;
        names.insert(mti_name(raw));
    }
    EXPECT_EQ(names.size(), all.size());
    EXPECT_EQ(mti_name(Mti::kVerifyNodeIdGlobal), "Verify Node ID Global");
    EXPECT_EQ(mti_name(std::uint16_t{0x04F9}), "");
}

TEST(Pip, FactSheetExampleBytes) {
    const ProtocolSet set{Protocol::kDatagram,      Protocol::kMemoryConfiguration,
                          Protocol::kEventExchange, Protocol::kAcdi,
                          Protocol::kSnip,          Protocol::kCdi};
    const auto bytes = set.encode();
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.end()),
              (std::vector<std::uint8_t>{0x54, 0x58, 0, 0, 0, 0}));
    EXPECT_EQ(ProtocolSet::decode(bytes), set);
}

TEST(Pip, EveryFlagOnItsByteAndBit) {
    struct Case {
        Protocol p;
        int byte;
        std::uint8_t mask;
    };
    const Case cases[] = {
        {Protocol::kSimpleProtocol, 0, 0x80},
        {Protocol::kDatagram, 0, 0x40},
        {Protocol::kStream, 0, 0x20},
        {Protocol::kMemoryConfiguration, 0, 0x10},
        {Protocol::kReservation, 0, 0x08},
        {Protocol::kEventExchange, 0, 0x04},
        {Protocol::kIdentification, 0, 0x02},
        {Protocol::kTeachingLearning, 0, 0x01},
        {Protocol::kRemoteButton, 1, 0x80},
        {Protocol::kAcdi, 1, 0x40},
        {Protocol::kDisplay, 1, 0x20},
        {Protocol::kSnip, 1, 0x10},
        {Protocol::kCdi, 1, 0x08},
        {Protocol::kTractionControl, 1, 0x04},
        {Protocol::kFdi, 1, 0x02},
        {Protocol::kFunctionConfiguration, 2, 0x40},
        {Protocol::kFirmwareUpgrade, 2, 0x20},
        {Protocol::kFirmwareUpgradeActive, 2, 0x10},
    };
    for (const auto& c : cases) {
        const auto bytes = ProtocolSet{c.p}.encode();
        for (int i = 0; i < 6; ++i) {
            EXPECT_EQ(bytes[i], i == c.byte ? c.mask : 0) << "byte " << i;
        }
    }
}

TEST(Pip, TruncatedInputReadsZeros) {
    const std::uint8_t two[] = {0x54, 0x58};
    const auto set = ProtocolSet::decode(two);
    EXPECT_TRUE(set.has(Protocol::kSnip));
    EXPECT_FALSE(set.has(Protocol::kFirmwareUpgrade));
    EXPECT_EQ(set.bits(), 0x5458'0000'0000u);
    EXPECT_EQ(ProtocolSet::decode({}).bits(), 0u);
    const std::uint8_t eight[] = {0, 0, 0, 0, 0, 1, 0xFF, 0xFF};
    EXPECT_EQ(ProtocolSet::decode(eight).bits(), 1u);  // bytes past 6 ignored
    ProtocolSet s;
    s.set(Protocol::kCdi).set(Protocol::kCdi, false);
    EXPECT_EQ(s.bits(), 0u);
}

TEST(DatagramDefs, OkFlags) {
    EXPECT_EQ(datagram::ok_flags(true), 0x80);
    EXPECT_EQ(datagram::ok_flags(true, 3), 0x83);
    EXPECT_EQ(datagram::ok_flags(false, 99), 0x0F);
    EXPECT_TRUE(datagram::is_reply_pending(0x80));
    EXPECT_FALSE(datagram::reply_timeout(0x80));
    EXPECT_EQ(datagram::reply_timeout(0x83), std::chrono::seconds(8));
    EXPECT_TRUE(datagram::is_two_byte_type(0xE5));
    EXPECT_TRUE(datagram::is_six_byte_type(0xF0));
    EXPECT_FALSE(datagram::is_six_byte_type(0x20));
    EXPECT_EQ(datagram::kMaxSize, 72u);
}

}  // namespace
}  // namespace olcb
