// The exchanges the clock checks judge (clock_probe.hpp): Query, the Set exchange, the run
// through midnight, the saved state set back, the start-up.
#include "conformance/checks/clock_probe.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "base/hex.hpp"
#include "conformance/checks/clock_roles.hpp"

namespace olcb::conform::checks::clocks {

using namespace std::chrono_literals;

namespace {

// The rate a clock is run through midnight at: a fast minute per quarter of a real second, so
// the run lasts little more than the three seconds Report Year and Date follow the rollover by.
constexpr int kRunQuarters = 960;
// The longest running exchange (a clock that only takes slow rates is not run).
constexpr Duration kMaxRun = 150s;
// How long item 6 of a sequence is awaited (the next minute of a 1x clock is up to 60 s away).
constexpr Duration kNextMinuteWait = 10s;
constexpr Duration kNextMinuteWaitThorough = 65s;

Duration next_minute_bound(CheckRun& run) {
    return run.options().selection.thorough ? kNextMinuteWaitThorough : kNextMinuteWait;
}

}  // namespace

Sync await_next(CheckRun& run, NodeId clock, std::size_t mark, Sync sync, bool& awaited,
                Duration& waited) {
    awaited = false;
    if (!sync.complete() || !sync.running || sync.rate == 0 || sync.next) return sync;
    waited = fast_minute(sync.rate) + answer_window(run);
    if (waited > next_minute_bound(run)) return sync;
    awaited = true;
    const auto msgs = watch(run, clock, mark, waited, [](const std::vector<ClockMsg>& m) {
        return read_sync(m).next.has_value();
    });
    return read_sync(msgs);
}

ClockQuery ClockQuery::ask(CheckRun& run, Key key) {
    const NodeId clock{key};
    Session& s = run.session();
    ClockQuery q;
    const std::size_t mark = s.message_mark();
    q.sent = s.link().now();
    send_event(s, Mti::kEventReport, clock, ClockEvent::of(Kind::kQuery));
    const auto msgs =
        watch(run, clock, mark, 2 * answer_window(run),
              [](const std::vector<ClockMsg>& m) { return read_sync(m).items.size() == 5; });
    q.sync = await_next(run, clock, mark, read_sync(msgs), q.next_awaited, q.next_wait);
    return q;
}

const ClockQuery& query_of(CheckRun& run, NodeId clock) {
    return run.probe<ClockQuery>(clock.value());
}

namespace {

// Sends a Set (or Start/Stop) and waits for its Report for at most the answer window when
// `wait`; the Report of an earlier Set of the same form is not taken for it.
Echo set_and_echo(CheckRun& run, NodeId clock, const ClockEvent& set) {
    Session& s = run.session();
    const std::size_t mark = s.message_mark();
    const TimePoint sent = s.link().now();
    send_event(s, Mti::kEventReport, clock, set);
    Echo e{set, std::nullopt, {}};
    if (!bt::is_set(set.kind)) return e;
    const Kind report = set.as_report().kind;
    const auto msgs = watch(run, clock, mark, answer_window(run), [&](const auto& m) {
        return std::any_of(m.begin(), m.end(),
                           [&](const ClockMsg& c) { return is_pcer(c, report); });
    });
    for (const ClockMsg& m : msgs) {
        if (!is_pcer(m, report)) continue;
        e.got = m.event;
        e.after = m.at - sent;
        break;
    }
    return e;
}

void set_exchange(CheckRun& run, NodeId clock, SetSession& c) {
    Session& s = run.session();
    const std::size_t mark = s.message_mark();
    c.first_set = s.link().now();
    set_and_echo(run, clock, ClockEvent::of(Kind::kStop));
    for (const ClockEvent& e :
         {ClockEvent::report_time(1, 23).as_set(), ClockEvent::report_date(7, 22).as_set(),
          ClockEvent::report_year(2023).as_set()})
        c.echoes.push_back(set_and_echo(run, clock, e));
    // A second later, the last Set: the sequence is owed three seconds after it, not the first.
    s.wait(std::max<Duration>(0s, c.first_set + 1s - s.link().now()));
    c.last_set = s.link().now();
    c.echoes.push_back(set_and_echo(run, clock, ClockEvent::report_rate(16).as_set()));
    const TimePoint until = c.last_set + kSettle + 2 * answer_window(run);
    c.set_msgs = watch(run, clock, mark, until - s.link().now(), [&](const auto& m) {
        const auto syncs = read_syncs(m);
        return std::any_of(syncs.begin(), syncs.end(), [&](const Sync& y) {
            return y.at() >= c.last_set + kSettle - kEarly && y.items.size() == 5;
        });
    });
    // A little longer: a second sequence would show here.
    s.wait(answer_window(run) / 2);
    c.set_msgs = clock_msgs(s, run.alias(), mark, clock);
    c.set_end = s.link().now();
}

void odd_date_exchange(CheckRun& run, NodeId clock, SetSession& c) {
    Session& s = run.session();
    c.odd_date = set_and_echo(run, clock, ClockEvent::report_date(2, 30).as_set());
    const std::size_t mark = s.message_mark();
    send_event(s, Mti::kEventReport, clock, ClockEvent::of(Kind::kQuery));
    const auto msgs = watch(run, clock, mark, 2 * answer_window(run),
                            [](const auto& m) { return read_sync(m).items.size() == 5; });
    c.odd_sync = read_sync(msgs);
}

// A Query at the end of the run: item 6 of its sequence marks a minute boundary as exactly as
// Report Time 23:59 did, a dozen fast minutes later, which is what clock.rate measures.
void end_with_query(CheckRun& run, NodeId clock, const RunSeen& seen) {
    Session& s = run.session();
    const std::size_t mark = s.message_mark();
    send_event(s, Mti::kEventReport, clock, ClockEvent::of(Kind::kQuery));
    watch(run, clock, mark, fast_minute(seen.rate) + 2 * answer_window(run),
          [](const std::vector<ClockMsg>& m) { return read_sync(m).next.has_value(); });
}

// Asks for the reports of 23:59 and 00:00 as a display would, then runs the clock from
// 2023-12-31 23:58 at a fast minute per quarter second; watches until Report Year and Date
// follow the rollover (or the time the rate gives has passed), then ends with a Query.
void run_exchange(CheckRun& run, NodeId clock, RunSeen& seen) {
    Session& s = run.session();
    const std::size_t mark = s.message_mark();
    for (const ClockEvent& e : {ClockEvent::report_time(23, 59), ClockEvent::report_time(0, 0)})
        send_event(s, Mti::kConsumerIdentifiedValid, clock, e);
    set_and_echo(run, clock, ClockEvent::of(Kind::kStop));
    const Echo rate = set_and_echo(run, clock, ClockEvent::report_rate(kRunQuarters).as_set());
    set_and_echo(run, clock, ClockEvent::report_year(2023).as_set());
    set_and_echo(run, clock, ClockEvent::report_date(12, 31).as_set());
    set_and_echo(run, clock, ClockEvent::report_time(23, 58).as_set());
    seen.rate = rate.got ? rate.got->rate_quarters : kRunQuarters;
    if (seen.rate <= 0) {
        seen.not_run = "Set Rate " + bt::rate_text(kRunQuarters) + " left the rate at " +
                       bt::rate_text(seen.rate) + ": the clock would not run forward";
        return;
    }
    const Duration span = 2 * fast_minute(seen.rate) + kSettle + 2 * answer_window(run);
    if (span > kMaxRun) {
        seen.not_run = "at the rate the clock took (" + bt::rate_text(seen.rate) +
                       ") two fast minutes last too long";
        return;
    }
    seen.started = s.link().now();
    send_event(s, Mti::kEventReport, clock, ClockEvent::of(Kind::kStart));
    seen.msgs = watch(run, clock, mark, span, [&](const std::vector<ClockMsg>& m) {
        const auto roll = std::find_if(
            m.begin(), m.end(), [](const ClockMsg& x) { return is_pcer(x, Kind::kDateRollover); });
        return roll != m.end() &&
               std::any_of(roll, m.end(),
                           [](const ClockMsg& x) { return is_pcer(x, Kind::kReportYear); }) &&
               std::any_of(roll, m.end(),
                           [](const ClockMsg& x) { return is_pcer(x, Kind::kReportDate); });
    });
    end_with_query(run, clock, seen);
    seen.msgs = clock_msgs(s, run.alias(), mark, clock);
}

// The Sets that put the saved state back, its time advanced by the real time passed at its rate.
std::string set_back(CheckRun& run, NodeId clock, const ClockQuery& saved, FastTime t) {
    Session& s = run.session();
    const Sync& was = saved.sync;
    const Fields f = fields_of(advance(t, was, saved.sent, s.link().now()));
    for (const ClockEvent& e :
         {ClockEvent::of(Kind::kStop), ClockEvent::report_rate(was.rate).as_set(),
          ClockEvent::report_year(f.year).as_set(),
          ClockEvent::report_date(f.month, f.day).as_set(),
          ClockEvent::report_time(f.hour, f.minute).as_set()})
        send_event(s, Mti::kEventReport, clock, e);
    if (was.running) send_event(s, Mti::kEventReport, clock, ClockEvent::of(Kind::kStart));
    char buf[80];
    std::snprintf(buf, sizeof buf, "%04d-%02d-%02d %02d:%02d, rate %s, %s", f.year, f.month, f.day,
                  f.hour, f.minute, bt::rate_text(was.rate).c_str(),
                  was.running ? "running" : "stopped");
    return buf;
}

// Sets the saved state back and asks a Query whether the clock took it.
Restore put_back(CheckRun& run, NodeId clock) {
    const ClockQuery& saved = query_of(run, clock);
    const Sync& was = saved.sync;
    Restore r;
    const auto t = fast_time_of(was);
    if (!t) return r;
    r.to = set_back(run, clock, saved, *t);
    Session& s = run.session();
    s.wait(run.options().window);
    const std::size_t mark = s.message_mark();
    send_event(s, Mti::kEventReport, clock, ClockEvent::of(Kind::kQuery));
    const auto msgs = watch(run, clock, mark, 2 * answer_window(run),
                            [](const auto& m) { return read_sync(m).items.size() == 5; });
    const Sync now = read_sync(msgs);
    const auto back = fast_time_of(now);
    if (now.items.size() < 5 || !back) {
        r.problem = "a Query then got " + (now.started() ? now.text() : std::string("nothing"));
        return r;
    }
    const FastTime want = advance(*t, was, saved.sent, now.at());
    const auto off = *back > want ? *back - want : want - *back;
    if (now.running != was.running || now.rate != was.rate || off > std::chrono::minutes(2))
        r.problem = "a Query then showed " + now.text();
    return r;
}

// Why a session may not set this clock ("" when it may): its state must be saved first.
std::string unsaved(CheckRun& run, NodeId clock) {
    const ClockQuery& saved = query_of(run, clock);
    if (saved.sync.items.size() == 5 && fast_time_of(saved.sync)) return "";
    return "the clock's state could not be saved (Query: " +
           (saved.sync.started() ? saved.sync.text() : std::string("no sequence")) +
           "), so nothing was set";
}
}  // namespace

SetSession SetSession::ask(CheckRun& run, Key key) {
    const NodeId clock{key};
    SetSession c;
    c.not_run = unsaved(run, clock);
    if (!c.not_run.empty()) return c;
    set_exchange(run, clock, c);
    odd_date_exchange(run, clock, c);
    c.restore = put_back(run, clock);
    return c;
}

RunSession RunSession::ask(CheckRun& run, Key key) {
    const NodeId clock{key};
    RunSession c;
    c.not_run = unsaved(run, clock);
    if (!c.not_run.empty()) return c;
    run_exchange(run, clock, c.run);
    c.restore = put_back(run, clock);
    return c;
}

const SetSession& set_session(CheckRun& run, NodeId clock) {
    return run.probe<SetSession>(clock.value());
}

const RunSession& run_session(CheckRun& run, NodeId clock) {
    return run.probe<RunSession>(clock.value());
}

std::string SessionsMade::not_run() const {
    if (set && set->not_run.empty()) return "";
    if (running && running->not_run.empty()) return "";
    return set ? set->not_run : running ? running->not_run : "no session set the clock";
}

SessionsMade sessions_made(CheckRun& run, NodeId clock) {
    SessionsMade made{run.asked<SetSession>(clock.value()), run.asked<RunSession>(clock.value())};
    if (!made.set && !made.running) made.set = &set_session(run, clock);
    return made;
}

Startup Startup::ask(CheckRun& run) {
    Session& s = run.session();
    auto find = [&]() -> std::optional<std::size_t> {
        const auto all = s.messages_since(0);
        for (std::size_t i = all.size(); i-- > 0;) {
            const Message& m = all[i].message;
            if ((m.mti == Mti::kInitializationComplete ||
                 m.mti == Mti::kInitializationCompleteSimple) &&
                NodeId::from_bytes(m.payload) == run.node().id)
                return i;
        }
        return std::nullopt;
    };
    if (auto at = find()) return {at, ""};
    if (!run.options().reboot) return {};
    const NodeId id = run.node().id;
    const std::uint32_t before = s.track(id).reservations;
    static constexpr std::uint8_t kReset[] = {0x20, 0xA9};
    const MemResult r = s.command(run.node(), kReset);
    // A node may refuse to restart (OpenMRN on Linux: 0x1041); then no start-up is coming.
    if (r.rejected && !r.timed_out && r.error != 0 && !find())
        return {std::nullopt, "Reset/Reboot rejected with " + base::hex(r.error, 4) +
                                  ": the start-up was not observed"};
    s.run_until([&] { return find().has_value(); }, 10s);
    const std::uint32_t after = s.track(id).reservations;
    if (after > before) s.excuse_reservations(id, after - before);
    return {find(), ""};
}

std::string startup_gate(CheckRun& run) {
    const Startup& st = run.probe<Startup>();
    if (st.mark) return "";
    if (!st.refused.empty()) return st.refused;
    return run.options().reboot ? "no Initialization Complete within 10 s of Reset/Reboot"
                                : "needs --reboot (sends Reset/Reboot), or the node starting "
                                  "while lcc-conform runs";
}

}  // namespace olcb::conform::checks::clocks
