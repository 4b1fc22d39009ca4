// Broadcast Time (BroadcastTimeS/TN) wire facts in one place: the well-known clock IDs, the
// layout of a clock's 65,536 event IDs (its 6-byte "Specific Upper Part" and a 16-bit suffix
// whose byte 6 says the form), and their codec. A clock generator produces the Report forms and
// consumes the Set forms, Query and Start/Stop; Set = Report + 0x8000 (TN §2.4.5-2.4.8).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "base/node_id.hpp"

namespace olcb::broadcast_time {

/// "Default Fast Clock" (BroadcastTimeS §4).
inline constexpr NodeId kDefaultFastClock{0x0101'0000'0100ull};
/// "Default Real-time Clock".
inline constexpr NodeId kDefaultRealTimeClock{0x0101'0000'0101ull};
/// "Alternate Clock 1".
inline constexpr NodeId kAlternateClock1{0x0101'0000'0102ull};
/// "Alternate Clock 2".
inline constexpr NodeId kAlternateClock2{0x0101'0000'0103ull};

/// Set forms are their Report form plus this (Set Time 0x80+hour = Report Time 0x00+hour).
inline constexpr std::uint16_t kSetOffset = 0x8000;
/// Query (§4.9): the generator answers with the synchronization sequence (§6.3, §6.4).
inline constexpr std::uint16_t kQuerySuffix = 0xF000;
/// Stop (§4.10).
inline constexpr std::uint16_t kStopSuffix = 0xF001;
/// Start (§4.10).
inline constexpr std::uint16_t kStartSuffix = 0xF002;
/// Date Rollover (§4.11): sent right before time passes through 00:00 (§6.2).
inline constexpr std::uint16_t kDateRolloverSuffix = 0xF003;

/// Rate in quarters: 12-bit signed fixed point rrrrrrrrrr.rr (§4.4), -512.00 to 511.75.
inline constexpr std::int16_t kMinRateQuarters = -2048;
inline constexpr std::int16_t kMaxRateQuarters = 2047;
/// Years 0 to 4095 AD (§4.3).
inline constexpr std::uint16_t kMaxYear = 4095;

/// What one suffix of a clock's event IDs means.
enum class Kind : std::uint8_t {
    kReportTime,    ///< 0x00hh mm (§4.1)
    kReportDate,    ///< 0x2M dd (§4.2)
    kReportYear,    ///< 0x3yyy (§4.3)
    kReportRate,    ///< 0x4rrr (§4.4)
    kSetTime,       ///< 0x80+hh mm (§4.5)
    kSetDate,       ///< 0xA0+M dd (§4.6)
    kSetYear,       ///< 0xByyy (§4.7)
    kSetRate,       ///< 0xCrrr (§4.8)
    kQuery,         ///< 0xF000 (§4.9)
    kStop,          ///< 0xF001 (§4.10)
    kStart,         ///< 0xF002 (§4.10)
    kDateRollover,  ///< 0xF003 (§4.11)
    kReserved,      ///< every other suffix: never sent, ignored when received (§4.12)
};

/// One clock event's meaning, decoded. Only the fields of its kind are set.
struct ClockEvent {
    Kind kind = Kind::kReserved;
    std::uint8_t hour = 0;            ///< time forms: 0..23
    std::uint8_t minute = 0;          ///< time forms: 0..59
    std::uint8_t month = 0;           ///< date forms: 1..12
    std::uint8_t day = 0;             ///< date forms: 1..31
    std::uint16_t year = 0;           ///< year forms: 0..4095
    std::int16_t rate_quarters = 0;   ///< rate forms: -2048..2047 (quarters of real time)
    std::uint16_t reserved_code = 0;  ///< kReserved: the suffix as received

    static ClockEvent report_time(int hour, int minute);
    static ClockEvent report_date(int month, int day);
    static ClockEvent report_year(int year);
    static ClockEvent report_rate(int quarters);
    /// The Set form of a Report form (any other kind unchanged).
    ClockEvent as_set() const;
    /// The Report form of a Set form (any other kind unchanged).
    ClockEvent as_report() const;
    /// A kind without fields.
    static ClockEvent of(Kind kind);

    friend bool operator==(const ClockEvent&, const ClockEvent&) = default;
};

/// True for the four Report forms (what a generator produces and identifies).
constexpr bool is_report(Kind k) {
    return k == Kind::kReportTime || k == Kind::kReportDate || k == Kind::kReportYear ||
           k == Kind::kReportRate;
}
/// True for the four Set forms.
constexpr bool is_set(Kind k) {
    return k == Kind::kSetTime || k == Kind::kSetDate || k == Kind::kSetYear || k == Kind::kSetRate;
}

/// Meaning of a suffix (the event ID's low 16 bits); fields out of their ranges (hour 24,
/// minute 60, month 0 or 13, day 0 or 32) make it kReserved.
ClockEvent decode(std::uint16_t suffix);
/// The suffix of an event; nullopt for kReserved or a field out of its range.
std::optional<std::uint16_t> encode(const ClockEvent& event);

/// The clock an event ID belongs to: its upper six bytes.
constexpr NodeId clock_of(EventId id) {
    return NodeId{id.value() >> 16};
}
/// The low 16 bits of an event ID.
constexpr std::uint16_t suffix_of(EventId id) {
    return static_cast<std::uint16_t>(id.value() & 0xFFFF);
}
/// The event ID of one suffix of a clock.
constexpr EventId event_id(NodeId clock, std::uint16_t suffix) {
    return EventId(clock, suffix);
}
/// The event ID of an event of a clock; nullopt when it does not encode.
std::optional<EventId> event_id(NodeId clock, const ClockEvent& event);
/// The range ID covering all 65,536 event IDs of a clock (what §6.1's ranges carry).
EventId whole_range(NodeId clock);
/// True when range (a Range Identified event ID) covers every event ID of clock.
bool covers_whole_clock(EventId range, NodeId clock);

/// The rate of `quarters` as text: "4.00", "-0.25".
std::string rate_text(int quarters);
/// Rate text "4", "4.5", "-0.25" to quarters; nullopt unless a multiple of 0.25 in range.
std::optional<std::int16_t> parse_rate(std::string_view text);
/// The event in words: "Report Time 01:23", "Set Date 07-22", "Report Rate 4.00", "Query",
/// "reserved 0x5000".
std::string describe(const ClockEvent& event);
/// The clock's name: "Default Fast Clock" and the like for the four well-known IDs, else its
/// dotted ID.
std::string clock_name(NodeId clock);

}  // namespace olcb::broadcast_time
