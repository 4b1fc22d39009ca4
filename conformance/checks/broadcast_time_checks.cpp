// Broadcast Time generator checks (BroadcastTimeS): a clock generator's ranges, Query, Set,
// reports, rate, rollover, start-up and the restore, one registry entry each; the consumer's are
// in clock_consumer_checks.cpp. Broadcast Time has no PIP bit: a node generates the clocks it
// identifies producing (ClockRoles, from its answer to Identify Events addressed), and a check of
// a role it does not have SKIPs. The checks that set a clock run only on a node named with --node
// and not under --read-only: the state a Query saved (clock.query) is set back after each of the
// two sessions that set a clock (the Set exchange, the run through midnight), whichever check
// asks for a session first; clock.restored reports both (clock_probe.cpp).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "conformance/checks/checks.hpp"
#include "conformance/checks/clock_observer.hpp"
#include "conformance/checks/clock_probe.hpp"
#include "conformance/checks/clock_roles.hpp"

namespace olcb::conform::checks {
namespace {

using namespace clocks;
using namespace std::chrono_literals;

// Report Time events without an exception are at least a real minute apart (§6.2).
constexpr Duration kReportSpacing = 60s;
// Fast minutes pass in the real time the rate says within this share, plus kJitter.
constexpr double kRateTolerance = 0.03;

PerClock judge_query(CheckRun& run, NodeId clock) {
    const ClockQuery& q = query_of(run, clock);
    const Sync& s = q.sync;
    const std::string want =
        "Producer Identified Valid: Start/Stop, Rate, Year, Date, Time; then the next minute's "
        "Report Time";
    if (!s.started())
        return fail(
            "Query got no synchronization sequence within " + ms_text(2 * answer_window(run)), want,
            "nothing");
    if (!s.problem.empty())
        return fail("Query answered out of order: " + s.problem, want, s.text());
    if (const std::string next = judge_next(s, q.next_awaited, q.next_wait); !next.empty())
        return fail("Query answered, but " + next, want, s.text());
    std::string tail;
    if (s.next)
        tail = ", then " + bt::describe(s.next->event);
    else if (s.running && s.rate != 0)
        tail = " (item 6 not awaited: the next minute is up to " + ms_text(fast_minute(s.rate)) +
               " away; --thorough waits up to 65 s)";
    return pass("Query answered in order: " + s.text() + tail);
}

// ---- the generator's judgements ----

// The events a generator produces (Report forms, Start/Stop, Date Rollover) and consumes (Set
// forms, Query, Start/Stop), a sample of each form.
constexpr std::uint16_t kProducedSample[] = {0x0000,
                                             0x173B,
                                             0x2101,
                                             0x2C1F,
                                             0x3000,
                                             0x3FFF,
                                             0x4000,
                                             0x4FFF,
                                             bt::kStopSuffix,
                                             bt::kStartSuffix,
                                             bt::kDateRolloverSuffix};
constexpr std::uint16_t kConsumedSample[] = {
    0x8000, 0x973B, 0xA101,           0xAC1F,          0xB000,          0xBFFF,
    0xC000, 0xCFFF, bt::kQuerySuffix, bt::kStopSuffix, bt::kStartSuffix};

std::string not_covered(const std::function<bool(std::uint64_t)>& covers, NodeId clock,
                        std::span<const std::uint16_t> sample) {
    std::string out;
    for (std::uint16_t suffix : sample)
        if (!covers(EventId(clock, suffix).value()))
            out += (out.empty() ? "" : ", ") + bt::describe(bt::decode(suffix));
    return out;
}

bool whole(const std::set<std::uint64_t>& ranges, NodeId clock) {
    return std::any_of(ranges.begin(), ranges.end(),
                       [&](std::uint64_t r) { return bt::covers_whole_clock(EventId(r), clock); });
}

// "Producer Range Identified 01.01.00.00.01.00.FF.FF, Consumer Range Identified ...": the ranges
// of the answer within the clock's block.
std::string clock_ranges(const EventAnswers& a, NodeId clock) {
    std::string out;
    for (const auto& [name, ranges] :
         {std::pair{"Producer", &a.produced_ranges}, std::pair{"Consumer", &a.consumed_ranges}})
        for (std::uint64_t r : *ranges)
            if (bt::clock_of(EventId(r)) == clock)
                out += (out.empty() ? "" : ", ") + std::string(name) + " Range Identified " +
                       EventId(r).to_string();
    return out.empty() ? "no range of the clock" : out;
}

PerClock judge_ranges(CheckRun& run, NodeId clock) {
    const EventAnswers& a = run.probe<EventAnswers>(IdentifyTo::kTheNode);
    const std::string produced =
        not_covered([&](std::uint64_t id) { return a.produces(id); }, clock, kProducedSample);
    const std::string consumed =
        not_covered([&](std::uint64_t id) { return a.consumes(id); }, clock, kConsumedSample);
    const std::string range = bt::whole_range(clock).to_string();
    if (!produced.empty() || !consumed.empty()) {
        std::string seen;
        if (!produced.empty()) seen = "not identified as produced: " + produced;
        if (!consumed.empty())
            seen +=
                (seen.empty() ? "" : "; ") + std::string("not identified as consumed: ") + consumed;
        return fail(
            "the answer to Identify Events addressed leaves out events the generator "
            "produces or consumes",
            "Producer and Consumer Range Identified " + range, seen);
    }
    if (!whole(a.produced_ranges, clock) || !whole(a.consumed_ranges, clock))
        return warn("the generator's events are identified, but not as the two ranges of " + range +
                    " it announces at start-up (§6.1): " + clock_ranges(a, clock) + " (" +
                    a.describe() + ")");
    return pass("Producer and Consumer Range Identified " + range + " (the whole clock)");
}

void identify_ranges(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, false, [&](NodeId c) { return judge_ranges(run, c); });
}

void query(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, false, [&](NodeId c) { return judge_query(run, c); });
}

PerClock judge_set_immediate(CheckRun& run, NodeId clock) {
    const SetSession& c = set_session(run, clock);
    if (!c.not_run.empty()) return skip(c.not_run);
    std::string missing;
    std::string seen;
    for (const Echo& e : c.echoes) {
        if (!e.got) {
            missing += (missing.empty() ? "" : ", ") + bt::describe(e.asked);
            continue;
        }
        seen += (seen.empty() ? "" : "; ") + bt::describe(e.asked) + ": " + bt::describe(*e.got) +
                " after " + ms_text(e.after);
    }
    if (!missing.empty())
        return fail("no Report within " + ms_text(answer_window(run)) + " of " + missing,
                    "the effective Report Time, Date, Year or Rate at once after each Set",
                    seen.empty() ? "none" : seen);
    return pass("each Set was reported at once: " + seen);
}

void set_immediate(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, true, [&](NodeId c) { return judge_set_immediate(run, c); });
}

// The value a Set's report gave (what the clock took), else what was asked.
ClockEvent effective(const SetSession& c, Kind set) {
    for (const Echo& e : c.echoes)
        if (e.asked.kind == set) return e.got ? *e.got : e.asked.as_report();
    return ClockEvent{};
}

PerClock judge_set_sync(CheckRun& run, NodeId clock) {
    const SetSession& c = set_session(run, clock);
    if (!c.not_run.empty()) return skip(c.not_run);
    const std::vector<Sync> syncs = read_syncs(c.set_msgs);
    const auto it = std::find_if(syncs.begin(), syncs.end(),
                                 [&](const Sync& y) { return y.at() >= c.last_set; });
    const std::string want = "Stop, " + bt::describe(effective(c, Kind::kSetRate)) + ", " +
                             bt::describe(effective(c, Kind::kSetYear)) + ", " +
                             bt::describe(effective(c, Kind::kSetDate)) + ", " +
                             bt::describe(effective(c, Kind::kSetTime));
    if (it == syncs.end())
        return fail("no synchronization sequence within " + ms_text(c.set_end - c.last_set) +
                        " of the last Set",
                    want, "nothing");
    if (!it->problem.empty())
        return fail("the sequence after the Sets: " + it->problem, want, it->text());
    const bool right = !it->running && it->rate == effective(c, Kind::kSetRate).rate_quarters &&
                       it->year == effective(c, Kind::kSetYear) &&
                       it->date == effective(c, Kind::kSetDate) &&
                       it->time == effective(c, Kind::kSetTime);
    if (!right)
        return fail("the sequence after the Sets does not carry what was set", want, it->text());
    return pass("the sequence " + ms_text(it->at() - c.last_set) +
                " after the last Set: " + it->text());
}

void set_sync(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, true, [&](NodeId c) { return judge_set_sync(run, c); });
}

PerClock judge_set_once(CheckRun& run, NodeId clock) {
    const SetSession& c = set_session(run, clock);
    if (!c.not_run.empty()) return skip(c.not_run);
    const std::vector<Sync> syncs = read_syncs(c.set_msgs);
    std::string times;
    for (const Sync& y : syncs) times += (times.empty() ? "" : ", ") + ms_text(y.at() - c.last_set);
    const std::string want = "one sequence, three seconds after the last Set";
    const std::string seen = std::to_string(syncs.size()) + " sequences, at " +
                             (times.empty() ? "-" : times) + " from the last Set";
    if (syncs.empty()) return fail("no sequence after the Sets (see clock.set-sync)", want, seen);
    if (syncs.size() > 1)
        return fail("Sets 1 s apart brought " + std::to_string(syncs.size()) + " sequences", want,
                    seen);
    if (syncs.front().at() < c.last_set + kSettle - kEarly)
        return fail("the sequence came " + times + " after the last Set, before three seconds",
                    want, seen);
    return pass("Sets 1 s apart brought one sequence, " + times + " after the last Set");
}

void set_once(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, true, [&](NodeId c) { return judge_set_once(run, c); });
}

PerClock judge_set_effective(CheckRun& run, NodeId clock) {
    const SetSession& c = set_session(run, clock);
    if (!c.not_run.empty()) return skip(c.not_run);
    const std::string asked = bt::describe(c.odd_date.asked);
    if (!c.odd_date.got)
        return fail(asked + " (in 2023) got no Report Date within " + ms_text(answer_window(run)),
                    "the effective Report Date at once", "nothing");
    if (c.odd_sync.items.size() < 5)
        return skip("the Query after " + asked +
                    " got no whole sequence: the date taken is "
                    "not known");
    const std::string got = bt::describe(*c.odd_date.got);
    if (*c.odd_date.got != c.odd_sync.date)
        return fail(asked + " (in 2023) was reported as " + got + ", but a Query then showed " +
                        bt::describe(c.odd_sync.date),
                    "the Report Date of the date the clock took", got);
    return pass(asked + " (in 2023) reported as " + got + ", the date a Query then showed");
}

void set_effective(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, true, [&](NodeId c) { return judge_set_effective(run, c); });
}

// The first PCER of the running exchange matching pred, after Start.
const ClockMsg* first_after_start(const RunSeen& r,
                                  const std::function<bool(const ClockMsg&)>& pred,
                                  const ClockMsg* after = nullptr) {
    for (const ClockMsg& m : r.msgs) {
        if (m.at < r.started || (after && m.at < after->at) || &m == after) continue;
        if (pred(m)) return &m;
    }
    return nullptr;
}

const ClockMsg* report_of(const RunSeen& r, int hour, int minute) {
    return first_after_start(r, [&](const ClockMsg& m) {
        return m.mti == Mti::kEventReport && same_minute(m.event, hour, minute);
    });
}

PerClock judge_requested(CheckRun& run, NodeId clock) {
    const RunSession& c = run_session(run, clock);
    if (!c.not_run.empty()) return skip(c.not_run);
    if (!c.run.not_run.empty()) return skip(c.run.not_run);
    const ClockMsg* a = report_of(c.run, 23, 59);
    const ClockMsg* b = report_of(c.run, 0, 0);
    const std::string want =
        "Report Time 23:59 and 00:00 (identified as consumed) as they "
        "become valid";
    std::string seen =
        std::string(a ? "23:59 after " + ms_text(a->at - c.run.started) : "no 23:59") + ", " +
        (b ? "00:00 after " + ms_text(b->at - c.run.started) : "no 00:00");
    if (!a || !b)
        return fail(
            "a Report Time lcc-conform identified consuming did not come (2023-12-31 "
            "23:58 at " +
                bt::rate_text(c.run.rate) + ")",
            want, seen);
    return pass("Report Time 23:59 and 00:00, identified as consumed, came: " + seen +
                " from Start at " + bt::rate_text(c.run.rate));
}

void requested_minute(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, true, [&](NodeId c) { return judge_requested(run, c); });
}

PerClock judge_rate(CheckRun& run, NodeId clock) {
    const RunSession& c = run_session(run, clock);
    if (!c.not_run.empty()) return skip(c.not_run);
    if (!c.run.not_run.empty()) return skip(c.run.not_run);
    // The first and the last Report Time after Start: each goes out as its minute begins.
    const ClockMsg* first = report_of(c.run, 23, 59);
    const ClockMsg* last = nullptr;
    for (const ClockMsg& m : c.run.msgs)
        if (first && m.at > first->at && is_pcer(m, Kind::kReportTime)) last = &m;
    if (!first || !last || minutes_between(first->event, last->event) == 0)
        return skip("depends on clock.requested-minute: no Report Time 23:59 and a later one");
    const int minutes = minutes_between(first->event, last->event);
    const Duration want = minutes * fast_minute(c.run.rate);
    const Duration got = last->at - first->at;
    const auto tolerance = std::chrono::duration_cast<Duration>(want * kRateTolerance) + kJitter;
    const std::string what = bt::describe(first->event) + " to " + bt::describe(last->event) +
                             " took " + ms_text(got) + " at rate " + bt::rate_text(c.run.rate) +
                             " (" + std::to_string(minutes) + " fast minutes are " + ms_text(want) +
                             ")";
    if (got + tolerance < want || got > want + tolerance)
        return fail("the clock does not run at the rate it reports: " + what,
                    ms_text(want) + " +- " + ms_text(tolerance), ms_text(got));
    return pass(what);
}

void rate(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, true, [&](NodeId c) { return judge_rate(run, c); });
}
PerClock judge_rollover(CheckRun& run, NodeId clock) {
    const RunSession& c = run_session(run, clock);
    if (!c.not_run.empty()) return skip(c.not_run);
    if (!c.run.not_run.empty()) return skip(c.run.not_run);
    const std::string want =
        "Date Rollover before Report Time 00:00, Report Year 2024 and "
        "Report Date 01-01 three seconds after it";
    const ClockMsg* roll =
        first_after_start(c.run, [](const ClockMsg& m) { return is_pcer(m, Kind::kDateRollover); });
    if (!roll) return fail("no Date Rollover as the clock passed 00:00 on Dec 31", want, "none");
    const ClockMsg* midnight = report_of(c.run, 0, 0);
    if (midnight && midnight->at <= roll->at && midnight < roll)
        return fail("Report Time 00:00 came before Date Rollover", want,
                    "00:00, then Date Rollover " + ms_text(roll->at - midnight->at) + " later");
    const auto after = [&](Kind k) {
        return first_after_start(
            c.run, [&](const ClockMsg& m) { return is_pcer(m, k); }, roll);
    };
    const ClockMsg* year = after(Kind::kReportYear);
    const ClockMsg* date = after(Kind::kReportDate);
    if (!year || !date)
        return fail("Report Year and Report Date did not both follow Date Rollover", want,
                    std::string(year ? bt::describe(year->event) : "no Report Year") + ", " +
                        (date ? bt::describe(date->event) : "no Report Date"));
    const std::string seen = bt::describe(year->event) + " after " + ms_text(year->at - roll->at) +
                             ", " + bt::describe(date->event) + " after " +
                             ms_text(date->at - roll->at);
    if (year->event != ClockEvent::report_year(2024) ||
        date->event != ClockEvent::report_date(1, 1))
        return fail("after Dec 31 2023 the clock named another day", want, seen);
    const TimePoint latest = roll->at + kSettle + answer_window(run);
    for (const ClockMsg* m : {year, date})
        if (m->at < roll->at + kSettle - kEarly || m->at > latest)
            return fail("Report Year and Date did not come three seconds after Date Rollover", want,
                        seen);
    return pass("Date Rollover" + std::string(midnight ? " before Report Time 00:00" : "") +
                ", then " + seen);
}

void rollover(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, true, [&](NodeId c) { return judge_rollover(run, c); });
}

// Report Time minutes (hour * 60 + minute) some node on the segment identified consuming.
std::set<int> asked_minutes(Session& s, NodeId clock) {
    std::set<int> out;
    for (const ReceivedMessage& r : s.messages_since(0)) {
        if (!is_consumer_identified(r.message.mti)) continue;
        const auto id = EventId::from_bytes(r.message.payload);
        if (!id || bt::clock_of(*id) != clock) continue;
        const ClockEvent e = bt::decode(bt::suffix_of(*id));
        if (e.kind == Kind::kReportTime) out.insert(e.hour * 60 + e.minute);
    }
    return out;
}

// The Report Time PCERs of msgs that no exception of §6.2 explains: not asked for by a consumer,
// not item 6 of a sequence, not the report of a Set Time lcc-conform sent.
std::vector<const ClockMsg*> unexcused(const std::vector<ClockMsg>& msgs,
                                       const std::set<int>& asked) {
    std::set<const ClockMsg*> item6;
    for (std::size_t i = 0; i < msgs.size(); ++i) {
        if (!is_producer_identified(msgs[i].mti) || !opens_sequence(msgs[i].event.kind)) continue;
        const Sync y = read_sync(msgs, i);
        if (!y.next) continue;
        for (const ClockMsg& m : msgs)
            if (m.at == y.next->at && m.event == y.next->event) item6.insert(&m);
    }
    std::vector<const ClockMsg*> out;
    for (const ClockMsg& m : msgs) {
        if (!is_pcer(m, Kind::kReportTime) || item6.count(&m)) continue;
        if (asked.count(m.event.hour * 60 + m.event.minute)) continue;
        if (same_minute(m.event, 1, 23) || same_minute(m.event, 23, 58)) continue;
        out.push_back(&m);
    }
    return out;
}

// The first two Report Time PCERs of msgs less than a real minute apart with no reason
// (nullopt: none).
std::optional<std::pair<const ClockMsg*, const ClockMsg*>> too_close(
    const std::vector<ClockMsg>& msgs, const std::set<int>& asked) {
    const auto free = unexcused(msgs, asked);
    for (std::size_t i = 1; i < free.size(); ++i)
        if (free[i]->at - free[i - 1]->at < kReportSpacing - kJitter)
            return std::make_pair(free[i - 1], free[i]);
    return std::nullopt;
}

PerClock judge_frequency(CheckRun& run, NodeId clock) {
    const SessionsMade made = sessions_made(run, clock);
    if (const std::string why = made.not_run(); !why.empty()) return skip(why);
    std::set<int> asked = asked_minutes(run.session(), clock);
    // And the minutes lcc-conform itself identified consuming (its own messages are not logged).
    asked.insert({23 * 60 + 59, 0});
    std::vector<const std::vector<ClockMsg>*> seen;
    if (made.set && made.set->not_run.empty()) seen.push_back(&made.set->set_msgs);
    if (made.running && made.running->not_run.empty()) seen.push_back(&made.running->run.msgs);
    std::size_t reports = 0;
    for (const auto* msgs : seen) {
        reports += static_cast<std::size_t>(
            std::count_if(msgs->begin(), msgs->end(),
                          [](const ClockMsg& m) { return is_pcer(m, Kind::kReportTime); }));
        if (const auto pair = too_close(*msgs, asked))
            return fail(
                "Report Time events no consumer asked for came " +
                    ms_text(pair->second->at - pair->first->at) + " apart",
                "at most one a real minute, besides those consumers asked for, item "
                "6 of a sequence and a Set's report",
                bt::describe(pair->first->event) + ", then " + bt::describe(pair->second->event));
    }
    return pass(std::to_string(reports) +
                " Report Time events while the clock was set and run, "
                "none less than a real minute after another without a reason (the hourly "
                "minimum needs an hour: not judged)");
}

void report_frequency(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, true, [&](NodeId c) { return judge_frequency(run, c); });
}

PerClock judge_restored(CheckRun& run, NodeId clock) {
    const SessionsMade made = sessions_made(run, clock);
    if (const std::string why = made.not_run(); !why.empty()) return skip(why);
    std::string to;
    for (const auto& [name, session] :
         {std::pair{"the Set exchange", made.set ? &made.set->restore : nullptr},
          std::pair{"the run through midnight", made.running ? &made.running->restore : nullptr}}) {
        if (!session) continue;
        const Restore& r = *session;
        if (r.to.empty()) return skip("the saved state is no date: nothing was set back");
        if (!r.problem.empty())
            return fail("after " + std::string(name) + " the clock was set back to " + r.to +
                            ", but " + r.problem,
                        r.to, r.problem);
        to += (to.empty() ? "after " : "; after ") + std::string(name) + ": " + r.to;
    }
    return pass("the clock was set back to its saved state and a Query shows it (" + to +
                "); it may go on reporting 23:59 and 00:00, which lcc-conform identified "
                "consuming (no message withdraws that)");
}

void restored(CheckRun& run, const CheckSpec& spec) {
    each_generated(run, spec, true, [&](NodeId c) { return judge_restored(run, c); });
}

// Each Range Identified of the clock once, in the order first sent (the start-up's and an
// Identify Events answer's are the same messages).
std::string ranges_text(const std::vector<ClockMsg>& msgs) {
    std::vector<std::string> seen;
    for (const ClockMsg& m : msgs) {
        if (m.mti != Mti::kProducerRangeIdentified && m.mti != Mti::kConsumerRangeIdentified)
            continue;
        std::string one = std::string(mti_name(m.mti)) + " " + m.id.to_string();
        if (std::find(seen.begin(), seen.end(), one) == seen.end()) seen.push_back(std::move(one));
    }
    std::string out;
    for (const std::string& r : seen) out += (out.empty() ? "" : ", ") + r;
    return out.empty() ? "no Range Identified of the clock" : out;
}

PerClock judge_startup(CheckRun& run, NodeId clock) {
    const std::size_t mark = *run.probe<Startup>().mark;
    const auto first = watch(run, clock, mark, 2 * answer_window(run),
                             [](const auto& m) { return read_sync(m).items.size() == 5; });
    bool awaited = false;
    Duration waited{};
    const Sync sync = await_next(run, clock, mark, read_sync(first), awaited, waited);
    const auto msgs = clock_msgs(run.session(), run.alias(), mark, clock);
    const auto whole_of = [&](Mti mti) {
        return std::any_of(msgs.begin(), msgs.end(), [&](const ClockMsg& m) {
            return m.mti == mti && bt::covers_whole_clock(m.id, clock);
        });
    };
    const std::string want = "Producer and Consumer Range Identified " +
                             bt::whole_range(clock).to_string() + ", and the sequence";
    if (!whole_of(Mti::kProducerRangeIdentified) || !whole_of(Mti::kConsumerRangeIdentified))
        return fail("after start-up the clock's ranges do not both cover its 16 bits", want,
                    ranges_text(msgs));
    if (!sync.started()) return fail("no synchronization sequence after start-up", want, "none");
    if (!sync.problem.empty())
        return fail("the sequence after start-up: " + sync.problem, want, sync.text());
    if (const std::string next = judge_next(sync, awaited, waited); !next.empty())
        return fail("the sequence after start-up: " + next, want, sync.text());
    return pass("after start-up: " + ranges_text(msgs) + "; " + sync.text() +
                (sync.next ? ", then " + bt::describe(sync.next->event) : ""));
}

void startup(CheckRun& run, const CheckSpec& spec) {
    if (const std::string why = generator_gate(run); !why.empty()) return run.out(spec).skip(why);
    if (const std::string why = startup_gate(run); !why.empty()) return run.out(spec).skip(why);
    judge_clocks(run, spec, run.probe<ClockRoles>().generated,
                 [&](NodeId c) { return judge_startup(run, c); });
}

constexpr auto kClock = Category::kClock;
constexpr auto kShall = Strength::kShall;

// The entries judging the Query and the Set exchange.
std::vector<CheckSpec> set_entries() {
    return {
        {"clock.identify-ranges", 711, kClock, "BroadcastTimeS §6.1; EventTransportS §6.2", kShall,
         "a generator identifies the Report, Start/Stop and Date Rollover events it produces and "
         "the Set, Query and Start/Stop events it consumes; not as the two whole-clock ranges "
         "it announces at start-up WARNs",
         "",
         "(the Identify Events addressed answer) for each clock the node generates: events of "
         "every form covered, ideally by Producer and Consumer Range Identified of all 16 bits",
         identify_ranges},
        {"clock.query", 712, kClock, "BroadcastTimeS §6.3, §6.4", kShall,
         "a Query is answered with Producer Identified Valid for Start/Stop, Rate, Year, Date "
         "and Time in this order, then the next minute's Report Time when it becomes valid",
         "bt10",
         "PCER Query: the five items in order, all Valid; item 6 (the minute after item 5's, "
         "before it at a negative rate) when the clock runs and its next minute is within 10 s "
         "(--thorough: 65 s); nothing more while stopped",
         query},
        {"clock.set-immediate", 713, kClock, "BroadcastTimeS §6.5", kShall,
         "a Set Time, Date, Year or Rate takes effect at once and the generator produces the "
         "effective Report",
         "bt30",
         "(--node; the clock's state saved by clock.query) Stop, Set Time 01:23, Set Date 07-22, "
         "Set Year 2023, a second later Set Rate 4.00: each Report within the answer window",
         set_immediate},
        {"clock.set-sync", 714, kClock, "BroadcastTimeS §6.3, §6.5", kShall,
         "three seconds after the last Set the synchronization sequence carries what was set",
         "bt20",
         "(the same Sets) the sequence after the last Set: Stop and the values the Reports gave, "
         "in order",
         set_sync},
        {"clock.set-once", 715, kClock, "BroadcastTimeS §6.5", kShall,
         "the sequence follows three seconds after the last Set, so Sets in a row bring one",
         "bt40",
         "(the same Sets, the last a second after the first) exactly one sequence until 3 s + "
         "two answer windows after the last Set, not before its three seconds",
         set_once},
        {"clock.set-effective", 716, kClock, "BroadcastTimeS §6.5", kShall,
         "the Report a Set produces is the effective value", "",
         "(--node) Set Date 02-30 in 2023, then Query: its Report Date is the date the sequence "
         "then shows",
         set_effective},
    };
}

// The entries judging the run through midnight, the start-up and the restore.
std::vector<CheckSpec> run_entries() {
    return {
        {"clock.requested-minute", 717, kClock, "BroadcastTimeS §6.2", kShall,
         "a generator that received a Consumer Identified for a specific Report Time produces it "
         "when appropriate",
         "bt60",
         "(--node) Consumer Identified Valid for 23:59 and 00:00, then Stop, Set Rate 240.00, Set "
         "Year 2023, Set Date 12-31, Set Time 23:58, Start: Report Time 23:59 and 00:00 come",
         requested_minute},
        {"clock.report-frequency", 718, kClock, "BroadcastTimeS §6.2", kShall,
         "a running generator sends Report Time at most once a real minute, except item 6 of a "
         "sequence and the minutes consumers identified",
         "bt50",
         "(the Set and running exchanges the selected checks made; alone, the Set exchange) no "
         "two Report Time PCERs without such a reason less than a minute apart; the hourly "
         "minimum is not judged (it needs an hour)",
         report_frequency},
        {"clock.rate", 719, kClock, "BroadcastTimeS §5", kShall,
         "a running clock's time advances rate times as fast as real time (a normative "
         "statement of §5)",
         "",
         "(the running exchange, ended by a Query) from Report Time 23:59 to the last Report Time "
         "PCER (item 6 of that Query's sequence): the fast "
         "minutes between them at the rate the clock reported, within 3 % + 50 ms",
         rate},
        {"clock.rollover", 721, kClock, "BroadcastTimeS §5, §6.2", kShall,
         "Date Rollover goes out right before time passes 00:00, Report Year and Report Date "
         "three seconds later, naming the next day",
         "bt70",
         "(the running exchange) Date Rollover, not after Report Time 00:00; Report Year 2024 "
         "and Report Date 01-01 3 s (-0.25 s, + the answer window) after it",
         rollover},
        {"clock.startup", 722, kClock, "BroadcastTimeS §6.1", kShall,
         "a starting generator sends Producer and Consumer Range Identified covering the "
         "clock's 16 bits and the synchronization sequence",
         "bt80",
         "(--reboot `20 A9`, or a start-up seen during the run) after Initialization Complete: "
         "both ranges of all 16 bits, the sequence in order (item 6 as for clock.query)",
         startup},
        {"clock.restored", 723, kClock, "BroadcastTimeS §6.5", kShall,
         "Sets of the saved state take effect, so the clock ends as it was", "",
         "(after each exchange that set the clock; alone, the Set exchange) Stop, Set Rate, Year, "
         "Date and Time "
         "of the state clock.query saved, advanced by the time passed, Start if it ran, then a "
         "Query: its sequence agrees (time within 2 fast minutes)",
         restored},
    };
}

}  // namespace

std::vector<CheckSpec> broadcast_time_checks() {
    std::vector<CheckSpec> all = set_entries();
    for (const CheckSpec& s : run_entries()) all.push_back(s);
    // Clock events are Event Transport messages: a node whose PIP denies Event Exchange has no
    // clock to judge (there is no Broadcast Time bit; ClockRoles decides the rest).
    for (CheckSpec& s : all) s.needs = Protocol::kEventExchange;
    return all;
}

}  // namespace olcb::conform::checks
