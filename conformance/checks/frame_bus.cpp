// CAN-level checks of how the node shares the bus: alias collisions, the reserved header bit,
// bursts of traffic, standard frames and the start-up sequence after Reset/Reboot.
#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "conformance/checks/checks.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform::checks {
namespace {

using namespace std::chrono_literals;
using C = Category;

// A node ID no real node has, for the foreign AMD (the CID probe of the frame checks uses ...01).
constexpr std::uint64_t kForeignNodeId = 0x0201'12FE'0002ull;
// Frames of one capacity burst (OlcbChecker fr50 floods with 300), and the Verify in its middle.
constexpr std::size_t kBurstFrames = 300;
// How soon after a burst the node must have answered the Verify inside it (OlcbChecker fr50).
constexpr Duration kBurstAnswer = 800ms;
// With --thorough every ID OlcbChecker fr60 sends: 0x000..0x7FE.
constexpr unsigned kStandardIdsAll = 2047;
// How long a node has from Reset/Reboot to its Initialization Complete.
constexpr Duration kStartupWindow = 10s;
// The alias a collision takes away is reserved again (>= 200 ms) before the node answers.
constexpr Duration kNewAliasWait = 1s;

bool carries(const CanFrame& f, NodeId id) {
    return f.len == 6 && NodeId::from_bytes({f.data.data(), 6}) == id;
}

bool is_control(const CanFrame& f, can::ControlFrame kind) {
    return f.extended && can::is_control(f.id) && can::classify_control(f.id) == kind;
}

// A global (format 1) message frame with this 16-bit MTI.
bool is_global_mti(const CanFrame& f, std::uint16_t mti) {
    return f.extended && can::is_message(f.id) &&
           can::frame_format(f.id) == can::FrameFormat::kGlobalAddressed &&
           can::can_mti(f.id) == (mti & 0x0FFF);
}

bool is_verified(const CanFrame& f) {
    return is_global_mti(f, to_u16(Mti::kVerifiedNodeId)) ||
           is_global_mti(f, to_u16(Mti::kVerifiedNodeIdSimple));
}

// An addressed message frame (framing nibble + destination in the first two bytes).
CanFrame addressed(Mti mti, std::uint16_t src, std::uint16_t dst,
                   std::span<const std::uint8_t> payload,
                   can::AddressedFraming framing = can::AddressedFraming::kOnly) {
    std::array<std::uint8_t, 8> d{};
    d[0] = static_cast<std::uint8_t>(static_cast<std::uint8_t>(framing) | ((dst >> 8) & 0x0F));
    d[1] = static_cast<std::uint8_t>(dst & 0xFF);
    const std::size_t n = std::min<std::size_t>(payload.size(), 6);
    std::copy_n(payload.begin(), n, d.begin() + 2);
    return can::make_frame(can::message_header(to_u16(mti) & 0x0FFF, src),
                           std::span<const std::uint8_t>(d.data(), n + 2));
}

// Watches the frames arriving after a mark: each call sees only the ones not seen before.
class FrameScan {
public:
    explicit FrameScan(Session& s) : s_(s), next_(s.frame_mark()) {}
    /// True once pred held for a frame (the first such is kept in found()). Stays true: the
    /// link may ask a run_until predicate again after it held.
    template <typename Pred>
    bool any(Pred pred) {
        if (found_) return true;
        for (const CanFrame& f : s_.frames_since(next_)) {
            ++next_;
            if (pred(f)) {
                found_ = f;
                return true;
            }
        }
        return false;
    }
    const std::optional<CanFrame>& found() const { return found_; }

private:
    Session& s_;
    std::size_t next_;
    std::optional<CanFrame> found_;
};

// "CID7", "AMD", "Initialization Complete", or the header for anything else.
std::string frame_name(const CanFrame& f) {
    if (!f.extended) return "standard frame " + hex(f.id, 3);
    if (can::is_control(f.id)) return can::control_name(can::classify_control(f.id));
    const std::string_view name = mti_name(static_cast<std::uint16_t>(can::can_mti(f.id)));
    if (can::frame_format(f.id) == can::FrameFormat::kGlobalAddressed && !name.empty())
        return std::string(name);
    return "frame " + hex(f.id, 8);
}

}  // namespace

std::vector<std::uint16_t> unused_aliases(CheckRun& run, std::size_t count) {
    Session& s = run.session();
    std::set<std::uint16_t> used = {0, s.tool_alias(), run.alias()};
    for (const NodeInfo& n : s.nodes_seen()) used.insert(n.alias);
    for (const CanFrame& f : s.frames_since(0))
        if (f.extended) used.insert(can::source_alias(f.id));
    // An odd stride visits all 4096 values; the start is arbitrary, away from the low aliases
    // some generators favour.
    std::vector<std::uint16_t> out;
    for (unsigned k = 0; k < 0x1000 && out.size() < count; ++k) {
        const auto a = static_cast<std::uint16_t>((0xA5A + k * 0x123) & can::kAliasMask);
        if (!used.count(a)) out.push_back(a);
    }
    return out;
}

// Runs a check that makes the node reserve an alias again (a staged collision, a Reset): those
// reservations are the check's doing, so the node watch must not report a restart for them.
template <typename F>
void provoking_reservations(CheckRun& run, const CheckSpec& spec, F&& check) {
    Session& s = run.session();
    const NodeId id = run.node().id;
    const std::uint32_t before = s.track(id).reservations;
    check(run, spec);
    const std::uint32_t after = s.track(id).reservations;
    if (after > before) s.excuse_reservations(id, after - before);
}

// fr30: an AMD from the node's alias with another node ID means another node took the alias;
// the node must give it up (AMR with its node ID) and come back on a new one.
void stage_collision(CheckRun& run, const CheckSpec& spec) {
    Session& s = run.session();
    const NodeId id = run.node().id;
    const std::uint16_t old_alias = run.alias();
    FrameScan scan(s);
    s.inject(can::make_amd(old_alias, NodeId{kForeignNodeId}));
    auto amr = [&](const CanFrame& f) {
        return is_control(f, can::ControlFrame::kAmr) && can::source_alias(f.id) == old_alias;
    };
    s.run_until([&] { return scan.any(amr); }, run.options().answer_window);
    const std::string alias_text = "alias " + hex(old_alias, 3);
    if (!scan.found())
        return run.out(spec).fail(
            "no AMR after an AMD from the node's " + alias_text + " carrying another node ID",
            "AMR from " + alias_text + ", then a new alias", "no AMR within the answer window");
    if (!carries(*scan.found(), id))
        return run.out(spec).fail("the AMR giving up " + alias_text + " does not carry the node ID",
                                  "AMR with " + id.to_string(), "AMR without it");
    // A node may reserve its new alias at once (and miss a Verify meanwhile) or only when it
    // next has to send (OpenMRN): one Verify global makes the lazy one reserve, the eager one's
    // AMD is awaited, then the node is asked again.
    Message verify;
    verify.mti = Mti::kVerifyNodeIdGlobal;
    const auto bytes = id.to_bytes();
    verify.payload.assign(bytes.begin(), bytes.end());
    s.send(verify);
    s.run_until(
        [&] {
            const std::uint16_t now = s.track(id).alias;
            return now != 0 && now != old_alias;
        },
        run.options().answer_window + kNewAliasWait);
    auto found = s.find_node(id, run.options().answer_window);
    // §6.2.5 asks for the AMR and giving the alias up; taking a new one is not required.
    if (!found)
        return run.out(spec).warn(
            "AMR sent, but no Verified Node ID to a Verify global afterwards: "
            "the node did not come back on a new alias");
    if (found->alias == old_alias)
        return run.out(spec).fail(
            "AMR sent, but the node still answers from the " + alias_text + " it gave up",
            "a new alias", alias_text);
    run.out(spec).pass("AMR with the node ID from " + alias_text +
                       ", then Verified Node ID from the new alias " + hex(found->alias, 3));
}

// fr40: bit 28 is sent as 1 but must be ignored on receipt.
void ame_bit28(CheckRun& run, const CheckSpec& spec) {
    Session& s = run.session();
    const NodeId id = run.node().id;
    // The AME carries the node ID so only the node answers, not every node of a big segment.
    CanFrame ame = can::make_ame(s.tool_alias(), id);
    ame.id &= ~can::kReservedBit;
    FrameScan scan(s);
    s.inject(ame);
    auto amd = [&](const CanFrame& f) {
        return run.from_node(f) && is_control(f, can::ControlFrame::kAmd) && carries(f, id);
    };
    s.run_until([&] { return scan.any(amd); }, run.options().answer_window);
    const std::string what =
        "AME with the node ID and header bit 28 clear (" + hex(ame.id, 8) + ")";
    run.out(spec).judge(
        scan.found().has_value(),
        what + (scan.found() ? " answered with AMD" : ": no AMD within the answer window"),
        "AMD with the node ID", "no AMD within the answer window");
}

// One capacity burst: kBurstFrames frames from made-up aliases with an addressed Verify from us
// after the first half.
struct Burst {
    const char* name;
    std::vector<CanFrame> frames;
};

// aliases: 3 made-up senders, then the made-up destination of the addressed messages.
std::vector<Burst> capacity_bursts(const std::vector<std::uint16_t>& aliases) {
    const std::array<std::uint8_t, 8> event = {0x02, 0x01, 0x12, 0xFE, 0x00, 0x02, 0x00, 0x01};
    const std::array<std::uint8_t, 12> snip_part = {4, 'A', 0, 'B', 0, '1', 0, '2', 0, 2, 0, 0};
    std::vector<Burst> out = {{"global Verify Node ID", {}},
                              {"2-frame messages to another node", {}},
                              {"Identify Consumer", {}}};
    for (std::size_t i = 0; i < kBurstFrames; ++i) {
        const std::uint16_t src = aliases[i % 3];
        // Carrying another node ID, so the node owes no answer to them, only to our Verify.
        out[0].frames.push_back(can::make_node_id_frame(
            can::message_header(to_u16(Mti::kVerifyNodeIdGlobal) & 0x0FFF, src),
            NodeId{kForeignNodeId}));
        out[2].frames.push_back(can::make_frame(
            can::message_header(to_u16(Mti::kIdentifyConsumer) & 0x0FFF, src), event));
        if (i % 2) continue;
        // A SNIP reply to another node: multi-frame traffic the node only has to pass over.
        const std::span<const std::uint8_t> part(snip_part);
        out[1].frames.push_back(addressed(Mti::kSnipReply, src, aliases[3], part.first(6),
                                          can::AddressedFraming::kFirst));
        out[1].frames.push_back(addressed(Mti::kSnipReply, src, aliases[3], part.last(6),
                                          can::AddressedFraming::kLast));
    }
    return out;
}

// True when the node answered the Verify in the middle of the burst within kBurstAnswer.
bool burst_answered(CheckRun& run, const Burst& burst) {
    Session& s = run.session();
    const CanFrame verify = addressed(Mti::kVerifyNodeIdAddressed, s.tool_alias(), run.alias(), {});
    FrameScan scan(s);
    const std::size_t half = burst.frames.size() / 2;
    for (std::size_t i = 0; i < burst.frames.size(); ++i) {
        // Injected rather than sent by our stack, so it goes out between the burst's frames.
        if (i == half) s.inject(verify);
        s.inject(burst.frames[i]);
    }
    auto verified = [&](const CanFrame& f) {
        return run.from_node(f) && is_verified(f) && carries(f, run.node().id);
    };
    return s.run_until([&] { return scan.any(verified); }, kBurstAnswer);
}

// fr50: a node must keep up with a fully loaded bus.
void capacity(CheckRun& run, const CheckSpec& spec) {
    const std::vector<std::uint16_t> aliases = unused_aliases(run, 4);
    if (aliases.size() < 4)
        return run.out(spec).skip("no 4 unused aliases for the made-up senders");
    std::vector<std::string> failed;
    for (const Burst& b : capacity_bursts(aliases))
        if (!burst_answered(run, b)) failed.push_back(b.name);
    // Half of the last burst follows the Verify it answered: once the node answers a ping sent
    // after it, the next check's silence window starts at once, not after the burst's modelled
    // bus time (which a TCP link only assumes).
    if (failed.empty()) run.session().ping(run.node(), run.options().answer_window);
    if (failed.empty())
        return run.out(spec).pass(
            "Verify Node ID addressed answered within 0.8 s inside bursts of " +
            std::to_string(kBurstFrames) +
            " frames (global Verify, 2-frame messages to another node, "
            "Identify Consumer)");
    std::string names;
    for (const std::string& n : failed) names += (names.empty() ? "" : ", ") + n;
    run.out(spec).fail("no Verified Node ID within 0.8 s after a burst of " +
                           std::to_string(kBurstFrames) + " frames of: " + names,
                       "Verified Node ID after every burst",
                       std::to_string(failed.size()) + " of 3 bursts unanswered");
}

// A frame's kind: its header without the source alias.
std::uint32_t frame_kind(const CanFrame& f) {
    return f.id & ~std::uint32_t{0xFFF};
}

// The kinds of frame the node sends with nothing asked for a quiet window (its own chatter, e.g.
// a periodic Verify Node ID Global): those prove nothing about standard frames.
std::set<std::uint32_t> unprompted_kinds(CheckRun& run) {
    Session& s = run.session();
    const std::size_t mark = s.frame_mark();
    s.wait(run.options().quiet_window);
    std::set<std::uint32_t> kinds;
    for (const CanFrame& f : s.frames_since(mark))
        if (run.from_node(f)) kinds.insert(frame_kind(f));
    return kinds;
}

// fr60: OpenLCB uses extended frames only; standard frames on the bus are someone else's.
// What the node sent after the standard frames, but for what it also sends unprompted: nothing
// passes.
void judge_standard_frames(CheckRun& run, const CheckSpec& spec, std::size_t mark, unsigned count) {
    const std::string what = std::to_string(count) + " standard (11-bit) frames";
    const std::vector<CanFrame> window = run.session().frames_since(mark);
    if (std::none_of(window.begin(), window.end(),
                     [&](const CanFrame& f) { return run.from_node(f); }))
        return run.out(spec).pass(what + " ignored: nothing sent in the silence window");
    const std::set<std::uint32_t> chatter = unprompted_kinds(run);
    std::optional<CanFrame> answer;
    for (const CanFrame& f : window) {
        if (run.from_node(f) && !chatter.count(frame_kind(f))) {
            answer = f;
            break;
        }
    }
    if (!answer)
        return run.out(spec).pass(what +
                                  " ignored: the node sent only what it sends unprompted too");
    const std::string name = frame_name(*answer) + " (" + hex(answer->id, 8) + ")";
    run.out(spec).fail(what + " answered: the node sent " + name, "silence", name);
}

void inject_standard_frames(Session& s, unsigned count, bool every_id) {
    for (unsigned i = 0; i < count; ++i) {
        CanFrame f;
        f.extended = false;
        // Without --thorough: one ID in every 32, its low bits varied too (0x000 .. 0x7FF).
        f.id = every_id ? i : i * 0x20 + (i & 0x1F);
        f.len = static_cast<std::uint8_t>(i % 9);
        for (std::uint8_t k = 0; k < f.len; ++k) f.data[k] = static_cast<std::uint8_t>(i + k);
        s.inject(f);
    }
}

void standard_frames_ignored(CheckRun& run, const CheckSpec& spec) {
    Session& s = run.session();
    const bool all = run.options().selection.thorough;
    const unsigned count = all ? kStandardIdsAll : kStandardFramesQuick;
    // The quick set went out with the message probes' silence window: nothing at all from the
    // node in it settles this check without a window of its own.
    if (!all) {
        const SilenceAnswers& shared = run.probe<SilenceAnswers>();
        if (shared.standard_frames == count)
            return run.out(spec).pass(std::to_string(count) +
                                      " standard (11-bit) frames ignored: nothing sent in the "
                                      "silence window (shared with the addressing probes)");
    }
    // Another tool or node speaking in the window may make the node answer it: try again then.
    for (int attempt = 0; attempt < kQuietAttempts; ++attempt) {
        const std::size_t mark = s.frame_mark();
        inject_standard_frames(s, count, all);
        s.wait(run.options().window);
        if (run.others_spoke(mark)) continue;
        return judge_standard_frames(run, spec, mark, count);
    }
    run.out(spec).skip("other sources spoke in every silence window: fr60 not judged");
}

// The start-up sequence (CanFrameTransferS 6.2.1, 6.2.2, MessageNetworkS 3.4.1): steps 0..6.
constexpr std::array<const char*, 7> kStartupSteps = {"CID7",
                                                      "CID6",
                                                      "CID5",
                                                      "CID4",
                                                      "RID",
                                                      "AMD with its node ID",
                                                      "Initialization Complete with its node ID"};

// Which step of the node's start-up f is (nullopt: none).
std::optional<std::size_t> startup_step(const CanFrame& f, NodeId id) {
    if (!f.extended) return std::nullopt;
    if (can::is_cid(f.id)) {
        const int n = static_cast<int>(can::content(f.id) >> 12);
        const auto slice = static_cast<std::uint16_t>((id.value() >> (12 * (n - 4))) & 0xFFF);
        if (can::cid_node_id_bits(f.id) != slice) return std::nullopt;
        return static_cast<std::size_t>(7 - n);
    }
    if (is_control(f, can::ControlFrame::kRid)) return 4;
    if (is_control(f, can::ControlFrame::kAmd))
        return carries(f, id) ? 5 : std::optional<std::size_t>{};
    const bool init = is_global_mti(f, to_u16(Mti::kInitializationComplete)) ||
                      is_global_mti(f, to_u16(Mti::kInitializationCompleteSimple));
    if (init && carries(f, id)) return 6;
    return std::nullopt;
}

// How far each alias got through the start-up sequence, and what broke it.
struct StartupTrace {
    std::map<std::uint16_t, std::size_t> done;  // alias -> steps completed in order
    std::optional<std::uint16_t> complete;      // the alias that went through all of them
    std::size_t best = 0;                       // most steps any alias completed
    std::string broken;                         // the last deviation, in words

    void see(const CanFrame& f, NodeId id) {
        const std::uint16_t a = can::source_alias(f.id);
        const auto step = startup_step(f, id);
        // A CID7 with the node's bits starts a sequence (again, after a collision, on any alias).
        if (step == 0) {
            done[a] = 1;
        } else if (auto it = done.find(a); it != done.end() && it->second > 0) {
            if (step == it->second) {
                ++it->second;
            } else {
                broken = "after " + std::string(kStartupSteps[it->second - 1]) + " from alias " +
                         hex(a, 3) + " came " + frame_name(f);
                it->second = 0;
            }
        } else {
            return;
        }
        best = std::max(best, done[a]);
        if (done[a] == kStartupSteps.size()) complete = a;
    }
};

// fr10, me10: after Reset/Reboot the node goes through alias reservation and announces itself.
void watch_startup(CheckRun& run, const CheckSpec& spec) {
    if (!run.options().reboot) return run.out(spec).skip("needs --reboot (sends Reset/Reboot)");
    Session& s = run.session();
    const NodeId id = run.node().id;
    const std::uint32_t inits = s.track(id).initializations;
    const TimePoint sent = s.link().now();
    FrameScan scan(s);
    StartupTrace trace;
    auto complete = [&] {
        scan.any([&](const CanFrame& f) {
            trace.see(f, id);
            return trace.complete.has_value();
        });
        return trace.complete.has_value();
    };
    static constexpr std::uint8_t kReset[] = {0x20, 0xA9};
    // The node may restart before its Datagram Received OK: the frames are judged either way.
    const MemResult r = s.command(run.node(), kReset);
    if (r.rejected && !r.timed_out && r.error != 0 && !complete() &&
        s.track(id).initializations == inits)
        return run.out(spec).skip("Reset/Reboot rejected with " + hex(r.error) +
                                  ": the start-up sequence was not observed");
    const Duration left = kStartupWindow - (s.link().now() - sent);
    s.run_until(complete, std::max(left, Duration::zero()));
    if (trace.complete)
        return run.out(spec).pass(
            "after Reset/Reboot: CID7, CID6, CID5, CID4, RID, AMD, "
            "Initialization Complete from alias " +
            hex(*trace.complete, 3) + ", in order");
    std::string seen = trace.best == 0
                           ? "no CID7 with the node's ID bits"
                           : "nothing after " + std::string(kStartupSteps[trace.best - 1]);
    if (!trace.broken.empty()) seen += "; " + trace.broken;
    run.out(spec).fail("start-up sequence after Reset/Reboot incomplete within 10 s: " + seen,
                       "CID7, CID6, CID5, CID4, RID, AMD, Initialization Complete", seen);
}

void collision(CheckRun& run, const CheckSpec& spec) {
    provoking_reservations(run, spec, stage_collision);
}

void startup_sequence(CheckRun& run, const CheckSpec& spec) {
    provoking_reservations(run, spec, watch_startup);
}

std::vector<CheckSpec> frame_bus_checks() {
    return {
        {"frame.collision", 430, C::kFrame, "CanFrameTransferS §6.2.4, §6.2.5", Strength::kShall,
         "a frame from the node's alias makes it send AMR and stop using the alias; taking a new "
         "alias is not required (WARN)",
         "fr30",
         "AMD from the node's alias carrying another node ID: AMR with the node ID from that "
         "alias, then Verified Node ID to a Verify global from a new alias",
         collision, false, true},
        {"frame.ame-bit28", 440, C::kFrame, "CanFrameTransferS §4, §6.2.3", Strength::kShall,
         "bit 28 is ignored on receipt, so an AME with it clear is answered", "fr40",
         "AME with the node ID and header bit 28 clear: AMD from the node", ame_bit28},
        {"frame.capacity", 450, C::kFrame, "MessageNetworkS §3.4.2, §3.7", Strength::kNone,
         "no clause on frame throughput; an unanswered Verify after a burst WARNs", "fr50",
         "3 bursts of 300 frames from made-up aliases (global Verify for another node ID, 2-frame "
         "SNIP replies to another alias, Identify Consumer), an addressed Verify in the middle: "
         "Verified Node ID within 0.8 s after each",
         capacity, false, true},
        {"frame.standard-frames-ignored", 460, C::kFrame, "CanFrameTransferS §4", Strength::kShall,
         "nodes operate properly while error-free 11-bit frames are on the bus", "fr60",
         "64 standard (11-bit) frames over 0x000-0x7FF (--thorough: all 2,047 of OlcbChecker): "
         "nothing from the node within the silence window (retried while other sources speak); "
         "the 64 share the message addressing probes' window, and get one of their own once the "
         "node sends anything in it",
         standard_frames_ignored, false, true},
        {"frame.startup-sequence", 470, C::kFrame,
         "CanFrameTransferS §6.2.1, §6.2.2; MessageNetworkS §3.4.1", Strength::kShall,
         "after a reset: CID7-CID4, a wait, RID, AMD, then Initialization Complete before any "
         "other message",
         "fr10, me10",
         "(--reboot) `20 A9`: CID7-CID4, RID, AMD with the node ID, Initialization Complete, in "
         "order within 10 s (rejected Reset: SKIP quoting the code); writes nothing",
         startup_sequence, false, true},
    };
}

}  // namespace olcb::conform::checks
