// Listening to one clock and reading its synchronization sequence (clock_observer.hpp).
#include "conformance/checks/clock_observer.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "conformance/checks/probes.hpp"

namespace olcb::conform::checks::clocks {

std::string ms_text(Duration d) {
    return std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(d).count()) + " ms";
}

// Real time one fast minute takes at a rate (quarters, non-zero).
Duration fast_minute(int quarters) {
    const auto us = std::int64_t{60'000'000} * 4 / std::max(1, quarters < 0 ? -quarters : quarters);
    return std::chrono::microseconds(us);
}

std::vector<ClockMsg> clock_msgs(Session& s, std::uint16_t alias, std::size_t mark, NodeId clock) {
    std::vector<ClockMsg> out;
    for (const ReceivedMessage& r : s.messages_since(mark)) {
        if (r.message.source.alias != alias) continue;
        const auto id = EventId::from_bytes(r.message.payload);
        if (!id || bt::clock_of(*id) != clock) continue;
        out.push_back({r.message.mti, bt::decode(bt::suffix_of(*id)), r.at, *id});
    }
    return out;
}

// Runs the link until done() holds for the clock's messages since mark, at most `max`.
std::vector<ClockMsg> watch(CheckRun& run, NodeId clock, std::size_t mark, Duration max,
                            const std::function<bool(const std::vector<ClockMsg>&)>& done) {
    Session& s = run.session();
    std::vector<ClockMsg> got;
    s.run_until(
        [&] {
            got = clock_msgs(s, run.alias(), mark, clock);
            return done && done(got);
        },
        max);
    return clock_msgs(s, run.alias(), mark, clock);
}

void send_event(Session& s, Mti mti, NodeId clock, const ClockEvent& e) {
    const auto id = bt::event_id(clock, e);
    if (!id) return;
    Message m;
    m.mti = mti;
    const auto bytes = id->to_bytes();
    m.payload.assign(bytes.begin(), bytes.end());
    s.send(m);
}

bool is_pcer(const ClockMsg& m, Kind k) {
    return m.mti == Mti::kEventReport && m.event.kind == k;
}

bool same_minute(const ClockEvent& e, int hour, int minute) {
    return e.kind == Kind::kReportTime && e.hour == hour && e.minute == minute;
}

std::string Sync::text() const {
    std::string out;
    for (const ClockMsg& m : items) out += (out.empty() ? "" : ", ") + bt::describe(m.event);
    return out;
}

bool opens_sequence(Kind k) {
    return k == Kind::kStart || k == Kind::kStop;
}

namespace {

constexpr Kind kItems[] = {Kind::kStart, Kind::kReportRate, Kind::kReportYear, Kind::kReportDate,
                           Kind::kReportTime};
constexpr const char* kItemNames[] = {"Start or Stop", "Report Rate", "Report Year", "Report Date",
                                      "Report Time"};

void note_value(Sync& s, const ClockEvent& e) {
    switch (e.kind) {
        case Kind::kStart:
        case Kind::kStop:
            s.running = e.kind == Kind::kStart;
            break;
        case Kind::kReportRate:
            s.rate = e.rate_quarters;
            break;
        case Kind::kReportYear:
            s.year = e;
            break;
        case Kind::kReportDate:
            s.date = e;
            break;
        case Kind::kReportTime:
            s.time = e;
            break;
        default:
            break;
    }
}

void judge_order(Sync& s) {
    for (std::size_t k = 0; k < s.items.size(); ++k) {
        const ClockMsg& m = s.items[k];
        const bool fits = k == 0 ? opens_sequence(m.event.kind) : m.event.kind == kItems[k];
        if (!fits) {
            s.problem = "item " + std::to_string(k + 1) + " was " + bt::describe(m.event) +
                        ", expected " + kItemNames[k];
            return;
        }
        if (m.mti != Mti::kProducerIdentifiedValid) {
            s.problem = "item " + std::to_string(k + 1) + " (" + bt::describe(m.event) +
                        ") came as " + std::string(mti_name(m.mti)) +
                        ", not Producer Identified Valid";
            return;
        }
    }
    if (s.items.size() < 5)
        s.problem = "only " + std::to_string(s.items.size()) + " of the 5 Producer Identified " +
                    "items came" + (s.items.empty() ? "" : " (" + s.text() + ")");
}

}  // namespace

// The first sequence from msgs[from] on: the Producer Identified messages of the clock from the
// first one, up to five (a second Start or Stop opens another sequence), then item 6.
Sync read_sync(const std::vector<ClockMsg>& msgs, std::size_t from) {
    Sync s;
    std::size_t i = from;
    while (i < msgs.size() && !is_producer_identified(msgs[i].mti)) ++i;
    for (; i < msgs.size() && s.items.size() < 5; ++i) {
        const ClockMsg& m = msgs[i];
        if (!is_producer_identified(m.mti)) continue;
        if (!s.items.empty() && opens_sequence(m.event.kind)) break;
        s.items.push_back(m);
        note_value(s, m.event);
    }
    judge_order(s);
    for (; s.items.size() == 5 && i < msgs.size(); ++i) {
        if (is_pcer(msgs[i], Kind::kReportTime)) {
            s.next = msgs[i];
            break;
        }
    }
    return s;
}

// Every sequence in msgs, in order.
std::vector<Sync> read_syncs(const std::vector<ClockMsg>& msgs) {
    std::vector<Sync> out;
    for (std::size_t i = 0; i < msgs.size(); ++i) {
        if (!is_producer_identified(msgs[i].mti) || !opens_sequence(msgs[i].event.kind)) continue;
        out.push_back(read_sync(msgs, i));
    }
    return out;
}

// The Report Time item 6 must carry: the minute after item 5's (before it when time runs back).
ClockEvent next_minute(const Sync& s) {
    int of_day = s.time.hour * 60 + s.time.minute + (s.rate < 0 ? -1 : 1);
    of_day = (of_day + 24 * 60) % (24 * 60);
    return ClockEvent::report_time(of_day / 60, of_day % 60);
}

// "" when item 6 is right (or not owed: the clock is stopped), else what is wrong.
std::string judge_next(const Sync& s, bool awaited, Duration waited) {
    if (!s.running || s.rate == 0) {
        return s.next ? "item 6 (" + bt::describe(s.next->event) +
                            ") came, the clock being "
                            "stopped"
                      : "";
    }
    if (!s.next)
        return awaited
                   ? "item 6, the next minute's Report Time, did not come within " + ms_text(waited)
                   : "";
    const ClockEvent want = next_minute(s);
    if (s.next->event != want)
        return "item 6 was " + bt::describe(s.next->event) + ", expected " + bt::describe(want);
    return "";
}

std::optional<FastTime> fast_time_of(const Sync& s) {
    const std::chrono::year_month_day ymd{std::chrono::year{s.year.year},
                                          std::chrono::month{s.date.month},
                                          std::chrono::day{s.date.day}};
    if (!ymd.ok()) return std::nullopt;
    return FastTime{std::chrono::sys_days{ymd}} + std::chrono::hours(s.time.hour) +
           std::chrono::minutes(s.time.minute);
}

// The fast time a clock announcing s at `at` shows at `now`.
FastTime advance(FastTime t, const Sync& s, TimePoint at, TimePoint now) {
    if (!s.running) return t;
    const auto real = std::chrono::duration_cast<std::chrono::microseconds>(now - at).count();
    return t + std::chrono::microseconds(real * s.rate / 4);
}

Fields fields_of(FastTime t) {
    const auto day = std::chrono::floor<std::chrono::days>(t);
    const std::chrono::year_month_day ymd{day};
    const std::chrono::hh_mm_ss<std::chrono::microseconds> hms{t - day};
    return {static_cast<int>(ymd.year()), static_cast<int>(static_cast<unsigned>(ymd.month())),
            static_cast<int>(static_cast<unsigned>(ymd.day())),
            static_cast<int>(hms.hours().count()), static_cast<int>(hms.minutes().count())};
}

int minutes_between(const ClockEvent& a, const ClockEvent& b) {
    const int day = 24 * 60;
    return ((b.hour * 60 + b.minute) - (a.hour * 60 + a.minute) + day) % day;
}

}  // namespace olcb::conform::checks::clocks
