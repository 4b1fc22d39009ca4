// Train Search event IDs and the matching algorithm of TrainSearchS §6.3, with the search a
// throttle sends as the Identify Producer frame CAN carries.
#include "openlcb/train_search.hpp"

#include <gtest/gtest.h>

#include "openlcb/addressed_framing.hpp"
#include "openlcb/gc_test_util.hpp"

namespace olcb::train_search {
namespace {

using namespace test;

Query q(std::string_view text, std::uint8_t flag_byte) {
    auto query = Query::of(text, flag_byte);
    EXPECT_TRUE(query) << text;
    return query.value_or(Query{});
}

TrainIdentity dcc(std::uint32_t address, bool long_address, std::string name = {}) {
    return {std::move(name), TrackProtocol::kDcc, address, long_address};
}

TEST(TrainSearchEvent, QueryNibblesAndFlagsInTheLowFourBytes) {
    const Query a = q("12", flags::kAllocate | flags::kExact | flags::kAddressOnly);
    EXPECT_EQ(a.event(), EventId{0x090099FF12FFFFE0ull});
    const auto back = Query::from_event(EventId{0x090099FFFFFF1260ull});
    ASSERT_TRUE(back);
    EXPECT_EQ(back->flags, 0x60);
    EXPECT_EQ(back->nibbles[4], 1);
    EXPECT_EQ(back->to_string(), "12 exact address-only");
    EXPECT_FALSE(Query::from_event(EventId{0x0101000000000303ull}));
    EXPECT_TRUE(in_range(EventId{0x090099FF00000000ull}));
    EXPECT_FALSE(in_range(EventId{0x090099FE00000000ull}));
    EXPECT_FALSE(Query::of("1234567", 0));
    EXPECT_FALSE(Query::of("12a", 0));
    EXPECT_EQ(q("4 12", 0).event(), EventId{0x090099FF4F12FF00ull});
}

TEST(TrainSearchEvent, SentAsIdentifyProducer) {
    std::vector<CanFrame> frames;
    const auto id = q("1732", flags::kExact | flags::kAddressOnly).event().to_bytes();
    ASSERT_EQ(encode_message(
                  make_message(Mti::kIdentifyProducer, 0x12C, std::nullopt, {id.begin(), id.end()}),
                  frames),
              FramingError::kNone);
    EXPECT_EQ(texts(frames), (Strings{":X1991412CN090099FF1732FF60;"}));
}

TEST(TrainSearchReserved, NibblesAToEAndReservedProtocolsMatchNothing) {
    auto reserved_nibble = Query::from_event(EventId{0x090099FFFFFFFCE0ull});
    ASSERT_TRUE(reserved_nibble);
    EXPECT_TRUE(reserved_nibble->has_reserved());
    for (std::uint8_t f : {0xF0, 0xF8, 0xE3}) EXPECT_TRUE(q("12", f).has_reserved()) << int(f);
    for (std::uint8_t f : {0xE0, 0xE8, 0xEC, 0x61, 0x62, 0x64, 0x67})
        EXPECT_FALSE(q("12", f).has_reserved()) << int(f);
    EXPECT_FALSE(matches(q("12", 0xE3), dcc(12, false)));
    EXPECT_TRUE(matches(q("12", 0xE0), dcc(12, false)));
}

TEST(TrainSearchAddress, ExactOrPrefixOfTheDecimalAddress) {
    const TrainIdentity t = dcc(1732, true);
    EXPECT_TRUE(matches(q("1732", flags::kExact | flags::kAddressOnly), t));
    EXPECT_FALSE(matches(q("173", flags::kExact | flags::kAddressOnly), t));
    EXPECT_TRUE(matches(q("173", flags::kAddressOnly), t));
    EXPECT_FALSE(matches(q("732", flags::kAddressOnly), t));
    // Two terms are never an address.
    EXPECT_FALSE(matches(q("17 32", flags::kAddressOnly), t));
}

TEST(TrainSearchAddress, DccShortAndLongBelow128) {
    const std::uint8_t exact = flags::kExact | flags::kAddressOnly;
    const std::uint8_t want_long = protocol::kDcc | protocol::kDccLongAddress;
    EXPECT_TRUE(matches(q("12", exact | want_long), dcc(12, true)));
    EXPECT_FALSE(matches(q("12", exact | want_long), dcc(12, false)));
    EXPECT_TRUE(matches(q("12", exact | protocol::kDcc), dcc(12, false)));
    // A search (no allocate) for a short-form 12 also finds the long address 12; an allocate
    // does not.
    EXPECT_TRUE(matches(q("12", exact | protocol::kDcc), dcc(12, true)));
    EXPECT_FALSE(matches(q("12", exact | flags::kAllocate | protocol::kDcc), dcc(12, true)));
    // At 128 and above the form does not matter.
    EXPECT_TRUE(matches(q("1732", exact | flags::kAllocate), dcc(1732, true)));
}

TEST(TrainSearchProtocol, TheFlagBytesProtocolMustAgree) {
    const std::uint8_t exact = flags::kExact | flags::kAddressOnly;
    const TrainIdentity native{"", TrackProtocol::kNative, 3, false};
    EXPECT_TRUE(matches(q("3", exact | protocol::kNative), native));
    EXPECT_TRUE(matches(q("3", exact), native));
    EXPECT_FALSE(matches(q("3", exact | protocol::kDcc), native));
    EXPECT_FALSE(matches(q("3", exact | protocol::kMarklinMotorola | 1), native));
    EXPECT_EQ(requested_protocol(protocol::kMarklinMotorola | 2), TrackProtocol::kMarklinMotorola);
    EXPECT_EQ(requested_protocol(protocol::kMfx), TrackProtocol::kMfx);
    EXPECT_EQ(requested_protocol(0), std::nullopt);
    EXPECT_TRUE(requests_long_address(protocol::kDcc | protocol::kDccLongAddress | 3));
    EXPECT_FALSE(requests_long_address(protocol::kMarklinMotorola | protocol::kDccLongAddress));
}

TEST(TrainSearchName, DigitGroupsOfTheName) {
    const TrainIdentity t = dcc(5, false, "C&NW 415 Big-12");
    EXPECT_TRUE(matches(q("415", 0), t));
    EXPECT_TRUE(matches(q("41", 0), t));
    EXPECT_FALSE(matches(q("41", flags::kExact), t));
    EXPECT_TRUE(matches(q("415", flags::kExact), t));
    EXPECT_FALSE(matches(q("15", 0), t));  // must start a digit group
    // Non-digits are skipped: 415 then 12 read as one run.
    EXPECT_TRUE(matches(q("41512", 0), t));
    // Several terms: each must match.
    EXPECT_TRUE(matches(q("12 415", 0), t));
    EXPECT_FALSE(matches(q("12 99", 0), t));
    // Address only: the name is not looked at.
    EXPECT_FALSE(matches(q("415", flags::kAddressOnly), t));
    EXPECT_FALSE(matches(q("", 0), t));
}

}  // namespace
}  // namespace olcb::train_search
