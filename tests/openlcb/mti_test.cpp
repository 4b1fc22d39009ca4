// The MTI table (openlcb/mti.hpp): the bits an MTI carries, priorities and names.
#include "openlcb/mti.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <string_view>
#include <vector>

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

}  // namespace
}  // namespace olcb
