// One Broadcast Time clock of a simulated node (BroadcastTimeS), sans-I/O: told the time and the
// messages of the segment, it says what to send (a Send callback) and when it next has work
// (next_deadline(), then poll()). A generator keeps fast time running at its rate, reports it
// (§6.2), answers Query with the synchronization sequence (§6.3, §6.4) and obeys Set, Start and
// Stop (§6.5); a consumer (a clock display) announces the clock's range, asks for the time at
// start-up and follows what generators send. The faults change a clock through ClockQuirks only.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>

#include "openlcb/broadcast_time.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/message.hpp"

namespace olcb::simnode {

/// A clock's own time: a proleptic Gregorian instant (years 0..4095 on the wire), in µs.
using FastTime = std::chrono::sys_time<std::chrono::microseconds>;

/// Fast time of a calendar minute.
FastTime fast_time(int year, unsigned month, unsigned day, int hour, int minute);

/// "2023-07-22 01:23" (seconds dropped).
std::string fast_time_text(FastTime t);

/// "YYYY-MM-DDTHH:MM" (or with a space instead of T) to fast time; nullopt when malformed, not
/// a real date or outside years 0..4095.
std::optional<FastTime> parse_fast_time(std::string_view text);

/// What a clock is.
enum class ClockRole : std::uint8_t {
    kGenerator,  ///< the clock generator (a fast clock master)
    kConsumer,   ///< a clock consumer that tracks the time (a display)
};

/// A clock as a scenario describes it.
struct ClockConfig {
    ClockRole role = ClockRole::kGenerator;
    NodeId clock = broadcast_time::kDefaultFastClock;  ///< its 6-byte Specific Upper Part
    FastTime start = fast_time(1970, 1, 1, 0, 0);      ///< fast time at first start-up
    std::int16_t rate_quarters = 4;                    ///< 1.00
    bool running = true;

    friend bool operator==(const ClockConfig&, const ClockConfig&) = default;
};

/// A clock as the scenario key `clock` gives it (docs/scenarios.md): "ROLE [CLOCK] [rate=R]
/// [time=YYYY-MM-DDTHH:MM|now] [stopped|running]", ROLE generator or consumer, CLOCK one of
/// default-fast (the default), default-realtime, alternate-1, alternate-2 or a 6-byte ID;
/// `now` is wall_now (UTC). nullopt with a sentence in error when malformed.
std::optional<ClockConfig> parse_clock_config(std::string_view text, FastTime wall_now,
                                              std::string& error);
/// The text parse_clock_config() reads back as config.
std::string clock_config_text(const ClockConfig& config);

/// How a clock breaks the standard (set by the faults' clock hook; docs/faults.md).
struct ClockQuirks {
    /// Fast time runs this many percent faster than the rate it reports (0: true to it).
    int drift_percent = 0;
    bool ignores_query = false;  ///< a Query gets no synchronization sequence
    /// Its Consumer Range Identified covers only the upper half (Set, Query, Start/Stop), as
    /// OpenMRN's BroadcastTimeServer announces it.
    bool half_consumer_range = false;
    /// A Set is reported as asked, not as the clock took it (Set Date 02-30: Report Date 02-30
    /// while the clock went to a real date), as OpenMRN's BroadcastTimeServer does.
    bool reports_asked = false;
    bool sync_out_of_order = false;  ///< the sequence sends Time, Date, Year for Year, Date, Time
    /// What goes wrong at 00:00.
    enum class Rollover : std::uint8_t {
        kRight,      ///< as the standard says
        kYearKept,   ///< Dec 31 is followed by Jan 1 of the same year
        kDateKept,   ///< the date does not advance at midnight
        kEventLate,  ///< Date Rollover after the 00:00 Report Time, not before it
    } rollover = Rollover::kRight;

    friend bool operator==(const ClockQuirks&, const ClockQuirks&) = default;
};

/// One clock.
class BroadcastClock {
public:
    /// Sends one message from the node.
    using Send = std::function<void(Message)>;

    explicit BroadcastClock(ClockConfig config, ClockQuirks quirks = {});

    /// The node sent Initialization Complete: the ranges of §6.1, then a generator's
    /// synchronization sequence, a consumer's Query.
    void started(TimePoint now, const Send& send);
    /// Identify Events (global, or addressed to the node): the clock's ranges.
    void identify(const Send& send) const;
    /// A message of the segment (from another node).
    void on_message(const Message& msg, TimePoint now, const Send& send);
    /// Does what is due at now (call at next_deadline()).
    void poll(TimePoint now, const Send& send);
    /// When poll() next has work; nullopt when never.
    std::optional<TimePoint> next_deadline() const;

    /// The fast time at now.
    FastTime time_at(TimePoint now) const;
    std::int16_t rate_quarters() const { return rate_; }
    bool running() const { return running_; }
    const ClockConfig& config() const { return config_; }
    NodeId clock() const { return config_.clock; }
    /// Report Time minutes (hour * 60 + minute) some consumer identified.
    const std::set<int>& subscribed() const { return subscribed_; }

private:
    using Event = broadcast_time::ClockEvent;

    void send_event(const Send& send, Mti mti, const Event& event) const;
    void send_sync(TimePoint now, const Send& send);
    void minute_tick(TimePoint now, const Send& send);
    void roll_over(TimePoint now, bool forward, const Send& send);
    void report_time(TimePoint now, const Send& send);
    void apply_set(const Event& event, TimePoint now, const Send& send);
    void follow(const Event& event, bool instant, TimePoint now);
    void answer_identify(const Message& msg, const Event& event, const Send& send) const;
    void rebase(TimePoint now, FastTime t);
    Event current(broadcast_time::Kind kind, TimePoint now) const;

    ClockConfig config_;
    ClockQuirks quirks_;
    FastTime base_fast_;  // the fast time at base_real_
    TimePoint base_real_{};
    std::int16_t rate_;
    bool running_;
    std::chrono::sys_time<std::chrono::minutes> shown_;  // the minute last seen by minute_tick
    std::optional<TimePoint> sync_due_;                  // a synchronization sequence to send
    std::optional<TimePoint> rollover_due_;              // Report Year and Date after a rollover
    std::optional<TimePoint> last_report_;               // the last Report Time PCER sent
    bool next_minute_due_ = false;                       // the sequence's item 6 is still to come
    bool rollover_seen_ = false;  // consumer: a Date Rollover since the last 00:00
    bool ever_started_ = false;
    std::set<int> subscribed_;
};

}  // namespace olcb::simnode
