// Which clocks a node generates or consumes, the gates of the clock checks and the one result
// per check for every clock (clock_roles.hpp; ClockRoles in checks.hpp).
#include "conformance/checks/clock_roles.hpp"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "openlcb/broadcast_time.hpp"
#include "openlcb/event_range.hpp"

namespace olcb::conform::checks {
namespace {

namespace bt = olcb::broadcast_time;

constexpr NodeId kWellKnownClocks[] = {bt::kDefaultFastClock, bt::kDefaultRealTimeClock,
                                       bt::kAlternateClock1, bt::kAlternateClock2};

// True when one of ids or ranges touches the clock's block of 65,536 event IDs.
bool touches(const std::set<std::uint64_t>& ids, const std::set<std::uint64_t>& ranges,
             NodeId clock) {
    const EventId first(clock, 0);
    const EventId last(clock, 0xFFFF);
    for (std::uint64_t id : ids)
        if (bt::clock_of(EventId(id)) == clock) return true;
    for (std::uint64_t r : ranges) {
        const EventId range(r);
        if (range_first(range) <= last && range_last(range) >= first) return true;
    }
    return false;
}

void add_once(std::vector<NodeId>& list, NodeId clock) {
    if (std::find(list.begin(), list.end(), clock) == list.end()) list.push_back(clock);
}

}  // namespace

ClockRoles ClockRoles::ask(CheckRun& run) {
    const EventAnswers& a = run.probe<EventAnswers>(IdentifyTo::kTheNode);
    ClockRoles roles;
    roles.answered = !a.empty();
    for (NodeId clock : kWellKnownClocks) {
        if (touches(a.produced, a.produced_ranges, clock))
            add_once(roles.generated, clock);
        else if (touches(a.consumed, a.consumed_ranges, clock))
            add_once(roles.consumed, clock);
    }
    // A clock of its own ID: a produced range of exactly one clock's 16 bits, with consumed
    // events in the same block (§6.1's pair of ranges).
    for (std::uint64_t r : a.produced_ranges) {
        const EventId range(r);
        const NodeId clock = bt::clock_of(range);
        if (range_mask(range) == 0xFFFF && touches(a.consumed, a.consumed_ranges, clock))
            add_once(roles.generated, clock);
    }
    return roles;
}

std::string ClockRoles::describe() const {
    std::string out;
    for (NodeId c : generated) out += (out.empty() ? "" : ", ") + bt::clock_name(c);
    return out;
}

std::string not_identified_as(CheckRun& run, const std::string& what,
                              const std::function<bool(const EventAnswers&)>& applies) {
    const EventAnswers& a = run.probe<EventAnswers>(IdentifyTo::kTheNode);
    if (a.empty()) return "not known as " + what + ": Identify Events addressed got no answer";
    if (applies(a)) return "";
    return "not " + what +
           " (judged from its answer to Identify Events addressed: " + a.describe() + ")";
}

bool is_clock_report(CheckRun& run, const CanFrame& frame) {
    if (frame.len != 8) return false;
    const auto id = EventId::from_bytes(std::span(frame.data).first(8));
    if (!id) return false;
    const ClockRoles& roles = run.probe<ClockRoles>();
    const NodeId clock = bt::clock_of(*id);
    return std::find(roles.generated.begin(), roles.generated.end(), clock) !=
               roles.generated.end() ||
           std::find(roles.consumed.begin(), roles.consumed.end(), clock) != roles.consumed.end();
}

namespace clocks {

using namespace std::chrono_literals;

std::string generator_gate(CheckRun& run) {
    return not_identified_as(run, "a Broadcast Time clock generator", [&](const EventAnswers&) {
        return !run.probe<ClockRoles>().generated.empty();
    });
}

std::string consumer_gate(CheckRun& run) {
    return not_identified_as(run, "a Broadcast Time clock consumer", [&](const EventAnswers&) {
        return !run.probe<ClockRoles>().consumed.empty();
    });
}

std::string disruptive_gate(CheckRun& run) {
    if (run.options().read_only) return "--read-only: no clock is set";
    if (!run.options().named)
        return "sets the clock: runs only on a node named with --node (the layout's time would "
               "change)";
    return "";
}

Duration answer_window(CheckRun& run) {
    return std::max<Duration>(run.options().answer_window, 1s);
}

PerClock pass(std::string message) {
    return {Status::kPass, std::move(message), "", ""};
}
PerClock fail(std::string message, std::string expected, std::string seen) {
    return {Status::kFail, std::move(message), std::move(expected), std::move(seen)};
}
PerClock skip(std::string why) {
    return {Status::kSkip, std::move(why), "", ""};
}
PerClock warn(std::string message) {
    return {Status::kWarn, std::move(message), "", ""};
}

void judge_clocks(CheckRun& run, const CheckSpec& spec, const std::vector<NodeId>& clocks,
                  const std::function<PerClock(NodeId)>& one) {
    std::vector<PerClock> all;
    all.reserve(clocks.size());
    for (NodeId c : clocks) all.push_back(one(c));
    std::size_t worst = 0;
    for (std::size_t i = 1; i < all.size(); ++i)
        if (severity(all[i].status) > severity(all[worst].status)) worst = i;
    Verdict out = run.out(spec);
    if (all.size() == 1) {
        const PerClock& p = all.front();
        if (p.status == Status::kSkip) return out.skip(p.message);
        return out.add(p.status, p.message, p.expected, p.seen);
    }
    std::vector<std::string> details;
    details.reserve(all.size());
    for (std::size_t i = 0; i < all.size(); ++i)
        details.push_back(bt::clock_name(clocks[i]) + ": " + all[i].message);
    const PerClock& w = all[worst];
    if (w.status == Status::kSkip) return out.skip(details.front());
    out.add(w.status, bt::clock_name(clocks[worst]) + ": " + w.message, w.expected, w.seen,
            std::move(details));
}

void each_generated(CheckRun& run, const CheckSpec& spec, bool disruptive,
                    const std::function<PerClock(NodeId)>& one) {
    if (const std::string why = generator_gate(run); !why.empty()) return run.out(spec).skip(why);
    if (disruptive) {
        if (const std::string why = disruptive_gate(run); !why.empty())
            return run.out(spec).skip(why);
    }
    judge_clocks(run, spec, run.probe<ClockRoles>().generated, one);
}

}  // namespace clocks
}  // namespace olcb::conform::checks
