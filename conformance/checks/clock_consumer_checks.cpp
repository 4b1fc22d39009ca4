// Broadcast Time consumer checks (BroadcastTimeS §6.1; EventTransportS §6.4 for its answers): a
// display announces the clock at start-up and, fed what a generator sends, answers Identify
// Consumer for the events it consumes. Feeding a consumer a time changes what it shows, so the
// fed checks run only on a node named with --node and end with a Query, which makes the layout's
// generator tell every display the time again.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "conformance/checks/checks.hpp"
#include "conformance/checks/clock_observer.hpp"
#include "conformance/checks/clock_probe.hpp"
#include "conformance/checks/clock_roles.hpp"
#include "openlcb/event_range.hpp"

namespace olcb::conform::checks {
namespace {

using namespace clocks;

// How a consumer answered Identify Consumer for one of the clock's events.
enum class Answer : std::uint8_t { kNone, kRange, kIdentified };

struct Asked {
    std::uint16_t suffix;
    Answer answer;
};

// The consumer fed what OlcbChecker's bt110, bt120 and bt130 send, asked after each part whether
// it consumes the events, then a Query so the layout's generator tells every display the time
// again.
struct ConsumerSession {
    using Key = std::uint64_t;
    std::vector<Asked> after_sync, after_stop_start, after_rate;

    static ConsumerSession ask(CheckRun& run, Key clock);
};

Answer identify_consumer(CheckRun& run, NodeId clock, std::uint16_t suffix) {
    Session& s = run.session();
    const std::size_t mark = s.message_mark();
    send_event(s, Mti::kIdentifyConsumer, clock, bt::decode(suffix));
    const EventId id(clock, suffix);
    Answer best = Answer::kNone;
    s.run_until(
        [&] {
            for (const ClockMsg& m : clock_msgs(s, run.alias(), mark, clock)) {
                if (is_consumer_identified(m.mti) && m.id == id) best = Answer::kIdentified;
                if (m.mti == Mti::kConsumerRangeIdentified && in_range(id, m.id) &&
                    best == Answer::kNone)
                    best = Answer::kRange;
            }
            return best == Answer::kIdentified;
        },
        answer_window(run));
    return best;
}

std::vector<Asked> ask_each(CheckRun& run, NodeId clock, std::initializer_list<std::uint16_t> sfx) {
    std::vector<Asked> out;
    for (std::uint16_t x : sfx) out.push_back({x, identify_consumer(run, clock, x)});
    return out;
}

// What a generator sends as its sequence: 2023-07-22 01:23 at `rate`, running or stopped.
void feed_sequence(Session& s, NodeId clock, bool running, int rate) {
    const Mti valid = Mti::kProducerIdentifiedValid;
    send_event(s, valid, clock, ClockEvent::of(running ? Kind::kStart : Kind::kStop));
    send_event(s, valid, clock, ClockEvent::report_rate(rate));
    send_event(s, valid, clock, ClockEvent::report_year(2023));
    send_event(s, valid, clock, ClockEvent::report_date(7, 22));
    send_event(s, valid, clock, ClockEvent::report_time(1, 23));
    send_event(s, Mti::kEventReport, clock, ClockEvent::report_time(1, 24));
}

ConsumerSession ConsumerSession::ask(CheckRun& run, Key key) {
    const NodeId clock{key};
    Session& s = run.session();
    ConsumerSession c;
    feed_sequence(s, clock, false, 16);
    s.wait(run.options().window);
    c.after_sync =
        ask_each(run, clock, {bt::kStopSuffix, 0x4010, 0x37E7, 0x2716, 0x0117, bt::kStartSuffix});
    feed_sequence(s, clock, true, 16);
    send_event(s, Mti::kEventReport, clock, ClockEvent::of(Kind::kStop));
    s.wait(run.options().window);
    c.after_stop_start = ask_each(run, clock, {bt::kStopSuffix});
    send_event(s, Mti::kEventReport, clock, ClockEvent::of(Kind::kStart));
    s.wait(run.options().window);
    c.after_stop_start.push_back(
        {bt::kStartSuffix, identify_consumer(run, clock, bt::kStartSuffix)});
    send_event(s, Mti::kEventReport, clock, ClockEvent::report_rate(32));
    s.wait(run.options().window);
    c.after_rate = ask_each(run, clock, {0x4020});
    send_event(s, Mti::kEventReport, clock, ClockEvent::of(Kind::kQuery));
    return c;
}

PerClock judge_answers(const std::vector<Asked>& asked, const std::string& after) {
    std::string none;
    std::string ranges;
    for (const Asked& a : asked) {
        const std::string name = bt::describe(bt::decode(a.suffix));
        if (a.answer == Answer::kNone) none += (none.empty() ? "" : ", ") + name;
        if (a.answer == Answer::kRange) ranges += (ranges.empty() ? "" : ", ") + name;
    }
    const std::string want = "Consumer Identified with each event ID";
    if (!none.empty())
        return fail("after " + after + ", Identify Consumer got no answer for " + none, want,
                    "no answer for " + none);
    if (!ranges.empty()) {
        PerClock p;
        p.status = Status::kWarn;
        p.message = "after " + after + ", Identify Consumer for " + ranges +
                    " was answered with Consumer Range Identified, not Consumer Identified "
                    "carrying the event ID";
        return p;
    }
    return pass("after " + after + ", Consumer Identified for each: " + [&] {
        std::string all;
        for (const Asked& a : asked)
            all += (all.empty() ? "" : ", ") + bt::describe(bt::decode(a.suffix));
        return all;
    }());
}

void each_consumed(CheckRun& run, const CheckSpec& spec,
                   const std::function<PerClock(const ConsumerSession&)>& one) {
    if (const std::string why = consumer_gate(run); !why.empty()) return run.out(spec).skip(why);
    if (const std::string why = disruptive_gate(run); !why.empty()) return run.out(spec).skip(why);
    judge_clocks(run, spec, run.probe<ClockRoles>().consumed,
                 [&](NodeId c) { return one(run.probe<ConsumerSession>(c.value())); });
}

void consumer_sync(CheckRun& run, const CheckSpec& spec) {
    each_consumed(run, spec, [](const ConsumerSession& c) {
        return judge_answers(c.after_sync, "a sequence (stopped, 4.00, 2023-07-22 01:23)");
    });
}

void consumer_start_stop(CheckRun& run, const CheckSpec& spec) {
    each_consumed(run, spec, [](const ConsumerSession& c) {
        return judge_answers(c.after_stop_start, "Stop, then Start");
    });
}

void consumer_rate(CheckRun& run, const CheckSpec& spec) {
    each_consumed(run, spec, [](const ConsumerSession& c) {
        return judge_answers(c.after_rate, "Report Rate 8.00");
    });
}

PerClock judge_consumer_startup(CheckRun& run, NodeId clock) {
    const std::size_t mark = *run.probe<Startup>().mark;
    const auto msgs = watch(run, clock, mark, answer_window(run), [&](const auto& m) {
        return std::any_of(m.begin(), m.end(), [](const ClockMsg& x) {
            return x.mti == Mti::kConsumerRangeIdentified || is_consumer_identified(x.mti);
        });
    });
    std::string seen;
    for (const ClockMsg& m : msgs)
        if (m.mti == Mti::kConsumerRangeIdentified || is_consumer_identified(m.mti))
            seen +=
                (seen.empty() ? "" : ", ") + std::string(mti_name(m.mti)) + " " + m.id.to_string();
    if (seen.empty())
        return fail("after start-up the consumer announced none of the clock's events",
                    "Consumer Range Identified " + bt::whole_range(clock).to_string() +
                        " or Consumer Identified for the events it uses",
                    "none");
    return pass("after start-up: " + seen);
}

void consumer_startup(CheckRun& run, const CheckSpec& spec) {
    if (const std::string why = consumer_gate(run); !why.empty()) return run.out(spec).skip(why);
    if (const std::string why = startup_gate(run); !why.empty()) return run.out(spec).skip(why);
    judge_clocks(run, spec, run.probe<ClockRoles>().consumed,
                 [&](NodeId c) { return judge_consumer_startup(run, c); });
}

constexpr auto kClock = Category::kClock;
constexpr auto kShall = Strength::kShall;

}  // namespace

std::vector<CheckSpec> clock_consumer_checks() {
    std::vector<CheckSpec> all = {
        {"clock.consumer-startup", 724, kClock, "BroadcastTimeS §6.1", kShall,
         "a starting consumer sends Consumer Range Identified for the clock, or Consumer "
         "Identified for the events it uses",
         "bt100",
         "(--reboot, or a start-up seen during the run) after Initialization Complete: a "
         "Consumer (Range) Identified of the clock",
         consumer_startup},
        {"clock.consumer-sync", 725, kClock, "EventTransportS §6.4; BroadcastTimeS §6.3", kShall,
         "a consumer answers Identify Consumer for a clock event it consumes with Consumer "
         "Identified carrying that event ID; Consumer Range Identified alone WARNs",
         "bt110",
         "(--node) a sequence (Stop, 4.00, 2023, 07-22, 01:23, PCER 01:24), then Identify "
         "Consumer for Stop, Rate 4.00, Year, Date, Time and Start; at the end a Query so the "
         "layout's generator resets every display",
         consumer_sync},
        {"clock.consumer-start-stop", 726, kClock, "EventTransportS §6.4; BroadcastTimeS §4.10",
         kShall, "as clock.consumer-sync, for Stop and Start", "bt120",
         "(--node) PCER Stop, Identify Consumer Stop; PCER Start, Identify Consumer Start",
         consumer_start_stop},
        {"clock.consumer-rate", 727, kClock, "EventTransportS §6.4; BroadcastTimeS §4.4", kShall,
         "as clock.consumer-sync, for a new rate", "bt130",
         "(--node) PCER Report Rate 8.00, Identify Consumer for it", consumer_rate},
    };
    // As for the generator's checks (broadcast_time_checks.cpp).
    for (CheckSpec& s : all) s.needs = Protocol::kEventExchange;
    return all;
}

}  // namespace olcb::conform::checks
