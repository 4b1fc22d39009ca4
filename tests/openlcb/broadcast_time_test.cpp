// Broadcast Time wire facts (openlcb/broadcast_time.cpp): the suffix forms of BroadcastTimeS §4
// both ways, the reserved codes, rates, ranges, and PCER frames as GridConnect text.
#include "openlcb/broadcast_time.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "openlcb/addressed_framing.hpp"
#include "openlcb/event_range.hpp"
#include "openlcb/gridconnect.hpp"

namespace olcb::broadcast_time {
namespace {

// One PCER for event id from alias 0x343 as GridConnect text.
std::string pcer_text(EventId id) {
    Message m;
    m.mti = Mti::kEventReport;
    m.source = NodeHandle{NodeId{}, 0x343};
    const auto bytes = id.to_bytes();
    m.payload.assign(bytes.begin(), bytes.end());
    std::vector<CanFrame> frames;
    EXPECT_EQ(encode_message(m, frames), FramingError::kNone);
    return frames.empty() ? "" : gridconnect::format(frames.front());
}

TEST(BroadcastTime, WellKnownClocksAndTheirEventFrames) {
    EXPECT_EQ(kDefaultFastClock.to_string(), "01.01.00.00.01.00");
    EXPECT_EQ(kAlternateClock2.to_string(), "01.01.00.00.01.03");
    // Report Time 01:23 of the Default Fast Clock.
    const auto id = event_id(kDefaultFastClock, ClockEvent::report_time(1, 23));
    ASSERT_TRUE(id);
    EXPECT_EQ(id->to_string(), "01.01.00.00.01.00.01.17");
    EXPECT_EQ(pcer_text(*id), ":X195B4343N0101000001000117;");
    EXPECT_EQ(pcer_text(event_id(kDefaultRealTimeClock, kQuerySuffix)),
              ":X195B4343N010100000101F000;");
    EXPECT_EQ(clock_of(*id), kDefaultFastClock);
    EXPECT_EQ(suffix_of(*id), 0x0117);
    EXPECT_EQ(clock_name(kAlternateClock1), "Alternate Clock 1");
    EXPECT_EQ(clock_name(NodeId{0x050101012200ull}), "clock 05.01.01.01.22.00");
}

TEST(BroadcastTime, EveryFormEncodesAsTheStandardLaysItOut) {
    EXPECT_EQ(encode(ClockEvent::report_time(23, 59)), 0x173B);
    EXPECT_EQ(encode(ClockEvent::report_date(7, 22)), 0x2716);
    EXPECT_EQ(encode(ClockEvent::report_date(12, 31)), 0x2C1F);
    EXPECT_EQ(encode(ClockEvent::report_year(2023)), 0x37E7);
    EXPECT_EQ(encode(ClockEvent::report_year(4095)), 0x3FFF);
    EXPECT_EQ(encode(ClockEvent::report_rate(16)), 0x4010);     // 4.00
    EXPECT_EQ(encode(ClockEvent::report_rate(-2048)), 0x4800);  // -512.00 (TN §2.4.4)
    EXPECT_EQ(encode(ClockEvent::report_rate(-1)), 0x4FFF);     // -0.25
    EXPECT_EQ(encode(ClockEvent::report_time(5, 30).as_set()), 0x851E);
    EXPECT_EQ(encode(ClockEvent::report_date(7, 22).as_set()), 0xA716);
    EXPECT_EQ(encode(ClockEvent::report_year(2023).as_set()), 0xB7E7);
    EXPECT_EQ(encode(ClockEvent::report_rate(40).as_set()), 0xC028);
    EXPECT_EQ(encode(ClockEvent::of(Kind::kQuery)), kQuerySuffix);
    EXPECT_EQ(encode(ClockEvent::of(Kind::kStop)), 0xF001);
    EXPECT_EQ(encode(ClockEvent::of(Kind::kStart)), 0xF002);
    EXPECT_EQ(encode(ClockEvent::of(Kind::kDateRollover)), 0xF003);
    // Fields out of range have no code.
    EXPECT_FALSE(encode(ClockEvent::report_time(24, 0)));
    EXPECT_FALSE(encode(ClockEvent::report_time(0, 60)));
    EXPECT_FALSE(encode(ClockEvent::report_date(13, 1)));
    EXPECT_FALSE(encode(ClockEvent::report_date(1, 0)));
    EXPECT_FALSE(encode(ClockEvent::report_year(4096)));
    EXPECT_FALSE(encode(ClockEvent::report_rate(2048)));
    EXPECT_FALSE(encode(ClockEvent{}));
}

TEST(BroadcastTime, EveryDefinedSuffixDecodesBackAndTheRestIsReserved) {
    int defined = 0;
    for (std::uint32_t s = 0; s <= 0xFFFF; ++s) {
        const auto suffix = static_cast<std::uint16_t>(s);
        const ClockEvent e = decode(suffix);
        if (e.kind == Kind::kReserved) {
            EXPECT_EQ(e.reserved_code, suffix);
            continue;
        }
        ++defined;
        EXPECT_EQ(encode(e), suffix) << describe(e);
    }
    // 24*60 times and 12*31 dates (each twice), 4096 years and rates (twice), 4 specials.
    EXPECT_EQ(defined, 2 * (24 * 60 + 12 * 31 + 4096 + 4096) + 4);
    EXPECT_EQ(decode(0x1800).kind, Kind::kReserved);  // hour 24
    EXPECT_EQ(decode(0x003C).kind, Kind::kReserved);  // minute 60
    EXPECT_EQ(decode(0x2001).kind, Kind::kReserved);  // month 0
    EXPECT_EQ(decode(0x2D01).kind, Kind::kReserved);  // month 13
    EXPECT_EQ(decode(0x5000).kind, Kind::kReserved);
    EXPECT_EQ(decode(0xE123).kind, Kind::kReserved);
    EXPECT_EQ(decode(0xF004).kind, Kind::kReserved);
    EXPECT_EQ(decode(0x4800).rate_quarters, -2048);
    EXPECT_EQ(decode(0xC7FF).rate_quarters, 2047);
    EXPECT_EQ(decode(0x97 << 8 | 0x3B), ClockEvent::report_time(23, 59).as_set());
}

TEST(BroadcastTime, DescribesEventsInWords) {
    EXPECT_EQ(describe(decode(0x0117)), "Report Time 01:23");
    EXPECT_EQ(describe(decode(0xA716)), "Set Date 07-22");
    EXPECT_EQ(describe(decode(0x37E7)), "Report Year 2023");
    EXPECT_EQ(describe(decode(0x4FFF)), "Report Rate -0.25");
    EXPECT_EQ(describe(decode(0xC010)), "Set Rate 4.00");
    EXPECT_EQ(describe(decode(0xF003)), "Date Rollover");
    EXPECT_EQ(describe(decode(0x5000)), "reserved 0x5000");
}

TEST(BroadcastTime, RatesAsText) {
    EXPECT_EQ(rate_text(16), "4.00");
    EXPECT_EQ(rate_text(-1), "-0.25");
    EXPECT_EQ(rate_text(2047), "511.75");
    EXPECT_EQ(rate_text(-2048), "-512.00");
    EXPECT_EQ(parse_rate("4"), 16);
    EXPECT_EQ(parse_rate("0.5"), 2);
    EXPECT_EQ(parse_rate("-0.25"), -1);
    EXPECT_EQ(parse_rate("511.75"), 2047);
    EXPECT_EQ(parse_rate("-512"), -2048);
    EXPECT_FALSE(parse_rate("512"));
    EXPECT_FALSE(parse_rate("0.3"));
    EXPECT_FALSE(parse_rate("1.125"));
    EXPECT_FALSE(parse_rate("x"));
    EXPECT_FALSE(parse_rate("4."));
    EXPECT_FALSE(parse_rate(""));
}

TEST(BroadcastTime, TheWholeRangeOfAClock) {
    const EventId range = whole_range(kDefaultFastClock);
    EXPECT_EQ(range.to_string(), "01.01.00.00.01.00.FF.FF");
    EXPECT_TRUE(covers_whole_clock(range, kDefaultFastClock));
    EXPECT_FALSE(covers_whole_clock(range, kDefaultRealTimeClock));
    // A clock whose upper part ends in a 1 bit: the run of zeros marks the range.
    EXPECT_EQ(whole_range(kDefaultRealTimeClock).to_string(), "01.01.00.00.01.01.00.00");
    EXPECT_TRUE(covers_whole_clock(whole_range(kDefaultRealTimeClock), kDefaultRealTimeClock));
    // The upper half alone (Set, Query, Start/Stop) is not the whole clock.
    const EventId upper = make_range(EventId(kDefaultFastClock, 0x8000), 15);
    EXPECT_EQ(upper.to_string(), "01.01.00.00.01.00.80.00");
    EXPECT_FALSE(covers_whole_clock(upper, kDefaultFastClock));
    EXPECT_TRUE(in_range(EventId(kDefaultFastClock, 0xF000), upper));
    EXPECT_FALSE(in_range(EventId(kDefaultFastClock, 0x0117), upper));
    EXPECT_EQ(range_first(upper), EventId(kDefaultFastClock, 0x8000));
    EXPECT_EQ(range_last(upper), EventId(kDefaultFastClock, 0xFFFF));
}

}  // namespace
}  // namespace olcb::broadcast_time
