// Train Control (TrainControlS): the Is Train event, the memory spaces, the controller and the
// reservation, and (only on a node named with --node, since they change the train's state) speed
// and direction, functions, the emergency stops, listeners and their forwarding, the heartbeat.
// Every check that moves the train takes control first, as a throttle must (§6.1), and gives it
// back with the speed at zero in the direction the train had.
#include <algorithm>
#include <variant>

#include "base/hex.hpp"
#include "conformance/checks/checks.hpp"
#include "openlcb/addressed_framing.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform::checks {

namespace tr = olcb::train;

namespace {

using namespace std::chrono_literals;

// The speeds the checks set: OlcbChecker's 0.75 for set/query, 0.5 where the train only needs to
// move; both exact in float16.
tr::Speed fast() {
    return tr::Speed::of(0.75, false);
}
tr::Speed slow() {
    return tr::Speed::of(0.5, false);
}
// The longest a train's first Heartbeat Request is awaited with --thorough (TrainControlTN §2.6.6
// suggests a 10 s period); without it, the short wait: heartbeats are optional, and 12 s of
// nothing on a train without them was most of a train node's run.
constexpr std::chrono::seconds kHeartbeatWait{12};
constexpr std::chrono::seconds kHeartbeatShortWait{3};
// Made-up listeners of train.listener: never on the segment, so nothing is forwarded to them.
constexpr NodeId kListenerA{kOtherNodeId + 0x10};
constexpr NodeId kListenerB{kOtherNodeId + 0x11};

std::string ms_text(Duration d) {
    return std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(d).count()) + " ms";
}

NodeId me(CheckRun& run) {
    return run.session().tool_id();
}

std::string flags_text(std::uint8_t flags) {
    return hex(flags, 2);
}

// "" when the check may change the train's state; otherwise why it SKIPs.
std::string may_drive(CheckRun& run, bool whole_layout = false) {
    return train_may_drive(run, whole_layout);
}

using Driving = TrainDriving;

// Sets a speed and reads it back: "" when the Set Speed reads back as sent, else why not.
std::string set_and_read(CheckRun& run, tr::Speed speed, tr::SpeedsReply* got = nullptr) {
    train_send(run, {tr::SetSpeed{speed}});
    std::string why;
    const auto r = train_ask<tr::SpeedsReply>(run, {tr::QuerySpeeds{}}, why);
    if (!r) return "Query Speeds after Set Speed " + speed.to_string() + ": " + why;
    if (got) *got = *r;
    if (r->set == speed) return {};
    return "Set Speed " + speed.to_string() + " (" + hex(speed.bits(), 4) + ") read back as " +
           r->set.to_string() + " (" + hex(r->set.bits(), 4) + ")";
}

void train_is_train(CheckRun& run, const CheckSpec& spec) {
    Session& s = run.session();
    Message m;
    m.mti = Mti::kIdentifyProducer;
    const auto raw = tr::kIsTrain.to_bytes();
    m.payload.assign(raw.begin(), raw.end());
    const std::size_t mark = s.message_mark();
    s.send(std::move(m));
    const auto identified = [&](const Message& r) {
        return r.source.alias == run.alias() &&
               (r.mti == Mti::kProducerIdentifiedValid ||
                r.mti == Mti::kProducerIdentifiedInvalid ||
                r.mti == Mti::kProducerIdentifiedUnknown) &&
               EventId::from_bytes(r.payload) == tr::kIsTrain;
    };
    const bool got = s.run_until(
        [&] {
            const auto since = s.messages_since(mark);
            return std::any_of(since.begin(), since.end(),
                               [&](const ReceivedMessage& r) { return identified(r.message); });
        },
        run.options().answer_window);
    run.out(spec).judge(got,
                        got ? "Identify Producer Is Train answered with Producer Identified"
                            : "no Producer Identified for Is Train (01.01.00.00.00.00.03.03)",
                        "Producer Identified 01.01.00.00.00.00.03.03", "no answer");
}

void train_memory_spaces(CheckRun& run, const CheckSpec& spec) {
    const auto& pip = run.probe<PipProbe>().reply;
    const SpaceInfo& f9 = run.probe<SpaceInfoProbe>(tr::kFunctionSpace);
    const std::string f9_text =
        f9.present ? "0xF9 present" : "0xF9 (functions, optional) not present";
    // A node claiming FDI owes 0xFA: fdi.space judges it.
    if (pip && pip->has(Protocol::kFdi))
        return run.out(spec).pass(f9_text + "; FDI claimed (0xFA: see fdi.space)");
    const SpaceInfo& fa = run.probe<SpaceInfoProbe>(tr::kFdiSpace);
    if (fa.present)
        return run.out(spec).pass(f9_text + "; 0xFA present although the PIP claims no FDI");
    const std::string asked = fa.answered ? "Space Info says not present" : "no Space Info reply";
    // OlcbChecker tr070 FAILs this ("required space 0xFA not present"); §3 only recommends it.
    run.out(spec).warn(f9_text + "; no FDI (0xFA: " + asked +
                       "): a train node is strongly recommended to provide FDI (§3)");
}

void train_controller(CheckRun& run, const CheckSpec& spec) {
    std::string why;
    const auto before = train_ask<tr::ControllerReply>(run, {tr::QueryController{}}, why);
    if (!before)
        return run.out(spec).fail("Query Controller: " + why, "Query Controller Reply", why);
    if (!before->controller.is_zero() && before->controller != me(run))
        return run.out(spec).pass("Query Controller answered: controlled by " +
                                  before->controller.to_string() + " (not taken from it)");
    if (!may_drive(run).empty())
        return run.out(spec).pass(
            "Query Controller answered (no controller); assign and release "
            "run only on a node named with --node");
    const TimePoint sent = run.session().link().now();
    const auto a = train_ask<tr::AssignReply>(run, {tr::AssignController{0, me(run)}}, why);
    const Duration took = run.session().link().now() - sent;
    if (!a) return run.out(spec).fail("Assign Controller: " + why, "Assign Controller Reply", why);
    const auto q = train_ask<tr::ControllerReply>(run, {tr::QueryController{}}, why);
    train_send(run, {tr::ReleaseController{0, me(run)}});
    const auto after = train_ask<tr::ControllerReply>(run, {tr::QueryController{}}, why);
    if (a->result != tr::assign_result::kOk)
        return run.out(spec).pass("Assign Controller refused (result " + hex(a->result, 2) +
                                  "): a train may refuse (§6.1)");
    if (took > base::kRequesterTimeout)
        return run.out(spec).fail("Assign Controller answered after " + ms_text(took),
                                  "a reply within 3 s (§6.1)", ms_text(took));
    if (!q || q->controller != me(run))
        return run.out(spec).fail("after Assign Controller, Query Controller names " +
                                      (q ? q->controller.to_string() : why),
                                  me(run).to_string(), q ? q->controller.to_string() : why);
    if (!after || !after->controller.is_zero())
        return run.out(spec).fail("after Release Controller, Query Controller names " +
                                      (after ? after->controller.to_string() : why),
                                  "00.00.00.00.00.00", after ? after->controller.to_string() : why);
    // The flags byte is reserved (OlcbChecker tr090 expects bit 0 set while assigned).
    run.out(spec).pass("Assign Controller OK in " + ms_text(took) +
                       ", Query Controller named lcc-conform (flags " + flags_text(q->flags) +
                       ", reserved), Release Controller cleared it");
}

void train_reserve(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_drive(run); !why.empty()) return run.out(spec).skip(why);
    std::string why;
    const auto first = train_ask<tr::ReserveReply>(run, {tr::Reserve{}}, why);
    if (!first) return run.out(spec).fail("Reserve: " + why, "Reserve Reply", why);
    if (first->result != 0)
        return run.out(spec).pass("Reserve refused (result " + hex(first->result, 2) +
                                  "): reserved by another node");
    const auto again = train_ask<tr::ReserveReply>(run, {tr::Reserve{}}, why);
    train_send(run, {tr::Release{}});
    const auto after = train_ask<tr::ReserveReply>(run, {tr::Reserve{}}, why);
    train_send(run, {tr::Release{}});
    run.session().wait(0ms);
    if (!again || !after)
        return run.out(spec).fail("a Reserve got no Reserve Reply (" + why + ")", "Reserve Reply",
                                  why);
    // The standard gives Reserve no rules beyond its reply: both answers to a second Reserve
    // conform (OlcbChecker tr100 wants it accepted, its plan's other section refused).
    run.out(spec).pass("Reserve OK; a second Reserve from lcc-conform " +
                       std::string(again->result == 0 ? "accepted" : "refused") + " (" +
                       hex(again->result, 2) + "); after Release, Reserve " +
                       (after->result == 0 ? "OK" : "refused " + hex(after->result, 2)));
}

void train_speed(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_drive(run); !why.empty()) return run.out(spec).skip(why);
    Driving d(run);
    if (!d.blocked().empty()) return run.out(spec).skip(d.blocked());
    // Direction at zero too: the sign of ±0 is the train's direction (TN §2.5).
    for (tr::Speed speed :
         {fast().flipped(), tr::Speed::of(0, true), fast(), tr::Speed::of(0, false)}) {
        if (const std::string bad = set_and_read(run, speed); !bad.empty())
            return run.out(spec).fail(bad, speed.to_string() + " (" + hex(speed.bits(), 4) + ")",
                                      bad);
    }
    run.out(spec).pass(
        "Set Speed 0.75 reverse, 0 reverse, 0.75 forward, 0 forward each read back "
        "exactly (the direction of zero too)");
}

void train_function(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_drive(run); !why.empty()) return run.out(spec).skip(why);
    std::string why;
    const auto original = train_ask<tr::FunctionReply>(run, {tr::QueryFunction{0}}, why);
    if (!original)
        return run.out(spec).fail("Query Function F0: " + why, "Query Function Reply", why);
    Driving d(run);
    if (!d.blocked().empty()) return run.out(spec).skip(d.blocked());
    std::string bad;
    for (const std::uint16_t value : {std::uint16_t{1}, std::uint16_t{0}}) {
        train_send(run, {tr::SetFunction{0, value}});
        const auto r = train_ask<tr::FunctionReply>(run, {tr::QueryFunction{0}}, why);
        if (!r || r->value != value) {
            bad = "Set Function F0 = " + std::to_string(value) + " read back as " +
                  (r ? std::to_string(r->value) : why);
            break;
        }
    }
    if (original->value != 0) train_send(run, {tr::SetFunction{0, original->value}});
    if (!bad.empty()) return run.out(spec).fail(bad, "the value set", bad);
    run.out(spec).pass("F0 set on (1) and off (0), each read back by Query Function");
}

void train_estop(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_drive(run); !why.empty()) return run.out(spec).skip(why);
    Driving d(run);
    if (!d.blocked().empty()) return run.out(spec).skip(d.blocked());
    auto v = run.out(spec);
    if (const auto bad = set_and_read(run, slow().flipped()); !bad.empty())
        return v.skip("depends on train.speed: " + bad);
    train_send(run, {tr::EmergencyStop{}});
    std::string why;
    const auto stopped = train_ask<tr::SpeedsReply>(run, {tr::QuerySpeeds{}}, why);
    if (!stopped) return v.fail("Query Speeds after Emergency Stop: " + why, "a reply", why);
    if (stopped->set != tr::Speed::of(0, true))
        return v.fail("after Emergency Stop the Set Speed is " + stopped->set.to_string(),
                      "0 reverse: zero, the direction kept (§6.2)", stopped->set.to_string());
    if ((stopped->status & tr::kStatusEmergencyStop) == 0)
        return v.fail("after Emergency Stop the status byte is " + hex(stopped->status, 2),
                      "bit 0 set (Emergency Stop state, §4.4)", hex(stopped->status, 2));
    tr::SpeedsReply resumed;
    if (const auto bad = set_and_read(run, slow(), &resumed); !bad.empty())
        return v.fail("after Emergency Stop: " + bad, slow().to_string(), bad);
    if ((resumed.status & tr::kStatusEmergencyStop) != 0)
        return v.fail("a Set Speed after Emergency Stop left status bit 0 set",
                      "bit 0 clear: a Set Speed leaves the Emergency Stop state (§5)",
                      hex(resumed.status, 2));
    v.pass(
        "Emergency Stop: Set Speed 0 reverse, E-Stop bit set; a Set Speed 0.5 forward "
        "left the state");
}

// Global Emergency Stop (or Off): the Set Speed stays, a Set Speed during it is kept, the
// E-Stop status bit (Emergency Stop only) stays clear.
void global_stop(CheckRun& run, const CheckSpec& spec, EventId enter, EventId leave) {
    if (const auto why = may_drive(run, true); !why.empty()) return run.out(spec).skip(why);
    Driving d(run);
    if (!d.blocked().empty()) return run.out(spec).skip(d.blocked());
    auto v = run.out(spec);
    if (const auto bad = set_and_read(run, slow().flipped()); !bad.empty())
        return v.skip("depends on train.speed: " + bad);
    const auto report = [&](EventId id) {
        Message m;
        m.mti = Mti::kEventReport;
        const auto raw = id.to_bytes();
        m.payload.assign(raw.begin(), raw.end());
        run.session().send(std::move(m));
    };
    report(enter);
    std::string why;
    const auto during = train_ask<tr::SpeedsReply>(run, {tr::QuerySpeeds{}}, why);
    std::string bad;
    if (!during) {
        bad = "Query Speeds: " + why;
    } else if (during->set != slow().flipped()) {
        bad = "the event changed the Set Speed to " + during->set.to_string();
    } else {
        bad = set_and_read(run, slow());  // a Set Speed during the state is taken
    }
    report(leave);
    run.session().wait(0ms);
    if (!bad.empty())
        return v.fail(bad, "Set Speed unchanged by the event, a new Set Speed kept (§6.2)", bad);
    v.pass(enter.to_string() +
           " left the Set Speed 0.5 reverse as it was; Set Speed 0.5 forward "
           "during it read back; cleared with " +
           leave.to_string());
}

void train_global_stop(CheckRun& run, const CheckSpec& spec) {
    global_stop(run, spec, tr::kEmergencyStopAll, tr::kClearEmergencyStopAll);
}

void train_global_off(CheckRun& run, const CheckSpec& spec) {
    global_stop(run, spec, tr::kEmergencyOffAll, tr::kClearEmergencyOffAll);
}

// The listener list as the train reports it: count and every entry (index order).
struct ListenerList {
    std::uint8_t count = 0;
    std::vector<tr::ListenerEntry> entries;
};

std::optional<ListenerList> query_listeners(CheckRun& run, std::string& why) {
    const auto head = train_ask<tr::ListenersReply>(run, {tr::QueryListeners{}}, why);
    if (!head) return std::nullopt;
    ListenerList list{head->count, {}};
    for (std::uint8_t i = 0; i < head->count; ++i) {
        const auto one = train_ask<tr::ListenersReply>(run, {tr::QueryListeners{i}}, why);
        if (!one || !one->entry) {
            why = "Query Nodes index " + std::to_string(i) + " of " + std::to_string(head->count) +
                  ": " + (one ? "no entry in the reply" : why);
            return std::nullopt;
        }
        list.entries.push_back(*one->entry);
    }
    return list;
}

// The code of an Attach or Detach Node Reply for node, nullopt when none came (why set).
std::optional<std::uint16_t> change_listener(CheckRun& run, const tr::Command& c, NodeId node,
                                             std::string& why) {
    const auto r = train_ask<tr::ListenerChangeReply>(run, c, why);
    if (!r) return std::nullopt;
    if (r->listener != node) {
        why = "the reply names " + r->listener.to_string() + ", not " + node.to_string();
        return std::nullopt;
    }
    return r->code;
}

// "" when the list is `before` followed by `added` (node, flags) in order; else what differs.
std::string list_differs(const ListenerList& now, const ListenerList& before,
                         const std::vector<tr::ListenerEntry>& added) {
    const std::size_t want = before.entries.size() + added.size();
    if (now.entries.size() != want)
        return std::to_string(now.entries.size()) + " listeners, expected " + std::to_string(want);
    for (std::size_t k = 0; k < added.size(); ++k) {
        const tr::ListenerEntry& e = now.entries[before.entries.size() + k];
        if (e.node != added[k].node || e.flags != added[k].flags)
            return "index " + std::to_string(e.index) + " is " + e.node.to_string() + " flags " +
                   flags_text(e.flags) + ", expected " + added[k].node.to_string() + " flags " +
                   flags_text(added[k].flags);
    }
    return {};
}

// The listener steps of train.listener: "" when all held, else the first that did not.
std::string listener_steps(CheckRun& run, const ListenerList& before) {
    namespace lf = tr::listener_flags;
    std::string why;
    const auto attach = [&](NodeId n, std::uint8_t f) {
        return change_listener(run, {tr::AttachListener{f, n}}, n, why);
    };
    const auto expect = [&](const std::vector<tr::ListenerEntry>& added) -> std::string {
        const auto now = query_listeners(run, why);
        return now ? list_differs(*now, before, added) : why;
    };
    if (const auto c = attach(kListenerA, lf::kReverse); c != 0)
        return "Attach Node A: " + (c ? "code " + hex(*c, 4) : why);
    if (const auto c = attach(kListenerB, lf::kLinkF0); c != 0)
        return "Attach Node B: " + (c ? "code " + hex(*c, 4) : why);
    if (auto bad = expect({{0, lf::kReverse, kListenerA}, {0, lf::kLinkF0, kListenerB}});
        !bad.empty())
        return "after attaching A and B: " + bad;
    // New flags for A keep its place (§5).
    if (const auto c = attach(kListenerA, lf::kReverse | lf::kLinkFn); c != 0)
        return "Attach Node A again (new flags): " + (c ? "code " + hex(*c, 4) : why);
    if (auto bad =
            expect({{0, lf::kReverse | lf::kLinkFn, kListenerA}, {0, lf::kLinkF0, kListenerB}});
        !bad.empty())
        return "after updating A's flags (the order shall not change, §5): " + bad;
    const auto detach_a =
        change_listener(run, {tr::DetachListener{0, kListenerA}}, kListenerA, why);
    if (detach_a != 0) return "Detach Node A: " + (detach_a ? "code " + hex(*detach_a, 4) : why);
    if (auto bad = expect({{0, lf::kLinkF0, kListenerB}}); !bad.empty())
        return "after detaching A: " + bad;
    return {};
}

void train_listener(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_drive(run); !why.empty()) return run.out(spec).skip(why);
    std::string why;
    const auto before = query_listeners(run, why);
    if (!before) return run.out(spec).fail("Query Nodes: " + why, "Query Nodes Replies", why);
    if (before->count + 2 > 255) return run.out(spec).skip("the train has 254 listeners already");
    const std::string bad = listener_steps(run, *before);
    // A node not attached: the code is only suggested (Not Found 0x1030), a failure expected.
    const auto again = change_listener(run, {tr::DetachListener{0, kListenerA}}, kListenerA, why);
    for (NodeId n : {kListenerA, kListenerB})
        change_listener(run, {tr::DetachListener{0, n}}, n, why);
    if (!bad.empty()) return run.out(spec).fail(bad, "Attach/Detach/Query Nodes as §6.5 says", bad);
    if (!again)
        return run.out(spec).fail("Detach of a node not attached: " + why, "a Detach Node Reply",
                                  why);
    if (*again == 0)
        return run.out(spec).warn(
            "Detach of a node not attached answered 0x0000 (success); "
            "Not Found 0x1030 is what §6.5 suggests");
    run.out(spec).pass(
        "two listeners attached, listed in order with their flags, A's flags "
        "updated in place, A detached; detaching it again: " +
        hex(*again, 4));
}

// A second node lcc-conform speaks for: kOtherNodeId on an unused alias, reserved as CAN asks
// (CID 7..4, 200 ms, RID, AMD) so the train knows it; AMR when done. The train then sees a
// command from a source other than its listener (lcc-conform).
class OtherNode {
public:
    explicit OtherNode(CheckRun& run) : run_(run) {
        const auto free = unused_aliases(run, 1);
        if (free.empty()) return;
        alias_ = free.front();
        Session& s = run.session();
        for (int n = 7; n >= 4; --n) s.inject(can::make_cid(n, NodeId{kOtherNodeId}, alias_));
        s.wait(base::kAliasReservationWait + 20ms);
        s.inject(can::make_rid(alias_));
        s.inject(can::make_amd(alias_, NodeId{kOtherNodeId}));
        s.wait(20ms);
    }
    OtherNode(const OtherNode&) = delete;
    OtherNode& operator=(const OtherNode&) = delete;
    ~OtherNode() {
        if (alias_ == 0) return;
        run_.session().inject(can::make_amr(alias_, NodeId{kOtherNodeId}));
        run_.session().wait(0ms);
    }
    std::uint16_t alias() const { return alias_; }
    void send(const tr::Command& c) {
        Message m;
        m.mti = Mti::kTractionControlCommand;
        m.source = NodeHandle{NodeId{kOtherNodeId}, alias_};
        m.destination = NodeHandle{run_.node().id, run_.alias()};
        m.payload = tr::encode(c);
        std::vector<CanFrame> frames;
        if (encode_message(m, frames) != FramingError::kNone) return;
        for (const CanFrame& f : frames) run_.session().inject(f);
    }

private:
    CheckRun& run_;
    std::uint16_t alias_ = 0;
};

// The commands the train forwarded to lcc-conform since mark, decoded.
std::vector<tr::Command> forwarded_to_us(CheckRun& run, std::size_t mark) {
    std::vector<tr::Command> out;
    for (const ReceivedMessage& r : run.session().messages_since(mark)) {
        if (r.message.mti != Mti::kTractionControlCommand || r.message.source.alias != run.alias())
            continue;
        if (auto d = tr::decode_command(r.message.payload); d.ok()) out.push_back(*d.value);
    }
    return out;
}

// True when the node refused a command of the other node (TDE or OIR to its alias).
bool refused_other(CheckRun& run, std::size_t frame_mark, std::uint16_t other) {
    for (const CanFrame& f : run.session().frames_since(frame_mark)) {
        if (!run.from_node(f) || !can::is_message(f.id) || f.data.size() < 2) continue;
        const auto mti = can::can_mti(f.id);
        if ((mti == 0x0A8 || mti == 0x068) && can::addressed_dest(f.data[0], f.data[1]) == other)
            return true;
    }
    return false;
}

// Sends c from the other node; what the train forwarded to lcc-conform within the window.
std::vector<tr::Command> forwarded_after(CheckRun& run, OtherNode& other, const tr::Command& c,
                                         bool expect, bool& refused) {
    const std::size_t mark = run.session().message_mark();
    const std::size_t frames = run.session().frame_mark();
    other.send(c);
    if (expect) {
        run.session().run_until([&] { return !forwarded_to_us(run, mark).empty(); },
                                run.options().answer_window);
    } else {
        run.session().wait(run.options().window);
    }
    refused = refused || refused_other(run, frames, other.alias());
    return forwarded_to_us(run, mark);
}

// The forwarding steps of train.listener-forward: "" when all held, else the first that did not.
std::string forwarding_steps(CheckRun& run, OtherNode& other, bool& refused) {
    auto got = forwarded_after(run, other, {tr::SetSpeed{slow()}}, true, refused);
    if (refused) return {};
    if (got.empty()) return "Set Speed 0.5 forward from another node was not forwarded";
    const auto* s = std::get_if<tr::SetSpeed>(&got.front().body);
    if (!s || !got.front().forwarded || s->speed != slow().flipped())
        return "Set Speed 0.5 forward arrived as " + tr::describe(got.front()) +
               " (listener flags Reverse: 0.5 reverse with the P bit expected)";
    got = forwarded_after(run, other, {tr::SetFunction{0, 1}}, true, refused);
    if (got.empty() || !std::holds_alternative<tr::SetFunction>(got.front().body))
        return "Set Function F0 (Link F0 set) was not forwarded";
    got = forwarded_after(run, other, {tr::SetFunction{3, 1}}, false, refused);
    if (!got.empty()) return "Set Function F3 was forwarded although Link Fn is clear";
    // From the listener itself: never back to the source (§6.5).
    const std::size_t mark = run.session().message_mark();
    train_send(run, {tr::SetSpeed{slow().flipped()}});
    run.session().wait(run.options().window);
    if (!forwarded_to_us(run, mark).empty()) return "a Set Speed from the listener came back to it";
    return {};
}

void train_listener_forward(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_drive(run); !why.empty()) return run.out(spec).skip(why);
    Driving d(run);
    if (!d.blocked().empty()) return run.out(spec).skip(d.blocked());
    std::string why;
    namespace lf = tr::listener_flags;
    const auto code = change_listener(
        run, {tr::AttachListener{lf::kReverse | lf::kLinkF0, me(run)}}, me(run), why);
    if (code != 0)
        return run.out(spec).skip("depends on train.listener: attaching lcc-conform: " +
                                  (code ? hex(*code, 4) : why));
    std::string bad;
    bool refused = false;
    {
        OtherNode other(run);
        if (other.alias() != 0) bad = forwarding_steps(run, other, refused);
        if (other.alias() == 0) bad = "no free alias for a second source";
    }
    train_send(run, {tr::SetFunction{0, 0}});
    train_send(run, {tr::SetFunction{3, 0}});
    change_listener(run, {tr::DetachListener{0, me(run)}}, me(run), why);
    if (refused)
        return run.out(spec).skip(
            "the train refuses operations from a node that is not its "
            "controller (allowed, §6.1): forwarding not judged");
    if (bad == "no free alias for a second source") return run.out(spec).skip(bad);
    if (!bad.empty())
        return run.out(spec).fail(bad, "forwarded to the listener with the P bit (§6.5)", bad);
    run.out(spec).pass(
        "with lcc-conform a listener (Reverse, Link F0): another node's Set Speed "
        "forwarded reversed with the P bit, F0 forwarded, F3 not, lcc-conform's "
        "own Set Speed not sent back");
}

// Waits up to `wait` for a Heartbeat Request from the node; its timeout in seconds.
std::optional<std::uint8_t> await_heartbeat(CheckRun& run, Duration wait) {
    std::string why;
    const auto r = train_await(
        run, run.session().message_mark(),
        [](const tr::Reply& x) { return std::holds_alternative<tr::HeartbeatRequest>(x); }, why,
        wait);
    if (!r) return std::nullopt;
    return std::get<tr::HeartbeatRequest>(*r).timeout;
}

// The heartbeat steps once a first request came after `period`: "" when they held.
std::string heartbeat_steps(CheckRun& run, Duration period) {
    std::string why;
    // Any command clears the request: the train keeps its speed (§6.6).
    train_send(run, {tr::Noop{}});
    const auto kept = train_ask<tr::SpeedsReply>(run, {tr::QuerySpeeds{}}, why);
    if (!kept || kept->set != slow())
        return "after a No-op answered the request the Set Speed is " +
               (kept ? kept->set.to_string() : why);
    const auto second = await_heartbeat(run, period + period / 2 + run.options().answer_window);
    if (!second) return {};  // one request, no second: nothing more to judge
    // Unanswered: at the deadline the train takes a Set Speed 0 (§6.6).
    run.session().wait(std::chrono::seconds(*second) + run.options().window);
    const auto after = train_ask<tr::SpeedsReply>(run, {tr::QuerySpeeds{}}, why);
    if (!after || after->set != slow().stopped())
        return "the heartbeat deadline (" + std::to_string(*second) +
               " s) passed unanswered, "
               "the Set Speed is still " +
               (after ? after->set.to_string() : why);
    // Stopped: no more requests (§6.6).
    if (const auto more = await_heartbeat(run, period + run.options().window))
        return "a Heartbeat Request came while the Set Speed was zero";
    return {};
}

void train_heartbeat(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_drive(run); !why.empty()) return run.out(spec).skip(why);
    Driving d(run);
    if (!d.blocked().empty()) return run.out(spec).skip(d.blocked());
    if (const auto bad = set_and_read(run, slow()); !bad.empty())
        return run.out(spec).skip("depends on train.speed: " + bad);
    const TimePoint moving = run.session().link().now();
    const bool thorough = run.options().selection.thorough;
    const std::chrono::seconds wait = thorough ? kHeartbeatWait : kHeartbeatShortWait;
    const auto first = await_heartbeat(run, wait);
    if (!first)
        return run.out(spec).pass("no Heartbeat Request in " + std::to_string(wait.count()) +
                                  " s while moving: heartbeats are optional (§6.6)" +
                                  (thorough ? "" : "; --thorough waits 12 s"));
    const Duration period = run.session().link().now() - moving;
    const std::string bad = heartbeat_steps(run, period);
    if (!bad.empty()) return run.out(spec).fail(bad, "the heartbeat as §6.6 says", bad);
    run.out(spec).pass("Heartbeat Request after " + ms_text(period) + " (deadline " +
                       std::to_string(*first) +
                       " s): a No-op kept the train moving; unanswered, "
                       "it stopped, and sent no request while stopped");
}

// Set Function and the function space agree: a write of 0xF9 byte 0 reads back through Query
// Function F0 (OlcbChecker's plan, "checks in development").
void train_function_space(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_drive(run); !why.empty()) return run.out(spec).skip(why);
    const SpaceInfo& f9 = run.probe<SpaceInfoProbe>(tr::kFunctionSpace);
    if (!f9.present) return run.out(spec).skip("no function space 0xF9 (optional, §7.1)");
    if (f9.read_only) return run.out(spec).skip("space 0xF9 is read-only");
    std::string why;
    const auto original = train_ask<tr::FunctionReply>(run, {tr::QueryFunction{0}}, why);
    if (!original) return run.out(spec).skip("depends on train.function: " + why);
    Driving d(run);
    if (!d.blocked().empty()) return run.out(spec).skip(d.blocked());
    train_send(run, {tr::SetFunction{0, 0}});
    const std::vector<std::uint8_t> on{1};
    const MemResult w = run.note(
        run.session().write(run.node(), static_cast<memory::Space>(tr::kFunctionSpace), 0, on));
    const auto r = train_ask<tr::FunctionReply>(run, {tr::QueryFunction{0}}, why);
    train_send(run, {tr::SetFunction{0, original->value}});
    if (!w.ok) return run.out(spec).skip("the write of 0xF9 byte 0 failed: " + describe(w));
    if (!r || r->value != 1)
        return run.out(spec).fail(
            "0xF9 byte 0 written 1, Query Function F0 says " + (r ? std::to_string(r->value) : why),
            "1", r ? std::to_string(r->value) : why);
    run.out(spec).pass("0xF9 byte 0 written 1: Query Function F0 reads 1");
}

}  // namespace

std::string train_may_drive(CheckRun& run, bool whole_layout) {
    if (!run.options().named)
        return "changes the train's state: runs only on a node named with --node";
    if (run.options().read_only) return "--read-only: the train's state is left alone";
    if (whole_layout && !run.options().selection.thorough)
        return "stops every train on the segment for a moment: runs only with --thorough";
    return {};
}

TrainDriving::TrainDriving(CheckRun& run) : run_(run) {
    std::string why;
    const auto c = train_ask<tr::ControllerReply>(run, {tr::QueryController{}}, why);
    if (c && !c->controller.is_zero() && c->controller != me(run)) {
        blocked_ = "the train is controlled by " + c->controller.to_string() +
                   ": lcc-conform does not take it away";
        return;
    }
    if (const auto s = train_ask<tr::SpeedsReply>(run, {tr::QuerySpeeds{}}, why))
        reverse_ = s->set.reverse();
    const auto a = train_ask<tr::AssignReply>(run, {tr::AssignController{0, me(run)}}, why);
    if (!a) {
        blocked_ = "depends on train.controller: Assign Controller got no reply (" + why + ")";
    } else if (a->result != tr::assign_result::kOk) {
        blocked_ =
            "the train refused lcc-conform as its controller (result " + hex(a->result, 2) + ")";
    } else {
        held_ = true;
    }
}

TrainDriving::~TrainDriving() {
    if (!held_) return;
    train_send(run_, {tr::SetSpeed{tr::Speed::of(0, reverse_)}});
    train_send(run_, {tr::ReleaseController{0, me(run_)}});
    run_.session().wait(0ms);  // both on the wire before the next check
}

void train_send(CheckRun& run, const tr::Command& command) {
    Message m;
    m.mti = Mti::kTractionControlCommand;
    m.destination = NodeHandle{run.node().id, run.alias()};
    m.payload = tr::encode(command);
    run.session().send(std::move(m));
}

std::optional<tr::Reply> train_await(CheckRun& run, std::size_t mark,
                                     const std::function<bool(const tr::Reply&)>& wanted,
                                     std::string& why, Duration window) {
    Session& s = run.session();
    std::optional<tr::Reply> got;
    std::size_t scanned = mark;
    std::string bad;
    s.run_until(
        [&] {
            const auto since = s.messages_since(scanned);
            for (const ReceivedMessage& r : since) {
                ++scanned;
                const Message& m = r.message;
                if (m.mti != Mti::kTractionControlReply || m.source.alias != run.alias()) continue;
                auto d = tr::decode_reply(m.payload);
                if (!d.ok()) {
                    bad = d.error + " (" + base::hex_bytes(m.payload) + ")";
                    continue;
                }
                if (!wanted(*d.value)) continue;
                got = d.value;
                return true;
            }
            return false;
        },
        window.count() > 0 ? window : run.options().answer_window);
    if (!got)
        why = bad.empty() ? "no answer within " +
                                ms_text(window.count() > 0 ? window : run.options().answer_window)
                          : "a reply that does not decode: " + bad;
    return got;
}

namespace {

CheckSpec train(CheckSpec s) {
    s.needs = Protocol::kTractionControl;
    return s;
}

// The checks that move the train (only on a node named with --node).
std::vector<CheckSpec> train_moving_checks() {
    return {
        train({"train.speed", 746, Category::kTrain, "TrainControlS §4.3, §4.4, §5",
               Strength::kShall,
               "Query Speeds returns the most recent Set Speed, float16 with its sign as the "
               "direction (zero included)",
               "tr020",
               "(--node) Set Speed 0.75 reverse, 0 reverse, 0.75 forward, 0 forward, each "
               "followed by Query Speeds: the same 16 bits back",
               train_speed}),
        train({"train.function", 747, Category::kTrain, "TrainControlS §4.3, §4.4, §6.3",
               Strength::kShall, "Query Function returns the value Set Function set", "tr030",
               "(--node) Set Function F0 = 1, Query; F0 = 0, Query; F0 restored", train_function}),
        train({"train.function-space", 748, Category::kTrain, "TrainControlS §6.3, §7.1",
               Strength::kShould,
               "function values are the 0xF9 space: a write there is what Query Function reads "
               "(a read need not return the last write, TN §2.7.1)",
               "",
               "(--node, 0xF9 present) Set F0 = 0, write 1 to 0xF9 byte 0, Query Function F0 "
               "reads 1; F0 restored",
               train_function_space}),
        train({"train.estop", 749, Category::kTrain, "TrainControlS §4.4, §5, §6.2",
               Strength::kShall,
               "Emergency Stop sets the Set Speed to zero keeping the direction and sets status "
               "bit 0; a Set Speed leaves the state",
               "tr040",
               "(--node) Set Speed 0.5 reverse, Emergency Stop, Query: 0 reverse and bit 0; Set "
               "Speed 0.5 forward, Query: 0.5 forward and bit 0 clear",
               train_estop}),
        train({"train.global-estop", 751, Category::kTrain, "TrainControlS §5, §6.2",
               Strength::kShall,
               "Emergency Stop All stops the train without changing its Set Speed; a Set Speed "
               "during it is kept",
               "tr050",
               "(--node --thorough) Set Speed 0.5 reverse, PCER Emergency Stop All, Query: "
               "unchanged; Set Speed 0.5 forward, Query; PCER Clear Emergency Stop All",
               train_global_stop, true}),
        train({"train.global-eoff", 752, Category::kTrain, "TrainControlS §5, §6.2",
               Strength::kShall,
               "Emergency Off All stops the train without changing its Set Speed; a Set Speed "
               "during it is kept",
               "tr060",
               "(--node --thorough) as train.global-estop with Emergency Off All and Clear "
               "Emergency Off All",
               train_global_off, true}),
        train({"train.listener", 753, Category::kTrain, "TrainControlS §4.3, §4.4, §5, §6.5",
               Strength::kShall,
               "Attach/Detach Node replies echo the node ID with an error code; Query Nodes "
               "lists the listeners in attach order with their flags; new flags keep the place",
               "tr080",
               "(--node) attach A (Reverse) and B (Link F0), list them, update A's flags, detach "
               "A, list, detach A again (WARN unless an error code), detach B",
               train_listener}),
        train({"train.listener-forward", 754, Category::kTrain, "TrainControlS §6.5",
               Strength::kShall,
               "operations are forwarded to listeners with the P bit: Set Speed always (reversed "
               "with Rev direction), F0 iff Link F0, other functions iff Link Fn, never back to "
               "the source",
               "",
               "(--node) lcc-conform attached (Reverse, Link F0); a second node lcc-conform "
               "speaks for sends Set Speed, F0, F3: forwarded as the flags say",
               train_listener_forward}),
        train({"train.heartbeat", 755, Category::kTrain, "TrainControlS §6.6", Strength::kShall,
               "no Heartbeat Request while the Set Speed is zero; any command clears a request; "
               "an unanswered one stops the train at its deadline",
               "tr110",
               "(--node) Set Speed 0.5, wait up to 3 s (--thorough: 12 s) for a request (none: "
               "PASS, optional), "
               "No-op, wait for the next, leave it unanswered: Set Speed 0 after the deadline",
               train_heartbeat}),
    };
}

}  // namespace

std::vector<CheckSpec> train_control_checks() {
    std::vector<CheckSpec> all = {
        train({"train.is-train-event", 741, Category::kTrain, "TrainControlS §4.1, §6.4",
               Strength::kShall, "a train node produces the Is Train event", "tr010",
               "Identify Producer 01.01.00.00.00.00.03.03: a Producer Identified from the node",
               train_is_train}),
        train({"train.memory-spaces", 742, Category::kTrain, "TrainControlS §3, §7",
               Strength::kShould,
               "a train node is strongly recommended to provide FDI (0xFA); 0xF9 is optional",
               "tr070",
               "Space Info 0xF9 and 0xFA: WARN when the PIP claims no FDI and 0xFA is missing "
               "(with the FDI claim, fdi.space judges 0xFA)",
               train_memory_spaces}),
        train({"train.controller", 744, Category::kTrain, "TrainControlS §4.3, §4.4, §6.1",
               Strength::kShall,
               "Assign Controller answered within 3 s; Query Controller names the active "
               "controller (zero when none); Release by the controller clears it",
               "tr090",
               "Query Controller; on a node named with --node: Assign (lcc-conform), Query, "
               "Release, Query; the flags byte is reserved and only shown",
               train_controller}),
        train({"train.reserve", 745, Category::kTrain, "TrainControlS §4.3, §4.4", Strength::kShall,
               "Reserve is answered with a Reserve Reply; the standard gives no rule on a second "
               "Reserve from the same node",
               "tr100",
               "(--node) Reserve, Reserve again, Release, Reserve, Release: each Reserve gets a "
               "Reply; the results are shown, not judged",
               train_reserve}),
    };
    std::vector<CheckSpec> moving = train_moving_checks();
    all.insert(all.end(), moving.begin(), moving.end());
    return all;
}

}  // namespace olcb::conform::checks
