#include "openlcb/broadcast_time.hpp"

#include <charconv>
#include <cstdio>

#include "openlcb/event_range.hpp"

namespace olcb::broadcast_time {
namespace {

constexpr std::uint16_t kFormMask = 0xF000;
constexpr std::uint16_t kValueMask = 0x0FFF;

ClockEvent reserved(std::uint16_t suffix) {
    ClockEvent e;
    e.reserved_code = suffix;
    return e;
}

ClockEvent time_form(Kind kind, std::uint16_t suffix) {
    const int hour = (suffix >> 8) & 0x7F;
    const int minute = suffix & 0xFF;
    if (hour > 23 || minute > 59) return reserved(suffix);
    ClockEvent e = ClockEvent::report_time(hour, minute);
    e.kind = kind;
    return e;
}

ClockEvent date_form(Kind kind, std::uint16_t suffix) {
    const int month = (suffix >> 8) & 0x0F;
    const int day = suffix & 0xFF;
    if (month < 1 || month > 12 || day < 1 || day > 31) return reserved(suffix);
    ClockEvent e = ClockEvent::report_date(month, day);
    e.kind = kind;
    return e;
}

std::int16_t signed_rate(std::uint16_t suffix) {
    const int v = suffix & kValueMask;
    return static_cast<std::int16_t>((v & 0x800) != 0 ? v - 0x1000 : v);
}

ClockEvent value_form(Kind kind, std::uint16_t suffix) {
    ClockEvent e;
    e.kind = kind;
    if (kind == Kind::kReportYear || kind == Kind::kSetYear)
        e.year = static_cast<std::uint16_t>(suffix & kValueMask);
    else
        e.rate_quarters = signed_rate(suffix);
    return e;
}

ClockEvent special(std::uint16_t suffix) {
    switch (suffix) {
        case kQuerySuffix:
            return ClockEvent::of(Kind::kQuery);
        case kStopSuffix:
            return ClockEvent::of(Kind::kStop);
        case kStartSuffix:
            return ClockEvent::of(Kind::kStart);
        case kDateRolloverSuffix:
            return ClockEvent::of(Kind::kDateRollover);
        default:
            return reserved(suffix);
    }
}

std::uint16_t two_bytes(int high, int low) {
    return static_cast<std::uint16_t>((high << 8) | low);
}

}  // namespace

ClockEvent ClockEvent::report_time(int hour, int minute) {
    ClockEvent e;
    e.kind = Kind::kReportTime;
    e.hour = static_cast<std::uint8_t>(hour);
    e.minute = static_cast<std::uint8_t>(minute);
    return e;
}

ClockEvent ClockEvent::report_date(int month, int day) {
    ClockEvent e;
    e.kind = Kind::kReportDate;
    e.month = static_cast<std::uint8_t>(month);
    e.day = static_cast<std::uint8_t>(day);
    return e;
}

ClockEvent ClockEvent::report_year(int year) {
    ClockEvent e;
    e.kind = Kind::kReportYear;
    e.year = static_cast<std::uint16_t>(year);
    return e;
}

ClockEvent ClockEvent::report_rate(int quarters) {
    ClockEvent e;
    e.kind = Kind::kReportRate;
    e.rate_quarters = static_cast<std::int16_t>(quarters);
    return e;
}

ClockEvent ClockEvent::of(Kind kind) {
    ClockEvent e;
    e.kind = kind;
    return e;
}

ClockEvent ClockEvent::as_set() const {
    ClockEvent e = *this;
    switch (kind) {
        case Kind::kReportTime:
            e.kind = Kind::kSetTime;
            break;
        case Kind::kReportDate:
            e.kind = Kind::kSetDate;
            break;
        case Kind::kReportYear:
            e.kind = Kind::kSetYear;
            break;
        case Kind::kReportRate:
            e.kind = Kind::kSetRate;
            break;
        default:
            break;
    }
    return e;
}

ClockEvent ClockEvent::as_report() const {
    ClockEvent e = *this;
    switch (kind) {
        case Kind::kSetTime:
            e.kind = Kind::kReportTime;
            break;
        case Kind::kSetDate:
            e.kind = Kind::kReportDate;
            break;
        case Kind::kSetYear:
            e.kind = Kind::kReportYear;
            break;
        case Kind::kSetRate:
            e.kind = Kind::kReportRate;
            break;
        default:
            break;
    }
    return e;
}

ClockEvent decode(std::uint16_t suffix) {
    switch (suffix & kFormMask) {
        case 0x0000:
        case 0x1000:
            return time_form(Kind::kReportTime, suffix);
        case 0x2000:
            return date_form(Kind::kReportDate, suffix);
        case 0x3000:
            return value_form(Kind::kReportYear, suffix);
        case 0x4000:
            return value_form(Kind::kReportRate, suffix);
        case 0x8000:
        case 0x9000:
            return time_form(Kind::kSetTime, suffix);
        case 0xA000:
            return date_form(Kind::kSetDate, suffix);
        case 0xB000:
            return value_form(Kind::kSetYear, suffix);
        case 0xC000:
            return value_form(Kind::kSetRate, suffix);
        case 0xF000:
            return special(suffix);
        default:
            return reserved(suffix);
    }
}

std::optional<std::uint16_t> encode(const ClockEvent& event) {
    const ClockEvent r = event.as_report();
    const std::uint16_t set = is_set(event.kind) ? kSetOffset : 0;
    std::optional<std::uint16_t> report;
    switch (r.kind) {
        case Kind::kReportTime:
            if (r.hour <= 23 && r.minute <= 59) report = two_bytes(r.hour, r.minute);
            break;
        case Kind::kReportDate:
            if (r.month >= 1 && r.month <= 12 && r.day >= 1 && r.day <= 31)
                report = two_bytes(0x20 + r.month, r.day);
            break;
        case Kind::kReportYear:
            if (r.year <= kMaxYear) report = static_cast<std::uint16_t>(0x3000 + r.year);
            break;
        case Kind::kReportRate:
            if (r.rate_quarters >= kMinRateQuarters && r.rate_quarters <= kMaxRateQuarters)
                report = static_cast<std::uint16_t>(
                    0x4000 | (static_cast<std::uint16_t>(r.rate_quarters) & kValueMask));
            break;
        case Kind::kQuery:
            return kQuerySuffix;
        case Kind::kStop:
            return kStopSuffix;
        case Kind::kStart:
            return kStartSuffix;
        case Kind::kDateRollover:
            return kDateRolloverSuffix;
        default:
            return std::nullopt;
    }
    if (!report) return std::nullopt;
    return static_cast<std::uint16_t>(*report | set);
}

std::optional<EventId> event_id(NodeId clock, const ClockEvent& event) {
    const auto suffix = encode(event);
    if (!suffix) return std::nullopt;
    return EventId(clock, *suffix);
}

EventId whole_range(NodeId clock) {
    return make_range(EventId(clock, 0), 16);
}

bool covers_whole_clock(EventId range, NodeId clock) {
    return in_range(EventId(clock, 0), range) && in_range(EventId(clock, 0xFFFF), range);
}

std::string rate_text(int quarters) {
    const int magnitude = quarters < 0 ? -quarters : quarters;
    char buf[24];
    std::snprintf(buf, sizeof buf, "%s%d.%02d", quarters < 0 ? "-" : "", magnitude / 4,
                  (magnitude % 4) * 25);
    return buf;
}

std::optional<std::int16_t> parse_rate(std::string_view text) {
    bool negative = false;
    if (!text.empty() && (text.front() == '-' || text.front() == '+')) {
        negative = text.front() == '-';
        text.remove_prefix(1);
    }
    const std::size_t dot = text.find('.');
    const std::string_view whole = text.substr(0, dot);
    std::string fraction(dot == std::string_view::npos ? "" : text.substr(dot + 1));
    if (whole.empty() || fraction.size() > 2 || (dot != std::string_view::npos && fraction.empty()))
        return std::nullopt;
    fraction.resize(2, '0');
    int units = 0;
    int hundredths = 0;
    auto [p1, e1] = std::from_chars(whole.data(), whole.data() + whole.size(), units);
    auto [p2, e2] = std::from_chars(fraction.data(), fraction.data() + 2, hundredths);
    if (e1 != std::errc{} || p1 != whole.data() + whole.size() || e2 != std::errc{} ||
        p2 != fraction.data() + 2 || units > 512 || hundredths % 25 != 0)
        return std::nullopt;
    const int quarters = (units * 4 + hundredths / 25) * (negative ? -1 : 1);
    if (quarters < kMinRateQuarters || quarters > kMaxRateQuarters) return std::nullopt;
    return static_cast<std::int16_t>(quarters);
}

std::string describe(const ClockEvent& event) {
    char buf[48];
    const bool set = is_set(event.kind);
    const char* verb = set ? "Set" : "Report";
    switch (event.as_report().kind) {
        case Kind::kReportTime:
            std::snprintf(buf, sizeof buf, "%s Time %02d:%02d", verb, event.hour, event.minute);
            return buf;
        case Kind::kReportDate:
            std::snprintf(buf, sizeof buf, "%s Date %02d-%02d", verb, event.month, event.day);
            return buf;
        case Kind::kReportYear:
            std::snprintf(buf, sizeof buf, "%s Year %d", verb, event.year);
            return buf;
        case Kind::kReportRate:
            return std::string(verb) + " Rate " + rate_text(event.rate_quarters);
        case Kind::kQuery:
            return "Query";
        case Kind::kStop:
            return "Stop";
        case Kind::kStart:
            return "Start";
        case Kind::kDateRollover:
            return "Date Rollover";
        default:
            std::snprintf(buf, sizeof buf, "reserved 0x%04X", event.reserved_code);
            return buf;
    }
}

std::string clock_name(NodeId clock) {
    if (clock == kDefaultFastClock) return "Default Fast Clock";
    if (clock == kDefaultRealTimeClock) return "Default Real-time Clock";
    if (clock == kAlternateClock1) return "Alternate Clock 1";
    if (clock == kAlternateClock2) return "Alternate Clock 2";
    return "clock " + clock.to_string();
}

}  // namespace olcb::broadcast_time
