// Broadcast Time faults: a clock generator (the `clock` key, docs/scenarios.md) that breaks
// BroadcastTimeS. They change nothing in a node without clocks.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

void drift(ClockQuirks& quirks, FaultValue v) {
    quirks.drift_percent = static_cast<int>(v.value);
}

void no_query_answer(ClockQuirks& quirks, FaultValue) {
    quirks.ignores_query = true;
}

void sync_reversed(ClockQuirks& quirks, FaultValue) {
    quirks.sync_out_of_order = true;
}

void half_range(ClockQuirks& quirks, FaultValue) {
    quirks.half_consumer_range = true;
}

void asked_reported(ClockQuirks& quirks, FaultValue) {
    quirks.reports_asked = true;
}

// The choices in parse order; the value is the choice's index + 1.
void rollover(ClockQuirks& quirks, FaultValue v) {
    using R = ClockQuirks::Rollover;
    constexpr R kChoices[] = {R::kYearKept, R::kDateKept, R::kEventLate};
    quirks.rollover = kChoices[v.value - 1];
}

}  // namespace

// A data table, one entry per fault: its length is not complexity.
// NOLINTNEXTLINE(readability-function-size)
std::vector<FaultDecl> clock_faults() {
    return {
        {
            .name = "clock-drift",
            .order = 600,
            .param = {ParamKind::kNumber, "PERCENT", 50, 1, 1000},
            .summary = "clock generators run PERCENT percent faster than the rate they report",
            .doc_parameter = "`PERCENT`, default 50 (1..1000)",
            .rule_broken = "BroadcastTimeS §5: a running clock's time advances rate times as "
                           "fast as real time",
            .client_sees = "every generator clock of the node reports its rate as set (Report "
                           "Rate, the synchronization sequence) but its fast time runs PERCENT "
                           "percent faster: at rate 60 with the default a fast minute passes in "
                           "0.67 s, not 1 s, so its Report Time events come early and consumers "
                           "that extrapolate from the rate fall behind",
            .verdict = Verdict::kFail,
            .category = "clock",
            .checks = {"clock.rate"},
            .hooks = {.clock = drift},
        },
        {
            .name = "clock-rollover-wrong",
            .order = 610,
            .param = {ParamKind::kChoice, "", 1, 1, 3, {"year", "date", "late"}},
            .summary = "clock generators get midnight wrong: the year does not advance on Dec 31 "
                       "(year), the date never advances (date), or Date Rollover comes after "
                       "the 00:00 report (late)",
            .doc_parameter = "`year` (default), `date` or `late`",
            .rule_broken = "BroadcastTimeS §5, §6.2: time progresses through midnight into the "
                           "next day (and year); Date Rollover is sent immediately before it, "
                           "Report Year and Report Date three seconds later",
            .client_sees = "`year`: Dec 31 23:59 is followed by Jan 1 of the same year (Report "
                           "Year 3 s after Date Rollover names the old year); `date`: at 00:00 "
                           "the date stays as it was; `late`: the 00:00 Report Time goes out "
                           "before Date Rollover, so a display sets its time back within the "
                           "day",
            .verdict = Verdict::kFail,
            .category = "clock",
            .checks = {"clock.rollover"},
            .hooks = {.clock = rollover},
        },
        {
            .name = "clock-query-ignored",
            .order = 620,
            .summary = "clock generators do not answer Query",
            .rule_broken = "BroadcastTimeS §6.4: a Query is answered with the synchronization "
                           "sequence of §6.3",
            .client_sees = "a PCER of the clock's Query event (suffix F0.00) gets nothing; the "
                           "start-up sequence, Set and Identify Events are answered as usual",
            .verdict = Verdict::kFail,
            .category = "clock",
            .checks = {"clock.query"},
            .hooks = {.clock = no_query_answer},
        },
        {
            .name = "clock-sync-order",
            .order = 630,
            .summary = "clock generators send the synchronization sequence as Start/Stop, Rate, "
                       "Time, Date, Year",
            .rule_broken = "BroadcastTimeS §6.3: Start/Stop, Rate, Year, Date, Time, then the "
                           "next minute's Report Time, in this order",
            .client_sees = "every synchronization sequence (start-up, Query, 3 s after a Set) "
                           "has its Producer Identified Valid messages for Year, Date and Time "
                           "in reverse order, so a display that takes the time before the date "
                           "applies it to the wrong day",
            .verdict = Verdict::kFail,
            .category = "clock",
            .checks = {"clock.query", "clock.set-sync"},
            .hooks = {.clock = sync_reversed},
        },
        {
            .name = "clock-half-range",
            .order = 640,
            .summary = "clock generators announce consuming only the upper half of the clock's "
                       "events (Set, Query, Start/Stop), as OpenMRN's time server does",
            .rule_broken = "BroadcastTimeS §6.1: at start-up a generator sends Producer and "
                           "Consumer Range Identified covering the whole 16 bits of the clock",
            .client_sees = "after Initialization Complete and on Identify Events the Consumer "
                           "Range Identified is 01.01.00.00.01.00.80.00 (0x8000-0xFFFF), not "
                           ".FF.FF; the Producer Range Identified covers all 16 bits. Seen on "
                           "OpenMRN's applications/time_server (its BroadcastTimeServer)",
            .verdict = Verdict::kFail,
            .category = "clock",
            .checks = {"clock.startup"},
            .hooks = {.clock = half_range},
        },
        {
            .name = "clock-reports-asked",
            .order = 650,
            .summary = "clock generators report a Set as asked, not as taken (Set Date 02-30: "
                       "Report Date 02-30 while the clock went to Feb 28)",
            .rule_broken = "BroadcastTimeS §6.5: a Set takes effect at once and the generator "
                           "produces the effective Report",
            .client_sees = "the Report Time, Date, Year or Rate right after a Set repeats the "
                           "Set's value; where the clock took another (a day past the month's "
                           "end, Set Rate 0) the next synchronization sequence shows the one it "
                           "took, so a display that believed the Report is wrong until then",
            .verdict = Verdict::kFail,
            .category = "clock",
            .checks = {"clock.set-effective"},
            .hooks = {.clock = asked_reported},
        },
    };
}

}  // namespace olcb::simnode
