// Protocol Identification flags (openlcb/pip.hpp): each protocol on its byte and bit.
#include "openlcb/pip.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <iterator>
#include <set>
#include <string_view>
#include <vector>

namespace olcb {
namespace {

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

TEST(Pip, EveryProtocolHasItsOwnName) {
    const Protocol all[] = {
        Protocol::kSimpleProtocol,
        Protocol::kDatagram,
        Protocol::kStream,
        Protocol::kMemoryConfiguration,
        Protocol::kReservation,
        Protocol::kEventExchange,
        Protocol::kIdentification,
        Protocol::kTeachingLearning,
        Protocol::kRemoteButton,
        Protocol::kAcdi,
        Protocol::kDisplay,
        Protocol::kSnip,
        Protocol::kCdi,
        Protocol::kTractionControl,
        Protocol::kFdi,
        Protocol::kFunctionConfiguration,
        Protocol::kFirmwareUpgrade,
        Protocol::kFirmwareUpgradeActive,
    };
    std::set<std::string_view> names;
    for (Protocol p : all) {
        EXPECT_NE(protocol_name(p), "unknown protocol");
        names.insert(protocol_name(p));
    }
    EXPECT_EQ(names.size(), std::size(all));
    EXPECT_EQ(protocol_name(Protocol::kTractionControl), "Traction Control");
}

}  // namespace
}  // namespace olcb
