// Message-level checks of addressing: messages addressed to another node get no answer, the
// Protocol Support Reply's reserved bytes and simple bit, and (last of all, --thorough) the
// duplicate node ID.
#include <algorithm>
#include <array>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "conformance/checks/checks.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform::checks {
namespace {

using C = Category;

// The well-known event a node reports a duplicate node ID with (CanFrameTransferS 6.2.6).
constexpr std::array<std::uint8_t, 8> kDuplicateEvent = {0x01, 0x01, 0, 0, 0, 0, 0x02, 0x01};

// An only-frame addressed message from src to dst (payload at most 6 bytes).
CanFrame addressed(std::uint16_t mti, std::uint16_t src, std::uint16_t dst,
                   std::span<const std::uint8_t> payload = {}) {
    std::array<std::uint8_t, 8> d{};
    d[0] = static_cast<std::uint8_t>((dst >> 8) & 0x0F);
    d[1] = static_cast<std::uint8_t>(dst & 0xFF);
    const std::size_t n = std::min<std::size_t>(payload.size(), 6);
    std::copy_n(payload.begin(), n, d.begin() + 2);
    return can::make_frame(can::message_header(mti & 0x0FFF, src),
                           std::span<const std::uint8_t>(d.data(), n + 2));
}

// A global or addressed (format 1) frame with one of these 16-bit MTIs.
bool is_mti(const CanFrame& f, std::initializer_list<Mti> mtis) {
    if (!f.extended || !can::is_message(f.id) ||
        can::frame_format(f.id) != can::FrameFormat::kGlobalAddressed)
        return false;
    return std::any_of(mtis.begin(), mtis.end(),
                       [&](Mti m) { return can::can_mti(f.id) == (to_u16(m) & 0x0FFF); });
}

// The alias of no node seen: what "addressed to another node" is sent to. The node under test
// may know other aliases; one nobody used cannot be its own.
std::optional<std::uint16_t> other_alias(CheckRun& run) {
    const std::vector<std::uint16_t> a = unused_aliases(run, 1);
    if (a.empty()) return std::nullopt;
    return a.front();
}

std::uint16_t dest_of(const CanFrame& f) {
    return f.len < 2 ? 0 : static_cast<std::uint16_t>((f.data[0] & 0x0F) << 8 | f.data[1]);
}

std::string name_of(const CanFrame& f) {
    // These answers' MTIs fit in 12 bits: the CAN-MTI is the whole MTI.
    const std::string_view name = mti_name(static_cast<std::uint16_t>(can::can_mti(f.id)));
    return name.empty() ? "an answer" : std::string(name);
}

// True for an OIR echoing the unknown addressed MTI (bytes 4-5 of the frame, after the
// destination and the error code).
bool echoes_unknown_addressed(const CanFrame& f) {
    return f.len >= 6 && (f.data[4] << 8 | f.data[5]) == kUnknownAddressedMti;
}

// What the node sent in one window after the four probes. A node answering a request addressed
// elsewhere answers its sender, us: a PSR, or an OIR echoing 0x04F9, addressed to us is such an
// answer; anything else addressed to us answers the unknown global MTI. false when another
// source spoke and a global answer (Verified Node ID) cannot be told from an answer to it.
bool judge_window(CheckRun& run, std::size_t mark, std::uint16_t other, SilenceAnswers& a) {
    Session& s = run.session();
    a = SilenceAnswers{};
    a.other = other;
    for (const CanFrame& f : s.frames_since(mark)) {
        if (!run.from_node(f)) continue;
        if (is_mti(f, {Mti::kVerifiedNodeId, Mti::kVerifiedNodeIdSimple}) && a.verified.empty())
            a.verified = name_of(f);
        const bool addressed = can::is_message(f.id) &&
                               can::frame_format(f.id) == can::FrameFormat::kGlobalAddressed &&
                               (can::can_mti(f.id) & 0x008) != 0;
        if (!addressed || dest_of(f) != s.tool_alias()) continue;
        std::string& slot =
            is_mti(f, {Mti::kProtocolSupportReply}) ? a.psr
            : is_mti(f, {Mti::kOptionalInteractionRejected}) && echoes_unknown_addressed(f)
                ? a.oir
                : a.to_us;
        if (slot.empty()) slot = name_of(f);
    }
    return a.verified.empty() || !run.others_spoke(mark);
}

bool node_spoke(CheckRun& run, std::size_t mark) {
    const std::vector<CanFrame> window = run.session().frames_since(mark);
    return std::any_of(window.begin(), window.end(),
                       [&](const CanFrame& f) { return run.from_node(f); });
}

}  // namespace

SilenceAnswers SilenceAnswers::ask(CheckRun& run) {
    Session& s = run.session();
    SilenceAnswers a;
    const auto other = other_alias(run);
    const std::uint16_t me = s.tool_alias();
    const auto id = run.node().id.to_bytes();
    // The four probes go out together and share one window: each answer says which it was for.
    // Without --thorough, frame.standard-frames-ignored's frames share it too while the node
    // stays wholly silent; once it speaks, the window is had again without them.
    unsigned standard = run.options().selection.thorough ? 0 : kStandardFramesQuick;
    for (int attempt = 0; attempt < kQuietAttempts; ++attempt) {
        const std::size_t mark = s.frame_mark();
        inject_standard_frames(s, standard, false);
        s.inject(can::make_frame(can::message_header(kUnknownGlobalMti, me)));
        if (other) {
            s.inject(addressed(to_u16(Mti::kVerifyNodeIdAddressed), me, *other, id));
            s.inject(addressed(to_u16(Mti::kProtocolSupportInquiry), me, *other));
            s.inject(addressed(kUnknownAddressedMti, me, *other));
        }
        s.wait(run.options().window);
        if (standard != 0 && node_spoke(run, mark)) {
            standard = 0;
            --attempt;  // the shared window is not one of the attempts
            continue;
        }
        if (judge_window(run, mark, other.value_or(0), a)) {
            a.judged = true;
            a.standard_frames = standard;
            break;
        }
    }
    a.has_other = other.has_value();
    return a;
}

namespace {

// One "addressed to another node: silence" check, from the shared probe.
void silent_to_other(CheckRun& run, const CheckSpec& spec, std::string SilenceAnswers::*seen_of,
                     const std::string& what) {
    const SilenceAnswers& a = run.probe<SilenceAnswers>();
    if (!a.has_other) return run.out(spec).skip("no unused alias to address");
    if (!a.judged)
        return run.out(spec).skip("other sources spoke in every silence window: not judged");
    const std::string& seen = a.*seen_of;
    const std::string sent = what + " addressed to alias " + hex(a.other, 3) + " (no node's)";
    run.out(spec).judge(seen.empty(),
                        seen.empty() ? sent + " ignored" : sent + " answered with " + seen,
                        "silence", seen.empty() ? "" : seen + " from the node");
}

}  // namespace

// me20: a Verify addressed elsewhere is not the node's to answer, even carrying its node ID.
void verify_other_silent(CheckRun& run, const CheckSpec& spec) {
    silent_to_other(run, spec, &SilenceAnswers::verified, "Verify Node ID with the node's ID");
}

// me30: a Protocol Support Inquiry addressed elsewhere gets no reply from this node.
void pip_other_silent(CheckRun& run, const CheckSpec& spec) {
    silent_to_other(run, spec, &SilenceAnswers::psr, "Protocol Support Inquiry");
}

// me40: only the addressee rejects an MTI it does not know.
void oir_other_silent(CheckRun& run, const CheckSpec& spec) {
    silent_to_other(run, spec, &SilenceAnswers::oir, "unknown MTI 0x04F9");
}

// me30: bytes 3-5 of the reply carry no protocol yet ("send as 0").
void pip_fourth_byte(CheckRun& run, const CheckSpec& spec) {
    Session& s = run.session();
    const std::uint16_t alias = run.alias();
    Message psi;
    psi.mti = Mti::kProtocolSupportInquiry;
    psi.destination = NodeHandle{run.node().id, alias};
    // Asked again, not taken from the PIP probe: the decoded set drops the raw bytes.
    s.send(psi);
    const auto reply = s.wait_for(
        [&](const Message& m) {
            return m.mti == Mti::kProtocolSupportReply && m.source.alias == alias;
        },
        run.options().answer_window);
    if (!reply) return run.out(spec).skip("no Protocol Support Reply (see message.pip-answered)");
    const std::vector<std::uint8_t>& p = reply->payload;
    std::string bad;
    for (std::size_t i = 3; i < p.size(); ++i)
        if (p[i] != 0 && bad.empty()) bad = "byte " + std::to_string(i + 1) + " is " + hex(p[i], 2);
    if (bad.empty())
        return run.out(spec).pass("Protocol Support Reply of " + std::to_string(p.size()) +
                                  " bytes: the reserved bytes from the 4th on are 0");
    run.out(spec).fail("Protocol Support Reply: " + bad + "; bytes 4-6 are reserved (send as 0)",
                       "0", bad);
}

// me60: the simple bit and the Verified Node ID MTI both say whether the node is simple.
void pip_simple_bit(CheckRun& run, const CheckSpec& spec) {
    const auto& pip = run.probe<PipProbe>().reply;
    if (!pip) return run.out(spec).skip("no Protocol Support Reply (see message.pip-answered)");
    const auto& mti = run.probe<FrameProbe>().verified_mti;
    if (!mti) return run.out(spec).skip("no Verified Node ID (see message.verify-addressed)");
    const bool bit = pip->has(Protocol::kSimpleProtocol);
    const bool simple_mti = *mti == Mti::kVerifiedNodeIdSimple;
    const std::string used = std::string(mti_name(*mti)) + " (" + hex(to_u16(*mti)) + ")";
    const std::string state = bit ? "set" : "clear";
    run.out(spec).judge(
        bit == simple_mti,
        "PIP Simple Protocol bit " + state + ", and the node answers Verify with " + used,
        bit ? "Verified Node ID Simple (0x0171)" : "Verified Node ID (0x0170)", used);
}

// me50: a Verified Node ID carrying the node's own ID says another node claims it.
void duplicate_node_id(CheckRun& run, const CheckSpec& spec) {
    Session& s = run.session();
    const std::size_t mark = s.frame_mark();
    // From our alias, injected: our own stack and the session's tracking never see it, so the
    // node stays mapped to its own alias.
    s.inject(can::make_node_id_frame(
        can::message_header(to_u16(Mti::kVerifiedNodeId) & 0x0FFF, s.tool_alias()), run.node().id));
    bool pcer = false;
    std::size_t seen = mark;
    auto reported = [&] {
        for (const CanFrame& f : s.frames_since(seen)) {
            ++seen;
            pcer = pcer ||
                   (run.from_node(f) && is_mti(f, {Mti::kEventReport}) && f.len == 8 &&
                    std::equal(kDuplicateEvent.begin(), kDuplicateEvent.end(), f.data.begin()));
        }
        return pcer;
    };
    s.run_until(reported, run.options().answer_window);
    const bool answers = s.ping(run.node(), run.options().answer_window);
    const std::string event = "duplicate-node-ID PCER 01.01.00.00.00.00.02.01";
    if (pcer && answers) return run.out(spec).pass(event + " sent; the node still answers Verify");
    if (pcer)
        return run.out(spec).warn(
            event +
            " sent, then no answer to Verify Node ID: "
            "CanFrameTransferS 6.2.6 has a node stay silent after that report "
            "until reset; the rest of the run cannot reach it");
    if (answers)
        return run.out(spec).warn("no " + event +
                                  " (optional indication; OlcbChecker treats it as "
                                  "a partial pass); the node still answers Verify");
    run.out(spec).fail(
        "after a Verified Node ID carrying its node ID the node no longer answers "
        "Verify Node ID, and sent no duplicate-node-ID report",
        "an answer to Verify Node ID (and optionally the PCER)", "no answer");
}

std::vector<CheckSpec> message_addressing_checks() {
    return {
        {"message.verify-other-silent", 480, C::kMessage, "MessageNetworkS §3.4.2", Strength::kNone,
         "replies are defined for Verify messages addressed to the node; none forbids answering "
         "others (WARN)",
         "me20",
         "Verify Node ID with the node's ID addressed to an alias no node uses: no Verified Node "
         "ID from the node within the silence window",
         verify_other_silent},
        {"message.pip-other-silent", 490, C::kMessage, "MessageNetworkS §3.4.3", Strength::kNone,
         "the reply is defined for an inquiry addressed to the node (WARN)", "me30",
         "Protocol Support Inquiry addressed to an alias no node uses: no Protocol Support Reply "
         "from the node within the silence window",
         pip_other_silent},
        {"message.oir-other-silent", 500, C::kMessage, "MessageNetworkS §3.5.1", Strength::kNone,
         "OIR answers messages addressed to the node itself (WARN)", "me40",
         "unassigned MTI 0x04F9 addressed to an alias no node uses: no OIR from the node within "
         "the silence window",
         oir_other_silent},
        {"message.pip-fourth-byte", 510, C::kMessage, "MessageNetworkS §3.3.7", Strength::kShall,
         "unallocated PIP bits are sent as 0", "me30",
         "Protocol Support Inquiry: the reply's 4th and later (reserved) bytes are 0",
         pip_fourth_byte},
        {"message.pip-simple-bit", 520, C::kMessage, "MessageNetworkS §4.1.4", Strength::kNone,
         "simple nodes use the simple Verified MTI; §4 is not normative (WARN)", "me60",
         "PIP Simple Protocol bit (0x80 of the first byte) set iff the node answers Verify with "
         "Verified "
         "Node ID Simple (0x0171), clear iff with 0x0170",
         pip_simple_bit},
    };
}

std::vector<CheckSpec> final_checks() {
    return {
        {"message.duplicate-node-id", 770, C::kMessage, "MessageNetworkS §3.5.4", Strength::kNone,
         "a node seeing its node ID elsewhere indicates it by whatever means it has, so the PCER "
         "and going silent are both allowed (WARN)",
         "me50",
         "Verified Node ID carrying the node's ID from our alias: PCER "
         "01.01.00.00.00.00.02.01 within the answer window (none: WARN, an optional indication), "
         "and the node still answers Verify (PCER then silence: WARN; silence alone: FAIL)",
         duplicate_node_id, true, true},
    };
}

}  // namespace olcb::conform::checks
