// A simulated node's Broadcast Time clock (simnode/broadcast_clock.cpp) on a simulated clock: the
// start-up ranges and sequence, Query, Set, the reports of a running clock, rollover at midnight
// and at the year's end, consumers following a generator, and the quirks the faults set.
#include "simnode/broadcast_clock.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace olcb::simnode {
namespace {

using namespace std::chrono_literals;
using broadcast_time::ClockEvent;
using broadcast_time::Kind;

const TimePoint t0{};

// What a clock sent, in words: "PIDV Report Rate 4.00", "PCER Report Time 01:24",
// "PRI 01.01.00.00.01.00.FF.FF".
std::string words(const Message& m) {
    const auto id = EventId::from_bytes(m.payload);
    if (!id) return "?";
    const std::string event =
        broadcast_time::describe(broadcast_time::decode(broadcast_time::suffix_of(*id)));
    switch (m.mti) {
        case Mti::kProducerIdentifiedValid:
            return "PIDV " + event;
        case Mti::kProducerIdentifiedUnknown:
            return "PIDU " + event;
        case Mti::kConsumerIdentifiedUnknown:
            return "CIDU " + event;
        case Mti::kEventReport:
            return "PCER " + event;
        case Mti::kProducerRangeIdentified:
            return "PRI " + id->to_string();
        case Mti::kConsumerRangeIdentified:
            return "CRI " + id->to_string();
        default:
            return "other";
    }
}

// A clock and everything it sent, driven through its deadlines up to a time.
struct Harness {
    BroadcastClock clock;
    std::vector<std::string> sent;
    std::vector<TimePoint> at;
    TimePoint now = t0;

    explicit Harness(ClockConfig config, ClockQuirks quirks = {}) : clock(config, quirks) {}

    BroadcastClock::Send send() {
        return [this](const Message& m) {
            sent.push_back(words(m));
            at.push_back(now);
        };
    }
    void start() { clock.started(now, send()); }
    // Runs every deadline up to `until` (then stays there).
    void run_to(TimePoint until) {
        for (auto d = clock.next_deadline(); d && *d <= until; d = clock.next_deadline()) {
            now = std::max(now, *d);
            clock.poll(now, send());
        }
        now = until;
    }
    void pcer(std::uint16_t suffix) { deliver(Mti::kEventReport, suffix); }
    void deliver(Mti mti, std::uint16_t suffix) {
        Message m;
        m.mti = mti;
        const auto bytes = EventId(clock.clock(), suffix).to_bytes();
        m.payload.assign(bytes.begin(), bytes.end());
        clock.on_message(m, now, send());
    }
    // What was sent since the last take() (at: when, in the same order, until the next take()).
    std::vector<std::string> take() {
        at.clear();
        return std::exchange(sent, {});
    }
};

ClockConfig generator(FastTime start, int rate_quarters = 4, bool running = true) {
    ClockConfig c;
    c.start = start;
    c.rate_quarters = static_cast<std::int16_t>(rate_quarters);
    c.running = running;
    return c;
}

using Strings = std::vector<std::string>;

TEST(BroadcastClock, StartsWithTheWholeRangesAndTheSynchronizationSequence) {
    Harness h(generator(fast_time(2023, 7, 22, 1, 23), 4 * 60));
    h.start();
    EXPECT_EQ(h.take(), (Strings{"PRI 01.01.00.00.01.00.FF.FF", "CRI 01.01.00.00.01.00.FF.FF",
                                 "PIDV Start", "PIDV Report Rate 60.00", "PIDV Report Year 2023",
                                 "PIDV Report Date 07-22", "PIDV Report Time 01:23"}));
    // Item 6: the next minute's Report Time when it becomes valid, 1 s later at rate 60.
    h.run_to(t0 + 999ms);
    EXPECT_TRUE(h.sent.empty());
    h.run_to(t0 + 1s);
    ASSERT_EQ(h.at.size(), 1u);
    EXPECT_EQ(h.at.back(), t0 + 1s);
    EXPECT_EQ(h.take(), Strings{"PCER Report Time 01:24"});
}

TEST(BroadcastClock, QueryAnsweredAtOnceAndIgnoredWithTheQuirk) {
    Harness h(generator(fast_time(2023, 7, 22, 1, 23), 4, false));
    h.start();
    h.take();
    h.run_to(t0 + 5s);
    h.pcer(broadcast_time::kQuerySuffix);
    // Stopped: no item 6.
    EXPECT_EQ(h.take(), (Strings{"PIDV Stop", "PIDV Report Rate 1.00", "PIDV Report Year 2023",
                                 "PIDV Report Date 07-22", "PIDV Report Time 01:23"}));
    h.run_to(t0 + 600s);
    EXPECT_TRUE(h.sent.empty());

    ClockQuirks quirks;
    quirks.ignores_query = true;
    Harness deaf(generator(fast_time(2023, 7, 22, 1, 23)), quirks);
    deaf.start();
    deaf.take();
    deaf.pcer(broadcast_time::kQuerySuffix);
    EXPECT_TRUE(deaf.sent.empty());
}

TEST(BroadcastClock, SetsTakeEffectAtOnceAndOneSequenceFollowsTheLast) {
    Harness h(generator(fast_time(1970, 1, 1, 0, 0)));
    h.start();
    h.run_to(t0 + 10s);
    h.take();
    h.pcer(broadcast_time::kStopSuffix);
    h.pcer(0x8117);  // Set Time 01:23
    h.pcer(0xA716);  // Set Date 07-22
    h.pcer(0xB7E7);  // Set Year 2023
    EXPECT_EQ(h.take(), (Strings{"PCER Report Time 01:23", "PCER Report Date 07-22",
                                 "PCER Report Year 2023"}));
    h.run_to(t0 + 11s);
    h.pcer(0xC010);  // Set Rate 4.00
    EXPECT_EQ(h.take(), Strings{"PCER Report Rate 4.00"});
    h.run_to(t0 + 13900ms);
    EXPECT_TRUE(h.sent.empty());  // 3 s after the last Set, not the first
    h.run_to(t0 + 14s);
    EXPECT_EQ(h.take(), (Strings{"PIDV Stop", "PIDV Report Rate 4.00", "PIDV Report Year 2023",
                                 "PIDV Report Date 07-22", "PIDV Report Time 01:23"}));
    EXPECT_EQ(h.clock.time_at(h.now), fast_time(2023, 7, 22, 1, 23));
}

TEST(BroadcastClock, SetValuesAreMadeEffective) {
    Harness h(generator(fast_time(2023, 1, 31, 12, 0)));
    h.start();
    h.take();
    h.pcer(0xA21F);  // Set Date 02-31: the month's last day
    EXPECT_EQ(h.take(), Strings{"PCER Report Date 02-28"});
    h.pcer(0xC000);  // Set Rate 0: the closest non-zero rate
    EXPECT_EQ(h.take(), Strings{"PCER Report Rate 0.25"});
    h.pcer(0xCFFC);  // Set Rate -1.00
    EXPECT_EQ(h.take(), Strings{"PCER Report Rate -1.00"});
    EXPECT_EQ(h.clock.rate_quarters(), -4);
}

TEST(BroadcastClock, ReportsTimeEveryFiveRealMinutesUnlessAsked) {
    Harness h(generator(fast_time(2023, 7, 22, 6, 0), 4 * 60));  // a fast minute per second
    h.start();
    h.take();
    // A display asks for 06:10 by its own Consumer Identified.
    h.deliver(Mti::kConsumerIdentifiedUnknown, 0x060A);
    h.run_to(t0 + 700s);
    std::vector<std::string> reports = h.take();
    // 06:01 (item 6), 06:10 (asked), then one five real minutes later each: 11:10, 16:10.
    EXPECT_EQ(reports, (Strings{"PCER Report Time 06:01", "PCER Report Time 06:10",
                                "PCER Report Time 11:10", "PCER Report Time 16:10"}));
}

TEST(BroadcastClock, RollsOverIntoTheNextDayAndYear) {
    Harness h(generator(fast_time(2023, 12, 31, 23, 58), 4 * 60));
    h.start();
    h.take();
    h.deliver(Mti::kConsumerIdentifiedUnknown, 0x0000);  // asks for 00:00
    h.run_to(t0 + 6s);
    ASSERT_EQ(h.at.size(), 5u);
    EXPECT_EQ(h.at[1], t0 + 2s);
    EXPECT_EQ(h.at[3], t0 + 5s);  // three seconds after the rollover
    EXPECT_EQ(h.take(),
              (Strings{"PCER Report Time 23:59", "PCER Date Rollover", "PCER Report Time 00:00",
                       "PCER Report Year 2024", "PCER Report Date 01-01"}));
}

TEST(BroadcastClock, RollsOverBackwardsWithANegativeRate) {
    Harness h(generator(fast_time(2024, 1, 1, 0, 1), -4 * 60));
    h.start();
    h.take();
    h.run_to(t0 + 6s);
    const Strings got = h.take();
    ASSERT_GE(got.size(), 3u);
    EXPECT_EQ(got[0], "PCER Report Time 00:00");  // item 6: the minute time runs into
    EXPECT_EQ(got[1], "PCER Date Rollover");
    EXPECT_EQ(got[got.size() - 2], "PCER Report Year 2023");
    EXPECT_EQ(got.back(), "PCER Report Date 12-31");
}

TEST(BroadcastClock, RolloverQuirks) {
    using R = ClockQuirks::Rollover;
    const auto after_midnight = [](R r) {
        ClockQuirks q;
        q.rollover = r;
        Harness h(generator(fast_time(2023, 12, 31, 23, 59), 4 * 60), q);
        h.start();
        h.take();
        h.deliver(Mti::kConsumerIdentifiedUnknown, 0x0000);
        h.run_to(t0 + 5s);
        return h.take();
    };
    EXPECT_EQ(after_midnight(R::kYearKept),
              (Strings{"PCER Date Rollover", "PCER Report Time 00:00", "PCER Report Year 2023",
                       "PCER Report Date 01-01"}));
    EXPECT_EQ(after_midnight(R::kDateKept),
              (Strings{"PCER Date Rollover", "PCER Report Time 00:00", "PCER Report Year 2023",
                       "PCER Report Date 12-31"}));
    EXPECT_EQ(after_midnight(R::kEventLate),
              (Strings{"PCER Report Time 00:00", "PCER Date Rollover", "PCER Report Year 2024",
                       "PCER Report Date 01-01"}));
}

TEST(BroadcastClock, DriftRunsFasterThanTheReportedRate) {
    ClockQuirks q;
    q.drift_percent = 50;
    Harness h(generator(fast_time(2023, 7, 22, 1, 23), 4 * 60), q);
    h.start();
    EXPECT_EQ(h.take().at(3), "PIDV Report Rate 60.00");
    h.run_to(t0 + 1s);
    ASSERT_EQ(h.at.size(), 1u);
    EXPECT_EQ(h.at.back(), t0 + 666667us);
    EXPECT_EQ(h.take(), Strings{"PCER Report Time 01:24"});
}

TEST(BroadcastClock, SequenceOutOfOrderWithTheQuirk) {
    ClockQuirks q;
    q.sync_out_of_order = true;
    Harness h(generator(fast_time(2023, 7, 22, 1, 23)), q);
    h.start();
    EXPECT_EQ(h.take(), (Strings{"PRI 01.01.00.00.01.00.FF.FF", "CRI 01.01.00.00.01.00.FF.FF",
                                 "PIDV Start", "PIDV Report Rate 1.00", "PIDV Report Time 01:23",
                                 "PIDV Report Date 07-22", "PIDV Report Year 2023"}));
}

TEST(BroadcastClock, OpenMrnLikeQuirks) {
    ClockQuirks q;
    q.half_consumer_range = true;
    q.reports_asked = true;
    Harness h(generator(fast_time(2023, 1, 31, 12, 0)), q);
    h.start();
    const Strings got = h.take();
    EXPECT_EQ(got.at(1), "CRI 01.01.00.00.01.00.80.00");
    h.pcer(0xA21E);  // Set Date 02-30: reported as asked, taken as Feb 28
    EXPECT_EQ(h.take(), Strings{"PCER Report Date 02-30"});
    EXPECT_EQ(h.clock.time_at(h.now), fast_time(2023, 2, 28, 12, 0));
}

TEST(BroadcastClock, AnswersIdentifyForItsOwnEventsOnly) {
    Harness h(generator(fast_time(2023, 7, 22, 1, 23)));
    h.start();
    h.take();
    h.deliver(Mti::kIdentifyProducer, 0x0117);
    h.deliver(Mti::kIdentifyProducer, 0x8117);  // a Set: consumed, not produced
    h.deliver(Mti::kIdentifyConsumer, 0x8117);
    h.deliver(Mti::kIdentifyConsumer, 0x5000);  // reserved
    EXPECT_EQ(h.take(), (Strings{"PIDU Report Time 01:23", "CIDU Set Time 01:23"}));
    // Another clock's events are not ours.
    Message m;
    m.mti = Mti::kIdentifyProducer;
    const auto bytes = EventId(broadcast_time::kAlternateClock1, 0x0117).to_bytes();
    m.payload.assign(bytes.begin(), bytes.end());
    h.clock.on_message(m, h.now, h.send());
    EXPECT_TRUE(h.sent.empty());
}

TEST(BroadcastClock, AConsumerAsksAndFollowsTheGenerator) {
    ClockConfig display;
    display.role = ClockRole::kConsumer;
    display.start = fast_time(1970, 1, 1, 0, 0);
    Harness c(display);
    c.start();
    EXPECT_EQ(c.take(), (Strings{"CRI 01.01.00.00.01.00.FF.FF", "PCER Query"}));
    EXPECT_FALSE(c.clock.next_deadline());
    // The generator's sequence: running at 4x, 2023-07-22 01:23.
    c.deliver(Mti::kProducerIdentifiedValid, broadcast_time::kStartSuffix);
    c.deliver(Mti::kProducerIdentifiedValid, 0x4010);
    c.deliver(Mti::kProducerIdentifiedValid, 0x37E7);
    c.deliver(Mti::kProducerIdentifiedValid, 0x2716);
    c.deliver(Mti::kProducerIdentifiedValid, 0x0117);
    c.now = t0 + 15s;  // a quarter of a real minute: one fast minute
    EXPECT_EQ(c.clock.time_at(c.now), fast_time(2023, 7, 22, 1, 24));
    c.deliver(Mti::kIdentifyConsumer, 0x0117);
    EXPECT_EQ(c.take(), Strings{"CIDU Report Time 01:23"});
    // Stop freezes it.
    c.pcer(broadcast_time::kStopSuffix);
    c.now = t0 + 60s;
    EXPECT_EQ(c.clock.time_at(c.now), fast_time(2023, 7, 22, 1, 24));
}

TEST(BroadcastClock, AConsumerCrossesMidnightOnDateRollover) {
    ClockConfig display;
    display.role = ClockRole::kConsumer;
    display.start = fast_time(2023, 7, 22, 23, 59);
    display.running = false;
    Harness c(display);
    c.start();
    c.pcer(broadcast_time::kDateRolloverSuffix);
    c.pcer(0x0000);
    EXPECT_EQ(c.clock.time_at(c.now), fast_time(2023, 7, 23, 0, 0));
    // Without the rollover, 00:00 sets the time back within the day.
    Harness d(display);
    d.start();
    d.pcer(0x0000);
    EXPECT_EQ(d.clock.time_at(d.now), fast_time(2023, 7, 22, 0, 0));
}

TEST(BroadcastClock, ClockSpecsParseAndPrintBack) {
    std::string error;
    const FastTime wall = fast_time(2025, 3, 4, 5, 6);
    auto c = parse_clock_config(
        "generator default-realtime rate=2.5 time=1955-07-04T06:00 "
        "stopped",
        wall, error);
    ASSERT_TRUE(c) << error;
    EXPECT_EQ(c->clock, broadcast_time::kDefaultRealTimeClock);
    EXPECT_EQ(c->rate_quarters, 10);
    EXPECT_FALSE(c->running);
    EXPECT_EQ(fast_time_text(c->start), "1955-07-04 06:00");
    EXPECT_EQ(clock_config_text(*c),
              "generator default-realtime rate=2.50 time=1955-07-04T06:00 stopped");
    EXPECT_EQ(parse_clock_config(clock_config_text(*c), wall, error), c);
    c = parse_clock_config("consumer 05.01.01.01.22.00 time=now", wall, error);
    ASSERT_TRUE(c) << error;
    EXPECT_EQ(c->role, ClockRole::kConsumer);
    EXPECT_EQ(c->clock, NodeId{0x050101012200ull});
    EXPECT_EQ(c->start, wall);
    EXPECT_FALSE(parse_clock_config("", wall, error));
    EXPECT_FALSE(parse_clock_config("display", wall, error));
    EXPECT_FALSE(parse_clock_config("generator rate=0.3", wall, error));
    EXPECT_NE(error.find("rate '0.3'"), std::string::npos) << error;
    EXPECT_FALSE(parse_clock_config("generator time=2023-02-30T00:00", wall, error));
    EXPECT_FALSE(parse_clock_config("generator time=4096-01-01T00:00", wall, error));
    EXPECT_FALSE(parse_clock_config("generator fast", wall, error));
    EXPECT_NE(error.find("unknown word 'fast'"), std::string::npos) << error;
}

}  // namespace
}  // namespace olcb::simnode
