// Listening to one Broadcast Time clock (BroadcastTimeS): the node's messages of a clock, the
// synchronization sequence (§6.3) read from them, and fast-time arithmetic. Shared by the
// clock probes (clock_probe) and the clock checks (broadcast_time_checks, clock_consumer_checks).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "conformance/checks/check_run.hpp"
#include "openlcb/broadcast_time.hpp"

namespace olcb::conform::checks::clocks {

namespace bt = olcb::broadcast_time;
using bt::ClockEvent;
using bt::Kind;

/// The synchronization sequence follows the last Set, and Report Year and Date follow a
/// rollover, by three seconds (§6.2, §6.5).
inline constexpr Duration kSettle = std::chrono::seconds(3);
/// A sequence or report this much before its three seconds is early (timers are coarse).
inline constexpr Duration kEarly = std::chrono::milliseconds(250);
/// Timer jitter allowed on top of a computed time.
inline constexpr Duration kJitter = std::chrono::milliseconds(50);

/// "1234 ms".
std::string ms_text(Duration d);
/// Real time one fast minute takes at a rate (quarters, non-zero).
Duration fast_minute(int quarters);

/// One message of the node carrying an event of the clock.
struct ClockMsg {
    Mti mti;
    ClockEvent event;
    TimePoint at;
    EventId id;  ///< as sent (a range's ID too)
};

/// The node's (alias) messages of the clock since mark.
std::vector<ClockMsg> clock_msgs(Session& s, std::uint16_t alias, std::size_t mark, NodeId clock);
/// Runs the link until done() holds for the clock's messages since mark, at most `max`.
std::vector<ClockMsg> watch(CheckRun& run, NodeId clock, std::size_t mark, Duration max,
                            const std::function<bool(const std::vector<ClockMsg>&)>& done);
/// Sends one of the clock's events as mti (PCER, Identified, Identify Consumer).
void send_event(Session& s, Mti mti, NodeId clock, const ClockEvent& e);
/// A PCER of that kind.
bool is_pcer(const ClockMsg& m, Kind k);
/// A Report Time of hour:minute.
bool same_minute(const ClockEvent& e, int hour, int minute);
/// Start or Stop: what opens a sequence.
bool opens_sequence(Kind k);

/// One synchronization sequence as the node sent it.
struct Sync {
    std::vector<ClockMsg> items;   ///< its Producer Identified messages, at most five
    std::string problem;           ///< why it is not items 1-5 in order ("" when it is)
    std::optional<ClockMsg> next;  ///< item 6: the next Report Time PCER after item 5
    // The state it announced, each value from the item of its kind.
    bool running = false;
    int rate = 0;
    ClockEvent year, date, time;

    bool started() const { return !items.empty(); }
    bool complete() const { return items.size() == 5 && problem.empty(); }
    TimePoint at() const { return items.empty() ? TimePoint{} : items.front().at; }
    /// "Stop, Rate 4.00, Year 2023, Date 07-22, Time 01:23".
    std::string text() const;
};

/// The first sequence from msgs[from] on: the Producer Identified messages of the clock from
/// the first one, up to five (a second Start or Stop opens another sequence), then item 6.
Sync read_sync(const std::vector<ClockMsg>& msgs, std::size_t from = 0);
/// Every sequence in msgs, in order.
std::vector<Sync> read_syncs(const std::vector<ClockMsg>& msgs);
/// The Report Time item 6 must carry: the minute after item 5's (before it when time runs back).
ClockEvent next_minute(const Sync& s);
/// "" when item 6 is right (or not owed: the clock is stopped), else what is wrong.
std::string judge_next(const Sync& s, bool awaited, Duration waited);

/// A fast date and time.
using FastTime = std::chrono::sys_time<std::chrono::microseconds>;
/// The date and time a sequence announced (nullopt: no valid date).
std::optional<FastTime> fast_time_of(const Sync& s);
/// The fast time a clock announcing s at `at` shows at `now`.
FastTime advance(FastTime t, const Sync& s, TimePoint at, TimePoint now);

struct Fields {
    int year, month, day, hour, minute;
};
Fields fields_of(FastTime t);
/// Fast minutes from a to b, forward through midnight.
int minutes_between(const ClockEvent& a, const ClockEvent& b);

}  // namespace olcb::conform::checks::clocks
