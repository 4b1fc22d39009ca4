// Event identification: Identify Events (global and addressed), Identify Producer / Consumer,
// the CDI's <eventid> values against what the node identifies, and (write phase) a rewritten
// event ID identified at once. The read-only checks write nothing.
#include "conformance/checks/events.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "conformance/backup/backup_keys.hpp"
#include "conformance/checks/checks.hpp"
#include "memory/memory_config_codec.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/event_range.hpp"

namespace olcb::conform::checks {
namespace {

using namespace std::chrono_literals;

// Eventid variables read from the node at most (every replica of every group up to this).
constexpr std::size_t kMaxEventVars = 512;
// Event IDs missing from the Identify Events answer asked one by one at most.
constexpr std::size_t kMaxFollowUps = 64;
// Detail lines a WARN lists at most.
constexpr std::size_t kMaxDetails = 64;
// Bytes one read may return (adjacent eventid variables are read together up to this).
constexpr std::uint32_t kMaxRead = 64;
// An event ID no node should have: the tool's own range (05.01.01.01.3F...).
constexpr std::uint64_t kUnknownEvent = 0x0501'0101'3FFF'FFFEull;
// events.follow-write writes 05.01.01.01.3F.FE.xx.yy, xx.yy from the variable's address.
constexpr std::uint64_t kFollowBase = 0x0501'0101'3FFE'0000ull;
// Event Inquiry: Identify Events is answered with every event the node produces and consumes.
constexpr std::string_view kInquiry = "EventTransportS §6.2";

using Windows = AnswerWindows;

Windows windows_of(const ProtocolOptions& o) {
    return {o.window, o.answer_window};
}

Windows windows_of(const CheckContext& ctx) {
    Windows w;
    if (ctx.timing)
        w = {std::max(w.quiet, ctx.timing->silence), std::max(w.answer, ctx.timing->answer)};
    return w;
}

bool in_range(std::uint64_t id, std::uint64_t range) {
    return olcb::in_range(EventId(id), EventId(range));
}

std::string event_text(std::uint64_t id) {
    return EventId(id).to_string();
}

bool has_event_bit(CheckRun& run) {
    const auto& pip = run.probe<PipProbe>().reply;
    return pip && pip->has(Protocol::kEventExchange);
}

// Nodes on the segment beyond which Identify Events global is left to --thorough: every node
// answers it with all its events (1,000 nodes: a storm of thousands of frames).
constexpr std::size_t kCrowd = 8;

// The nodes seen (lcc-conform runs left out) when there are more than kCrowd; 0 otherwise.
std::size_t crowd(CheckRun& run) {
    if (run.options().selection.thorough) return 0;
    std::size_t n = 0;
    for (const NodeInfo& seen : run.session().nodes_seen())
        if (!is_tool_id(seen.id)) ++n;
    return n > kCrowd ? n : 0;
}

// EventAnswers::ask (probes.hpp declares the probe; its asking lives here, beside the event
// checks' windows). Each form in a window of its own, never both at once: OpenMRN's time_server,
// sent the addressed form while it answered the global one, left its Producer Identified messages
// out of the next answer and answered no Broadcast Time Query until restarted (measured
// 2026-12-05).
EventAnswers answers_of(CheckRun& run, IdentifyTo to) {
    const Windows w = windows_of(run.options());
    // A node without the Event Exchange bit owes no answer: silence is awaited, not an answer.
    const Duration first = has_event_bit(run) ? w.answer : w.quiet;
    return identify_events(run.session(), run.node(), to, first, w);
}

// ---- the CDI's eventid variables ----

struct EventVar {
    std::uint8_t space = 0;
    std::uint32_t address = 0;
    std::string key, protection;
    std::optional<std::uint64_t> value;
};

struct EventVars {
    std::vector<EventVar> vars;
    bool capped = false;                  ///< the CDI has more than kMaxEventVars
    std::vector<std::string> unreadable;  ///< "name: what the read did"
};

EventVars event_vars(const cdi::Layout& layout) {
    EventVars out;
    layout.visit([&](const cdi::Cursor& c) {
        if (c.element().kind != cdi::ElementKind::kEventId || c.size() != 8) return true;
        if (out.vars.size() >= kMaxEventVars) {
            out.capped = true;
            return false;
        }
        if (c.space() > 0xFF || c.address() > 0xFFFFFFF7u) return true;
        out.vars.push_back({static_cast<std::uint8_t>(c.space()),
                            static_cast<std::uint32_t>(c.address()),
                            jmri_backup_key(layout, c),
                            protection_reason(layout, c),
                            {}});
        return true;
    });
    return out;
}

// Reads every variable's 8 bytes, adjacent variables together (at most kMaxRead bytes a read).
void read_values(Session& s, const NodeInfo& node, EventVars& ev,
                 const std::function<void(const MemResult&)>& note) {
    std::vector<EventVar>& v = ev.vars;
    for (std::size_t i = 0; i < v.size();) {
        std::size_t j = i + 1;
        while (j < v.size() && v[j].space == v[i].space && v[j].address == v[j - 1].address + 8 &&
               (j - i + 1) * 8 <= kMaxRead)
            ++j;
        const auto length = static_cast<std::uint32_t>((j - i) * 8);
        MemResult r =
            s.read_range(node, static_cast<memory::Space>(v[i].space), v[i].address, length, false);
        if (note) note(r);
        for (std::size_t k = i; k < j; ++k) {
            const std::size_t at = (k - i) * 8;
            if (r.ok && r.data.size() >= at + 8) {
                v[k].value = EventId::from_bytes(std::span(r.data).subspan(at, 8))->value();
            } else {
                ev.unreadable.push_back(v[k].key + ": " + describe(r));
            }
        }
        i = j;
    }
}

// ---- Identify Producer / Identify Consumer ----

struct Ask {
    std::uint64_t id = 0;
    bool producer = false;
};

void send_identify(Session& s, const Ask& a) {
    Message m;
    m.mti = a.producer ? Mti::kIdentifyProducer : Mti::kIdentifyConsumer;
    const auto bytes = EventId(a.id).to_bytes();
    m.payload.assign(bytes.begin(), bytes.end());
    s.send(m);
}

// True when m is the node's Identified message for a's ID in a's role (or a range covering it).
bool answers_ask(const Message& m, const Ask& a) {
    const auto id = EventId::from_bytes(m.payload);
    if (!id) return false;
    if (a.producer ? is_producer_identified(m.mti) : is_consumer_identified(m.mti))
        return id->value() == a.id;
    const Mti range = a.producer ? Mti::kProducerRangeIdentified : Mti::kConsumerRangeIdentified;
    return m.mti == range && in_range(a.id, id->value());
}

// Sends every ask and returns which got an answer: waits until each ask marked expected is
// answered (at most the answer window), then for silence (the quiet window since sending and
// since the last answer).
std::vector<bool> ask_all(Session& s, std::uint16_t alias, const std::vector<Ask>& asks,
                          const std::vector<bool>& expected, const Windows& w) {
    const std::size_t mark = s.message_mark();
    for (const Ask& a : asks) send_identify(s, a);
    std::vector<bool> answered(asks.size(), false);
    auto tally = [&](const std::vector<Message>& got) {
        std::fill(answered.begin(), answered.end(), false);
        for (const Message& m : got)
            for (std::size_t i = 0; i < asks.size(); ++i)
                if (answers_ask(m, asks[i])) answered[i] = true;
        for (std::size_t i = 0; i < asks.size(); ++i)
            if (expected[i] && !answered[i]) return false;
        return true;
    };
    const auto got = await_answers(
        s, alias, mark, [](const Message& m) { return is_identification(m.mti); }, tally, w.answer,
        w);
    tally(got);
    return answered;
}

// ---- events.identify-global, events.identify-addressed ----

// The answers the other event checks judge: global, or addressed on a crowded segment.
const EventAnswers& reference_answers(CheckRun& run) {
    return run.probe<EventAnswers>(crowd(run) == 0 ? IdentifyTo::kEveryNode : IdentifyTo::kTheNode);
}

void identify_global(CheckRun& run, const CheckSpec& spec) {
    Verdict out = run.out(spec);
    if (const std::size_t n = crowd(run))
        return out.skip(std::to_string(n) +
                        " nodes on the segment: Identify Events global would make every one "
                        "answer with all its events; the addressed form is judged (--thorough "
                        "asks it)");
    const auto& pip = run.probe<PipProbe>().reply;
    const EventAnswers& a = run.probe<EventAnswers>(IdentifyTo::kEveryNode);
    const std::string got = "Identify Events global answered with " + a.describe();
    if (!pip) {
        if (a.empty())
            return out.skip("no Protocol Support Reply and no answer to Identify Events global");
        return out.pass(got + " (no Protocol Support Reply to compare with)");
    }
    // §6.2 asks for every event the node has, not that it has any: silence is a note.
    if (pip->has(Protocol::kEventExchange)) {
        if (a.empty())
            return out.warn(
                "Identify Events global not answered although the PIP has the Event "
                "Exchange bit: a node with no events, or one that does not answer");
        return out.pass(got);
    }
    out.judge(a.empty(),
              a.empty() ? "Identify Events global not answered, as PIP has no Event Exchange bit"
                        : got + " although PIP has no Event Exchange bit",
              "silence (no Event Exchange bit)", a.describe());
}

// Lines naming each event or range one answer has and the other lacks.
std::vector<std::string> differences(const EventAnswers& global, const EventAnswers& addressed) {
    std::vector<std::string> out;
    auto compare = [&](const std::set<std::uint64_t>& g, const std::set<std::uint64_t>& a,
                       const std::string& what) {
        for (std::uint64_t id : g)
            if (!a.count(id))
                out.push_back(event_text(id) + ": " + what + " in the global answer only");
        for (std::uint64_t id : a)
            if (!g.count(id))
                out.push_back(event_text(id) + ": " + what + " in the addressed answer only");
    };
    compare(global.produced, addressed.produced, "produced");
    compare(global.consumed, addressed.consumed, "consumed");
    compare(global.produced_ranges, addressed.produced_ranges, "produced range");
    compare(global.consumed_ranges, addressed.consumed_ranges, "consumed range");
    return out;
}

void identify_addressed(CheckRun& run, const CheckSpec& spec) {
    Verdict out = run.out(spec);
    const EventAnswers& a = run.probe<EventAnswers>(IdentifyTo::kTheNode);
    if (has_event_bit(run) && a.empty())
        return out.warn(
            "Identify Events addressed not answered although the PIP has the Event "
            "Exchange bit: a node with no events, or one that does not answer");
    if (crowd(run) != 0)
        return out.pass("Identify Events addressed answered with " + a.describe() +
                        " (not compared with global: see events.identify-global)");
    const EventAnswers& g = run.probe<EventAnswers>(IdentifyTo::kEveryNode);
    std::vector<std::string> diff = differences(g, a);
    if (diff.empty())
        return out.pass(a.empty() ? "Identify Events addressed and global both unanswered"
                                  : "Identify Events addressed answered with " + a.describe() +
                                        ", the same events as global");
    const std::string message =
        "the answer to Identify Events addressed differs from the global "
        "one (" +
        std::to_string(diff.size()) + " differences; first " + diff.front() + ")";
    if (diff.size() > kMaxDetails) diff.resize(kMaxDetails);
    out.add(Status::kFail, message, "the events of the global answer", a.describe(),
            std::move(diff));
}

// ---- events.cdi-events-identified ----

// The event IDs the CDI's variables hold, each once with the first variable holding it (zero IDs
// mean "not set" and are left out).
std::map<std::uint64_t, std::string> distinct_ids(const EventVars& ev) {
    std::map<std::uint64_t, std::string> ids;
    for (const EventVar& v : ev.vars)
        if (v.value && *v.value != 0) ids.emplace(*v.value, v.key);
    return ids;
}

// Asks each of missing (up to kMaxFollowUps) by Identify Producer and Identify Consumer; removes
// those answered.
void follow_up(CheckRun& run, std::map<std::uint64_t, std::string>& missing) {
    std::vector<Ask> asks;
    for (const auto& [id, path] : missing) {
        if (asks.size() >= 2 * kMaxFollowUps) break;
        asks.push_back({id, true});
        asks.push_back({id, false});
    }
    if (asks.empty()) return;
    const std::vector<bool> answered =
        ask_all(run.session(), run.alias(), asks, std::vector<bool>(asks.size(), false),
                windows_of(run.options()));
    for (std::size_t i = 0; i < asks.size(); ++i)
        if (answered[i]) missing.erase(asks[i].id);
}

void cdi_events_identified(CheckRun& run, const CheckSpec& spec) {
    Verdict out = run.out(spec);
    const auto& layout = run.probe<CdiDownload>().layout;
    if (!layout) return out.skip("depends on cdi.valid: no layout");
    EventVars ev = event_vars(*layout);
    if (ev.vars.empty()) return out.skip("the CDI has no <eventid>");
    read_values(run.session(), run.node(), ev, [&](const MemResult& r) { run.note(r); });
    const std::map<std::uint64_t, std::string> ids = distinct_ids(ev);
    const std::string cap = ev.capped ? " (the first " + std::to_string(kMaxEventVars) +
                                            " eventid variables; the CDI has more)"
                                      : "";
    const std::string unread =
        ev.unreadable.empty() ? "" : "; " + std::to_string(ev.unreadable.size()) + " unreadable";
    if (ids.empty())
        return out.skip("every eventid variable read holds 00.00.00.00.00.00.00.00 (not set)" +
                        cap + unread);
    const EventAnswers& a = reference_answers(run);
    std::map<std::uint64_t, std::string> missing;
    for (const auto& [id, path] : ids)
        if (!a.produces(id) && !a.consumes(id)) missing.emplace(id, path);
    follow_up(run, missing);
    if (missing.empty() && ev.unreadable.empty())
        return out.pass("all " + std::to_string(ids.size()) +
                        " event IDs of the CDI's eventid variables identified" + cap);
    std::vector<std::string> details;
    details.reserve(missing.size() + ev.unreadable.size());
    for (const auto& [id, path] : missing) details.push_back(path + " = " + event_text(id));
    for (const std::string& u : ev.unreadable) details.push_back("unreadable: " + u);
    if (details.size() > kMaxDetails) details.resize(kMaxDetails);
    if (missing.empty())
        return out.warn("all event IDs read identified" + cap + unread, std::move(details));
    out.warn(std::to_string(missing.size()) + " of " + std::to_string(ids.size()) +
                 " event IDs of the CDI not identified by Identify Events nor by Identify "
                 "Producer/Consumer (a CDI does not say whether an event is produced or consumed)" +
                 cap + unread,
             std::move(details));
}

// ---- events.identify-producer-consumer ----

// An event ID the node neither produces nor consumes (nullopt if the few tried are all its own).
std::optional<std::uint64_t> unknown_event(const EventAnswers& a) {
    for (std::uint64_t id = kUnknownEvent; id > kUnknownEvent - 16; --id)
        if (!a.produces(id) && !a.consumes(id)) return id;
    return std::nullopt;
}

// §6.3/§6.4 owe an answer for the node's own events (a missing one FAILs); none forbids
// answering another's (WARN).
void judge_identify_answers(Verdict& out, const std::vector<std::string>& wrong,
                            std::vector<std::string> parts) {
    const bool missing = std::any_of(wrong.begin(), wrong.end(), [](const std::string& w) {
        return w.find("(not the node's)") == std::string::npos;
    });
    const std::string first = wrong.front() + (wrong.size() > 1 ? " (and more: see details)" : "");
    if (!missing) return out.warn(first, std::move(parts));
    out.add(Status::kFail, first, "Identified for the node's events", wrong.front(),
            std::move(parts));
}

// The asks of events.identify-producer-consumer: the first identified produced and consumed
// event (an answer owed each), and an event the node identified in neither role (silence owed).
std::vector<EventWindow::Ask> identify_asks(CheckRun& run) {
    const EventAnswers& a = reference_answers(run);
    std::vector<EventWindow::Ask> asks;
    if (!a.produced.empty()) asks.push_back({*a.produced.begin(), true, true, false});
    if (!a.consumed.empty()) asks.push_back({*a.consumed.begin(), false, true, false});
    if (const std::optional<std::uint64_t> unknown = unknown_event(a)) {
        asks.push_back({*unknown, true, false, false});
        asks.push_back({*unknown, false, false, false});
    }
    return asks;
}

// The node's Identified messages, each scan resuming where the previous one stopped: marks the
// asks they answer and keeps when the latest came.
struct AskTally {
    std::uint16_t alias = 0;
    std::size_t scanned = 0;
    TimePoint last{};

    // True when every owed ask is answered.
    bool scan(Session& s, std::vector<EventWindow::Ask>& asks) {
        for (const ReceivedMessage& r : s.messages_since(scanned)) {
            if (r.message.source.alias != alias || !is_identification(r.message.mti)) continue;
            last = std::max(last, r.at);
            for (EventWindow::Ask& k : asks)
                if (answers_ask(r.message, {k.id, k.producer})) k.answered = true;
        }
        scanned = s.message_mark();
        return std::all_of(asks.begin(), asks.end(),
                           [](const EventWindow::Ask& k) { return k.answered || !k.owed; });
    }
};

EventWindow event_window(CheckRun& run) {
    Session& s = run.session();
    const Windows w = windows_of(run.options());
    const CheckSelection& selected = run.options().selection;
    EventWindow out;
    if (selected.wants_id("events.identify-producer-consumer")) out.asks = identify_asks(run);
    AskTally tally{run.alias(), s.message_mark(), {}};
    for (const EventWindow::Ask& k : out.asks) send_identify(s, {k.id, k.producer});
    const TimePoint sent = s.link().now();
    tally.last = sent;
    if (!out.asks.empty()) s.run_until([&] { return tally.scan(s, out.asks); }, w.answer);
    // The PCERs only once the owed answers are in: a node they upset has answered already.
    TimePoint watched = s.link().now();
    const NodeTrack before = s.track(run.node().id);
    if (selected.wants_id("events.pcer-payload-tolerated")) {
        out.pcers = true;
        inject_payload_pcers(s);
        // The answer shows the PCERs were carried: the restart watch starts then, not after
        // their modelled bus time.
        out.carried = s.ping(run.node(), run.options().answer_window);
        if (out.carried) watched = s.link().now() + run.options().window;
    }
    const TimePoint stop = sent + w.answer * 10;
    for (std::size_t seen = s.message_mark();;) {
        tally.scan(s, out.asks);
        const TimePoint quiet = out.asks.empty() ? watched : std::min(stop, tally.last + w.quiet);
        const TimePoint until = std::max(watched, quiet);
        const TimePoint now = s.link().now();
        if (now >= until) break;
        s.run_until([&] { return s.message_mark() != seen; }, until - now);
        seen = s.message_mark();
    }
    if (out.pcers) {
        out.restarted = s.track(run.node().id).restarted_since(before);
        out.still_answers = out.carried && s.ping(run.node(), run.options().answer_window);
    }
    return out;
}

void identify_producer_consumer(CheckRun& run, const CheckSpec& spec) {
    Verdict out = run.out(spec);
    const EventAnswers& a = reference_answers(run);
    const EventWindow& window = run.probe<EventWindow>();
    if (window.asks.empty()) return out.skip("every event ID tried is the node's own");
    std::vector<std::string> parts, wrong;
    for (const EventWindow::Ask& k : window.asks) {
        const std::string what =
            std::string(k.producer ? "Identify Producer " : "Identify Consumer ") +
            event_text(k.id);
        const std::string reply = k.producer ? "Producer Identified" : "Consumer Identified";
        if (k.owed && !k.answered) wrong.push_back(std::string(what).append(": no ").append(reply));
        if (!k.owed && k.answered)
            wrong.push_back(std::string(what).append(" (not the node's): ").append(reply));
        parts.push_back(std::string(what).append(": ").append(k.owed ? reply : "silence"));
    }
    if (a.produced.empty()) parts.push_back("no produced event identified to ask for");
    if (a.consumed.empty()) parts.push_back("no consumed event identified to ask for");
    std::string all;
    for (const std::string& p : parts) all += (all.empty() ? "" : "; ") + p;
    if (wrong.empty()) return out.pass(all);
    judge_identify_answers(out, wrong, std::move(parts));
}

// ---- events.follow-write (write phase) ----

CheckResult follow_result(Status status, std::string message, std::string expected = {},
                          std::string seen = {}) {
    return {"events.follow-write", Category::kEvents,   status,         std::move(message),
            std::string(kInquiry), std::move(expected), std::move(seen)};
}

// The variable to rewrite: identified exactly (its role known), its value held by no other
// eventid variable (the old value must then go unidentified), not protected, selected.
const EventVar* follow_target(const EventVars& ev, const EventAnswers& a,
                              const ProtectionRules& rules, std::string& why) {
    std::map<std::uint64_t, int> uses;
    for (const EventVar& v : ev.vars)
        if (v.value) ++uses[*v.value];
    for (const EventVar& v : ev.vars) {
        if (!v.value || *v.value == 0 || uses[*v.value] != 1) continue;
        if (!a.produced.count(*v.value) && !a.consumed.count(*v.value)) continue;
        if (!v.protection.empty() || !selection_reason(rules, v.key).empty()) continue;
        return &v;
    }
    why = "no eventid variable is identified exactly, unique, unprotected and selected";
    return nullptr;
}

// 05.01.01.01.3F.FE.xx.yy from the address, stepped past any event ID the node already has.
std::uint64_t follow_value(const EventVar& v, const EventVars& ev, const EventAnswers& a) {
    std::uint64_t id = kFollowBase | (v.address & 0xFFFF);
    auto taken = [&](std::uint64_t x) {
        return a.produces(x) || a.consumes(x) ||
               std::any_of(ev.vars.begin(), ev.vars.end(),
                           [&](const EventVar& o) { return o.value == x; });
    };
    for (int i = 0; i < 0x10000 && taken(id); ++i) id = kFollowBase | ((id + 1) & 0xFFFF);
    return id;
}

struct FollowRun {
    Session& s;
    const NodeInfo& node;
    Windows w;
    std::vector<CheckResult> out;

    MemResult write_id(const EventVar& v, std::uint64_t id) {
        const auto bytes = EventId(id).to_bytes();
        return s.write(node, static_cast<memory::Space>(v.space), v.address, bytes);
    }
    void update_complete() { s.command(node, memory::encode(memory::UpdateComplete{})); }

    // What the variable reads: its event ID, or what the read did.
    std::string read_back(const EventVar& v, bool& original) {
        const MemResult back = s.read(node, static_cast<memory::Space>(v.space), v.address, 8);
        const auto got = back.ok ? EventId::from_bytes(back.data) : std::nullopt;
        original = got && got->value() == *v.value;
        return got ? event_text(got->value()) : describe(back);
    }
    // Writes the original back (twice at most) until it reads back, then Update Complete: ""
    // when it came back, else what the variable reads.
    std::string restore(const EventVar& v) {
        bool original = false;
        std::string seen = read_back(v, original);
        for (int attempt = 0; attempt < 2 && !original; ++attempt) {
            write_id(v, *v.value);
            seen = read_back(v, original);
        }
        update_complete();
        return original ? "" : seen;
    }
    void restore_failed(const EventVar& v, const std::string& seen) {
        out.push_back(follow_result(Status::kFail,
                                    v.key + ": original not restored (" + event_text(*v.value) +
                                        " written back, it reads " + seen + ")",
                                    event_text(*v.value), seen));
        out.push_back({"encoding.original-restored", Category::kEncoding, Status::kFail,
                       v.key + ": original " + event_text(*v.value) +
                           " did not read back after events.follow-write (reads " + seen + ")",
                       "", event_text(*v.value), seen});
    }
    void run(const EventVar& v, const EventAnswers& a, std::uint64_t id);
};

// Asks for the new ID and the old one in the variable's roles; "" when the node identifies the
// new one and not the old one, else what went wrong.
std::string follow_asks(FollowRun& f, const EventVar& v, const EventAnswers& a, std::uint64_t id) {
    std::vector<Ask> asks;
    std::vector<bool> expected;
    for (bool producer : {true, false}) {
        if (!(producer ? a.produced : a.consumed).count(*v.value)) continue;
        asks.push_back({id, producer});
        asks.push_back({*v.value, producer});
        expected.insert(expected.end(), {true, false});
    }
    const std::vector<bool> answered = ask_all(f.s, f.s.alias_of(f.node), asks, expected, f.w);
    std::string wrong;
    for (std::size_t i = 0; i < asks.size(); ++i) {
        if (answered[i] == expected[i]) continue;
        const std::string ask =
            std::string(asks[i].producer ? "Identify Producer " : "Identify Consumer ") +
            event_text(asks[i].id);
        wrong += (wrong.empty() ? "" : "; ") + ask +
                 (expected[i] ? ": no answer" : ": still identified (the original)");
    }
    return wrong;
}

void FollowRun::run(const EventVar& v, const EventAnswers& a, std::uint64_t id) {
    const std::string what = "after writing " + event_text(id) + " into " + v.key + " (space " +
                             hex(v.space, 2) + " at " + hex(v.address, 8) + ") and Update Complete";
    const MemResult written = write_id(v, id);
    if (!written.ok) {
        const std::string seen = restore(v);
        if (!seen.empty()) return restore_failed(v, seen);
        out.push_back(follow_result(Status::kSkip, "writing " + event_text(id) + " into " + v.key +
                                                       ": " + describe(written) + "; not tested"));
        return;
    }
    update_complete();
    const std::string wrong = follow_asks(*this, v, a, id);
    const std::string seen = restore(v);
    if (!seen.empty()) return restore_failed(v, seen);
    if (wrong.empty())
        out.push_back(
            follow_result(Status::kPass, what + ", the node identifies it and no longer " +
                                             event_text(*v.value) + "; the original is back"));
    else
        out.push_back(follow_result(Status::kFail, what + ": " + wrong,
                                    "the new event ID identified, the old one not", wrong));
}

}  // namespace

std::vector<CheckResult> events_follow_write(Session& session, const NodeInfo& node,
                                             const CheckContext& ctx,
                                             const ProtectionRules& rules) {
    FollowRun f{session, node, windows_of(ctx), {}};
    if (!ctx.layout) return {follow_result(Status::kSkip, "no CDI layout")};
    EventVars ev = event_vars(*ctx.layout);
    if (ev.vars.empty()) return {follow_result(Status::kSkip, "the CDI has no <eventid>")};
    read_values(session, node, ev, {});
    const EventAnswers a = identify_events(session, node, IdentifyTo::kTheNode, f.w.answer, f.w);
    std::string why;
    const EventVar* v = follow_target(ev, a, rules, why);
    if (!v) return {follow_result(Status::kSkip, why + "; nothing written")};
    f.run(*v, a, follow_value(*v, ev, a));
    return std::move(f.out);
}

std::vector<CheckSpec> event_checks() {
    return {
        {"events.identify-global", 610, Category::kEvents,
         "EventTransportS §6.2; MessageNetworkS §3.3.7", Strength::kShall,
         "Identify Events is answered for every event the node produces or consumes; a node with "
         "the Event Exchange bit and no events WARNs",
         "ev20",
         "Identify Events global: Producer/Consumer (Range) Identified from the node until quiet; "
         "at least one with the PIP Event Exchange bit, none without",
         identify_global},
        {"events.identify-addressed", 620, Category::kEvents, kInquiry, Strength::kShall,
         "the addressed Identify Events is answered like the global one", "ev10",
         "Identify Events addressed: the same produced/consumed events and ranges as global "
         "(asked after the global one's answers ended, never while the node answers it)",
         identify_addressed},
        {"events.cdi-events-identified", 630, Category::kEvents,
         "ConfigurationDescriptionInformationS §5.1.4.4; EventTransportS §6.2", Strength::kNone,
         "an eventid variable is storage; nothing says the node produces or consumes it (WARN)", "",
         "every non-zero event ID the CDI's eventid variables hold (read from the node, at most "
         "512) is identified by Identify Events or Identify Producer/Consumer; WARN lists others",
         cdi_events_identified},
        {"events.identify-producer-consumer", 640, Category::kEvents, "EventTransportS §6.3, §6.4",
         Strength::kShall,
         "Identify Producer/Consumer of the node's own event is answered; answering a foreign "
         "event is not forbidden (WARN)",
         "ev30, ev40",
         "Identify Producer/Consumer of an identified produced/consumed event: its Identified "
         "message; of 05.01.01.01.3F.FF.FF.FE (not the node's): silence",
         identify_producer_consumer},
    };
}

std::vector<CheckSpec> event_phase_checks() {
    return {
        {"events.follow-write", 970, Category::kEvents,
         "EventTransportS §6.2; MemoryConfigurationTN §2.4.23", Strength::kNone,
         "when written configuration takes effect is the node's choice (WARN)", "",
         "write phase: 05.01.01.01.3F.FE.xx.yy into one identified, unprotected eventid "
         "variable, Update Complete: the new ID identified, the old not; original back and read",
         nullptr},
    };
}

}  // namespace olcb::conform::checks

namespace olcb::conform {

EventAnswers EventAnswers::ask(CheckRun& run, IdentifyTo to) {
    return checks::answers_of(run, to);
}

EventWindow EventWindow::ask(CheckRun& run) {
    return checks::event_window(run);
}

}  // namespace olcb::conform
