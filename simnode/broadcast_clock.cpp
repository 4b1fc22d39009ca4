#include "simnode/broadcast_clock.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <utility>
#include <vector>

#include "openlcb/event_range.hpp"

namespace olcb::simnode {
namespace {

using namespace std::chrono;
using broadcast_time::ClockEvent;
using broadcast_time::Kind;

// The synchronization sequence and rollover reports follow the last Set by this (§6.2, §6.5).
constexpr Duration kSettle = seconds(3);
// Without a reason, Report Time goes out at the first minute this long after the last one: within
// §6.2's at most once a real minute and at least once a real hour, and a quiet bus in between.
constexpr Duration kReportSpacing = minutes(5);

struct Calendar {
    year_month_day date;
    hh_mm_ss<microseconds> time;
};

Calendar calendar(FastTime t) {
    const auto day = floor<days>(t);
    return {year_month_day{day}, hh_mm_ss<microseconds>{t - day}};
}

Message event_message(Mti mti, EventId id) {
    Message m;
    m.mti = mti;
    const auto bytes = id.to_bytes();
    m.payload.assign(bytes.begin(), bytes.end());
    return m;
}

// Days of the month of year y (a Set Date for the 31st of a 30-day month lands on its last day).
unsigned days_in(year y, month m) {
    return static_cast<unsigned>(year_month_day_last{y / m / last}.day());
}

// Ceiling of a / b for positive b.
std::int64_t ceil_div(std::int64_t a, std::int64_t b) {
    return a >= 0 ? (a + b - 1) / b : -((-a) / b);
}

bool parse_int(std::string_view text, int& out) {
    auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc{} && p == text.data() + text.size();
}

}  // namespace

FastTime fast_time(int y, unsigned m, unsigned d, int hour, int minute) {
    return FastTime{sys_days{year{y} / month{m} / day{d}}} + hours(hour) + minutes(minute);
}

std::string fast_time_text(FastTime t) {
    const Calendar c = calendar(t);
    char buf[40];
    std::snprintf(buf, sizeof buf, "%04d-%02u-%02u %02d:%02d", static_cast<int>(c.date.year()),
                  static_cast<unsigned>(c.date.month()), static_cast<unsigned>(c.date.day()),
                  static_cast<int>(c.time.hours().count()),
                  static_cast<int>(c.time.minutes().count()));
    return buf;
}

std::optional<FastTime> parse_fast_time(std::string_view text) {
    // YYYY-MM-DDTHH:MM
    if (text.size() != 16 || text[4] != '-' || text[7] != '-' ||
        (text[10] != 'T' && text[10] != ' ') || text[13] != ':')
        return std::nullopt;
    int y = 0;
    int mo = 0;
    int d = 0;
    int h = 0;
    int mi = 0;
    if (!parse_int(text.substr(0, 4), y) || !parse_int(text.substr(5, 2), mo) ||
        !parse_int(text.substr(8, 2), d) || !parse_int(text.substr(11, 2), h) ||
        !parse_int(text.substr(14, 2), mi))
        return std::nullopt;
    if (y < 0 || y > broadcast_time::kMaxYear || h > 23 || mi > 59 || h < 0 || mi < 0)
        return std::nullopt;
    const year_month_day ymd{year{y}, month{static_cast<unsigned>(mo)},
                             day{static_cast<unsigned>(d)}};
    if (!ymd.ok()) return std::nullopt;
    return fast_time(y, static_cast<unsigned>(mo), static_cast<unsigned>(d), h, mi);
}

namespace {

struct NamedClock {
    std::string_view name;
    NodeId id;
};
constexpr NamedClock kNamedClocks[] = {
    {"default-fast", broadcast_time::kDefaultFastClock},
    {"default-realtime", broadcast_time::kDefaultRealTimeClock},
    {"alternate-1", broadcast_time::kAlternateClock1},
    {"alternate-2", broadcast_time::kAlternateClock2},
};

// One word after the role; false with error set when it is not a clock word.
bool clock_word(std::string_view word, FastTime wall_now, ClockConfig& c, std::string& error) {
    for (const NamedClock& n : kNamedClocks) {
        if (word == n.name) {
            c.clock = n.id;
            return true;
        }
    }
    if (word == "stopped" || word == "running") {
        c.running = word == "running";
        return true;
    }
    if (word.starts_with("rate=")) {
        const auto q = broadcast_time::parse_rate(word.substr(5));
        if (!q)
            error = "rate '" + std::string(word.substr(5)) +
                    "' must be a multiple of 0.25 "
                    "from -512 to 511.75";
        if (q) c.rate_quarters = *q;
        return q.has_value();
    }
    if (word.starts_with("time=")) {
        const std::string_view value = word.substr(5);
        const auto t = value == "now" ? std::optional<FastTime>(wall_now) : parse_fast_time(value);
        if (!t)
            error = "time '" + std::string(value) +
                    "' must be YYYY-MM-DDTHH:MM (years "
                    "0..4095) or now";
        if (t) c.start = *t;
        return t.has_value();
    }
    if (auto id = NodeId::parse(word)) {
        c.clock = *id;
        return true;
    }
    error = "unknown word '" + std::string(word) + "'";
    return false;
}

}  // namespace

std::optional<ClockConfig> parse_clock_config(std::string_view text, FastTime wall_now,
                                              std::string& error) {
    std::vector<std::string_view> words;
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t start = text.find_first_not_of(" \t", at);
        if (start == std::string_view::npos) break;
        const std::size_t end = std::min(text.find_first_of(" \t", start), text.size());
        words.push_back(text.substr(start, end - start));
        at = end;
    }
    ClockConfig c;
    if (words.empty() || (words[0] != "generator" && words[0] != "consumer")) {
        error = "clock '" + std::string(text) + "' must start with generator or consumer";
        return std::nullopt;
    }
    c.role = words[0] == "generator" ? ClockRole::kGenerator : ClockRole::kConsumer;
    for (std::size_t k = 1; k < words.size(); ++k) {
        if (!clock_word(words[k], wall_now, c, error)) {
            error = std::string("clock '").append(text).append("': ").append(error);
            return std::nullopt;
        }
    }
    return c;
}

std::string clock_config_text(const ClockConfig& c) {
    std::string out = c.role == ClockRole::kGenerator ? "generator " : "consumer ";
    std::string name = c.clock.to_string();
    for (const NamedClock& n : kNamedClocks)
        if (n.id == c.clock) name = n.name;
    std::string time = fast_time_text(c.start);
    time[10] = 'T';
    return out + name + " rate=" + broadcast_time::rate_text(c.rate_quarters) + " time=" + time +
           (c.running ? " running" : " stopped");
}

BroadcastClock::BroadcastClock(ClockConfig config, ClockQuirks quirks)
    : config_(config),
      quirks_(quirks),
      base_fast_(config.start),
      rate_(config.rate_quarters),
      running_(config.running),
      shown_(floor<minutes>(config.start)) {}

FastTime BroadcastClock::time_at(TimePoint now) const {
    if (!running_ || rate_ == 0) return base_fast_;
    const std::int64_t real = duration_cast<microseconds>(now - base_real_).count();
    const std::int64_t num = std::int64_t{rate_} * (100 + quirks_.drift_percent);
    return base_fast_ + microseconds(real * num / 400);
}

void BroadcastClock::rebase(TimePoint now, FastTime t) {
    base_fast_ = t;
    base_real_ = now;
    shown_ = floor<minutes>(t);
}

ClockEvent BroadcastClock::current(Kind kind, TimePoint now) const {
    const Calendar c = calendar(time_at(now));
    switch (kind) {
        case Kind::kReportTime:
            return ClockEvent::report_time(static_cast<int>(c.time.hours().count()),
                                           static_cast<int>(c.time.minutes().count()));
        case Kind::kReportDate:
            return ClockEvent::report_date(static_cast<int>(static_cast<unsigned>(c.date.month())),
                                           static_cast<int>(static_cast<unsigned>(c.date.day())));
        case Kind::kReportYear:
            return ClockEvent::report_year(
                std::clamp(static_cast<int>(c.date.year()), 0, int{broadcast_time::kMaxYear}));
        case Kind::kReportRate:
            return ClockEvent::report_rate(rate_);
        default:
            return ClockEvent::of(running_ ? Kind::kStart : Kind::kStop);
    }
}

void BroadcastClock::send_event(const Send& send, Mti mti, const Event& event) const {
    if (const auto id = broadcast_time::event_id(config_.clock, event))
        send(event_message(mti, *id));
}

void BroadcastClock::started(TimePoint now, const Send& send) {
    // Fast time starts with the first start-up and runs on through restarts (a clock with a
    // battery).
    if (!std::exchange(ever_started_, true)) base_real_ = now;
    identify(send);
    if (config_.role == ClockRole::kConsumer) {
        send_event(send, Mti::kEventReport, ClockEvent::of(Kind::kQuery));
        return;
    }
    minute_tick(now, send);
    send_sync(now, send);
}

void BroadcastClock::identify(const Send& send) const {
    const EventId range = broadcast_time::whole_range(config_.clock);
    if (config_.role == ClockRole::kGenerator)
        send(event_message(Mti::kProducerRangeIdentified, range));
    const bool half = config_.role == ClockRole::kGenerator && quirks_.half_consumer_range;
    send(event_message(
        Mti::kConsumerRangeIdentified,
        half ? make_range(EventId(config_.clock, broadcast_time::kSetOffset), 15) : range));
}

void BroadcastClock::send_sync(TimePoint now, const Send& send) {
    const Mti valid = Mti::kProducerIdentifiedValid;
    send_event(send, valid, current(Kind::kStart, now));
    send_event(send, valid, current(Kind::kReportRate, now));
    const Kind middle[] = {Kind::kReportYear, Kind::kReportDate, Kind::kReportTime};
    if (quirks_.sync_out_of_order) {
        for (auto it = std::rbegin(middle); it != std::rend(middle); ++it)
            send_event(send, valid, current(*it, now));
    } else {
        for (Kind k : middle) send_event(send, valid, current(k, now));
    }
    next_minute_due_ = running_ && rate_ != 0;
}

void BroadcastClock::report_time(TimePoint now, const Send& send) {
    send_event(send, Mti::kEventReport, current(Kind::kReportTime, now));
    last_report_ = now;
    next_minute_due_ = false;
}

void BroadcastClock::roll_over(TimePoint now, bool forward, const Send& send) {
    using Rollover = ClockQuirks::Rollover;
    if (forward && quirks_.rollover == Rollover::kDateKept) {
        rebase(now, time_at(now) - days(1));
    } else if (forward && quirks_.rollover == Rollover::kYearKept) {
        const Calendar c = calendar(time_at(now));
        if (c.date.month() == January && c.date.day() == day{1})
            rebase(now, time_at(now) - (sys_days{c.date} -
                                        sys_days{(c.date.year() - years(1)) / January / 1}));
    }
    if (quirks_.rollover == Rollover::kEventLate) report_time(now, send);
    send_event(send, Mti::kEventReport, ClockEvent::of(Kind::kDateRollover));
    rollover_due_ = now + kSettle;
}

void BroadcastClock::minute_tick(TimePoint now, const Send& send) {
    const auto minute = floor<minutes>(time_at(now));
    if (minute == shown_) return;
    const bool forward = minute > shown_;
    const bool new_day = floor<days>(minute) != floor<days>(shown_);
    shown_ = minute;
    if (new_day) roll_over(now, forward, send);
    const Calendar c = calendar(time_at(now));
    const int of_day = static_cast<int>(c.time.hours().count() * 60 + c.time.minutes().count());
    const bool reported_late = new_day && quirks_.rollover == ClockQuirks::Rollover::kEventLate;
    const bool due = next_minute_due_ || subscribed_.count(of_day) != 0 || !last_report_ ||
                     now - *last_report_ >= kReportSpacing;
    if (due && !reported_late) report_time(now, send);
}

void BroadcastClock::poll(TimePoint now, const Send& send) {
    if (config_.role == ClockRole::kConsumer) return;
    minute_tick(now, send);
    if (rollover_due_ && now >= *rollover_due_) {
        rollover_due_.reset();
        send_event(send, Mti::kEventReport, current(Kind::kReportYear, now));
        send_event(send, Mti::kEventReport, current(Kind::kReportDate, now));
    }
    if (sync_due_ && now >= *sync_due_) {
        sync_due_.reset();
        send_sync(now, send);
    }
}

std::optional<TimePoint> BroadcastClock::next_deadline() const {
    if (config_.role == ClockRole::kConsumer) return std::nullopt;
    std::optional<TimePoint> at;
    auto consider = [&](std::optional<TimePoint> t) {
        if (t && (!at || *t < *at)) at = t;
    };
    consider(sync_due_);
    consider(rollover_due_);
    const std::int64_t num = std::int64_t{rate_} * (100 + quirks_.drift_percent);
    if (running_ && num != 0) {
        // Fast microseconds from base_fast_ to where the shown minute changes.
        const std::int64_t fast =
            num > 0 ? duration_cast<microseconds>(shown_ + minutes(1) - base_fast_).count()
                    : duration_cast<microseconds>(base_fast_ - shown_).count() + 1;
        const std::int64_t real = ceil_div(fast * 400, num > 0 ? num : -num);
        consider(base_real_ + microseconds(std::max<std::int64_t>(real, 0)));
    }
    return at;
}

void BroadcastClock::apply_set(const Event& event, TimePoint now, const Send& send) {
    FastTime t = time_at(now);
    const Calendar c = calendar(t);
    const sys_days today = floor<days>(t);
    switch (event.kind) {
        case Kind::kSetTime:
            t = FastTime{today} + hours(event.hour) + minutes(event.minute);
            break;
        case Kind::kSetDate: {
            const month m{event.month};
            const day d{std::min<unsigned>(event.day, days_in(c.date.year(), m))};
            t = FastTime{sys_days{c.date.year() / m / d}} + (t - FastTime{today});
            break;
        }
        case Kind::kSetYear: {
            const year y{event.year};
            const day d{std::min(static_cast<unsigned>(c.date.day()), days_in(y, c.date.month()))};
            t = FastTime{sys_days{y / c.date.month() / d}} + (t - FastTime{today});
            break;
        }
        default:
            break;
    }
    rebase(now, t);
    if (event.kind == Kind::kSetRate) rate_ = event.rate_quarters != 0 ? event.rate_quarters : 1;
    if (event.kind == Kind::kStart) running_ = true;
    if (event.kind == Kind::kStop) running_ = false;
    if (broadcast_time::is_set(event.kind))
        send_event(
            send, Mti::kEventReport,
            quirks_.reports_asked ? event.as_report() : current(event.as_report().kind, now));
    sync_due_ = now + kSettle;
}

// A consumer takes the time from what a generator sends (PCER, or Producer Identified Valid).
void BroadcastClock::follow(const Event& event, bool instant, TimePoint now) {
    FastTime t = time_at(now);
    const Calendar c = calendar(t);
    const sys_days today = floor<days>(t);
    switch (event.kind) {
        case Kind::kStart:
        case Kind::kStop:
            rebase(now, t);
            running_ = event.kind == Kind::kStart;
            return;
        case Kind::kReportRate:
            rebase(now, t);
            rate_ = event.rate_quarters;
            return;
        case Kind::kReportYear:
        case Kind::kReportDate: {
            const year y = event.kind == Kind::kReportYear ? year{event.year} : c.date.year();
            const month m = event.kind == Kind::kReportDate ? month{event.month} : c.date.month();
            const day d = event.kind == Kind::kReportDate ? day{event.day} : c.date.day();
            const year_month_day ymd{y, m, d};
            if (ymd.ok()) rebase(now, FastTime{sys_days{ymd}} + (t - FastTime{today}));
            return;
        }
        case Kind::kReportTime: {
            FastTime next = FastTime{today} + hours(event.hour) + minutes(event.minute);
            // A Date Rollover announced the new day: 00:00 after 23:59 is tomorrow's.
            if (instant && rollover_seen_ && next < t - hours(12)) next += days(1);
            rollover_seen_ = false;
            rebase(now, next);
            return;
        }
        case Kind::kDateRollover:
            rollover_seen_ = true;
            return;
        default:
            return;
    }
}

void BroadcastClock::answer_identify(const Message& msg, const Event& event,
                                     const Send& send) const {
    if (event.kind == Kind::kReserved) return;
    const auto id = EventId::from_bytes(msg.payload);
    if (msg.mti == Mti::kIdentifyConsumer) {
        // Both roles announced consuming the whole range.
        send(event_message(Mti::kConsumerIdentifiedUnknown, *id));
        return;
    }
    if (config_.role != ClockRole::kGenerator) return;
    const bool produced = broadcast_time::is_report(event.kind) || event.kind == Kind::kStart ||
                          event.kind == Kind::kStop || event.kind == Kind::kDateRollover;
    if (!produced) return;
    send(event_message(Mti::kProducerIdentifiedUnknown, *id));
}

void BroadcastClock::on_message(const Message& msg, TimePoint now, const Send& send) {
    const auto id = EventId::from_bytes(msg.payload);
    if (!id) return;
    if (msg.mti == Mti::kConsumerRangeIdentified) {
        // A display joined: tell it the time (BroadcastTimeTN §2.6.4 lets it ask; this spares it).
        if (config_.role == ClockRole::kGenerator &&
            broadcast_time::covers_whole_clock(*id, clock()))
            sync_due_ = sync_due_ ? std::min(*sync_due_, now) : now;
        return;
    }
    if (broadcast_time::clock_of(*id) != clock()) return;
    const Event event = broadcast_time::decode(broadcast_time::suffix_of(*id));
    if (msg.mti == Mti::kIdentifyConsumer || msg.mti == Mti::kIdentifyProducer) {
        answer_identify(msg, event, send);
        return;
    }
    if (config_.role == ClockRole::kConsumer) {
        if (msg.mti == Mti::kEventReport || msg.mti == Mti::kProducerIdentifiedValid)
            follow(event, msg.mti == Mti::kEventReport, now);
        return;
    }
    if (is_consumer_identified(msg.mti) && event.kind == Kind::kReportTime) {
        subscribed_.insert(event.hour * 60 + event.minute);
        return;
    }
    if (msg.mti != Mti::kEventReport) return;
    minute_tick(now, send);
    if (broadcast_time::is_set(event.kind) || event.kind == Kind::kStart ||
        event.kind == Kind::kStop) {
        apply_set(event, now, send);
    } else if (event.kind == Kind::kQuery && !quirks_.ignores_query) {
        send_sync(now, send);
    }
}

}  // namespace olcb::simnode
