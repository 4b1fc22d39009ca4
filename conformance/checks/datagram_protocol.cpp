// Datagram transport checks on raw frames: datagrams of no known protocol, and frame sequences
// that are not a datagram (a middle or last frame alone, a first frame overlapping another).
// Sent as injected frames from our alias so that our own stack's datagram transport (retries,
// timeouts) plays no part; the node's answers are read from the frames.
#include <algorithm>
#include <array>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "base/error_codes.hpp"
#include "conformance/checks/checks.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/datagram_defs.hpp"

namespace olcb::conform::checks {
namespace {

using namespace std::chrono_literals;
using C = Category;
using can::FrameFormat;

// A content type no protocol has (allocated: 0x01, 0x02, 0x20, 0x21, 0x28, 0x30, 0xE0-0xFF).
constexpr std::uint8_t kUnknownType = 0x5A;
// The sizes OlcbChecker da30 sends: one frame, two frames, the largest datagram.
constexpr std::array<std::size_t, 3> kSizes = {1, 10, datagram::kMaxSize};
// Attempts at a datagram the node rejects temporarily (busy) before giving up on it, and the
// pause before each resend (our own stack's resend delay).
constexpr int kAttempts = 5;
constexpr Duration kResendDelay = 20ms;
// After the first answer, how long a second one (a duplicate) is waited for.
constexpr Duration kSettle = 50ms;

// One Datagram Received OK or Datagram Rejected from the node to us.
struct Answer {
    bool ok = false;
    std::uint16_t code = 0;  // Rejected: the error code (missing bits read as 0)
};

using base::is_permanent;
using base::is_temporary;

bool is_out_of_order(std::uint16_t code) {
    return (code & 0xFFF0) == base::to_u16(base::ErrorCode::kOutOfOrder);
}

// What came, in words; a reject without a code says so instead of "0x0000".
std::string describe(const Answer& a) {
    if (a.ok) return "Datagram Received OK";
    return a.code ? "Datagram Rejected " + hex(a.code) : "Datagram Rejected without an error code";
}

// The node's Datagram Received OK / Rejected frames addressed to our alias, from `from` on.
std::vector<Answer> answers_since(CheckRun& run, std::size_t from) {
    Session& s = run.session();
    const auto ok_mti = static_cast<std::uint16_t>(to_u16(Mti::kDatagramReceivedOk) & 0x0FFF);
    const auto rej_mti = static_cast<std::uint16_t>(to_u16(Mti::kDatagramRejected) & 0x0FFF);
    std::vector<Answer> out;
    for (const CanFrame& f : s.frames_since(from)) {
        if (!run.from_node(f) || !can::is_message(f.id) || f.len < 2 ||
            can::frame_format(f.id) != FrameFormat::kGlobalAddressed ||
            can::addressed_dest(f.data[0], f.data[1]) != s.tool_alias())
            continue;
        const std::uint16_t mti = can::can_mti(f.id);
        if (mti == ok_mti) out.push_back({true, 0});
        if (mti == rej_mti) {
            const auto hi = static_cast<std::uint16_t>(f.len > 2 ? f.data[2] << 8 : 0);
            out.push_back({false, static_cast<std::uint16_t>(hi | (f.len > 3 ? f.data[3] : 0))});
        }
    }
    return out;
}

// The frames of one datagram from us to the node (only frame, or first, middles, last).
std::vector<CanFrame> datagram_frames(CheckRun& run, std::span<const std::uint8_t> data) {
    const std::uint16_t me = run.session().tool_alias();
    const std::uint16_t node = run.alias();
    if (data.size() <= 8)
        return {can::make_frame(can::addressed_header(FrameFormat::kDatagramOnly, node, me), data)};
    std::vector<CanFrame> out;
    for (std::size_t at = 0; at < data.size(); at += 8) {
        const FrameFormat f = at == 0                 ? FrameFormat::kDatagramFirst
                              : at + 8 >= data.size() ? FrameFormat::kDatagramLast
                                                      : FrameFormat::kDatagramMiddle;
        const std::size_t n = std::min<std::size_t>(8, data.size() - at);
        out.push_back(can::make_frame(can::addressed_header(f, node, me), data.subspan(at, n)));
    }
    return out;
}

// Injects frames and collects the node's answers: done at the first, then kSettle more for a
// duplicate (settle = false: at the first).
std::vector<Answer> send_raw(CheckRun& run, const std::vector<CanFrame>& frames, bool settle) {
    Session& s = run.session();
    const std::size_t mark = s.frame_mark();
    for (const CanFrame& f : frames) s.inject(f);
    s.run_until([&] { return !answers_since(run, mark).empty(); }, run.options().answer_window);
    if (settle && !answers_since(run, mark).empty()) s.wait(kSettle);
    return answers_since(run, mark);
}

// A node that does not claim datagrams (PIP) owes these checks nothing (OlcbChecker passes it).
bool claims_datagrams(CheckRun& run) {
    const auto& pip = run.probe<PipProbe>().reply;
    return !pip || pip->has(Protocol::kDatagram);
}

// The verdict on one unknown-protocol datagram: "" when rejected 0x1042, else what came.
struct SizeVerdict {
    Status status = Status::kPass;
    std::string note;     // "" for the standard's answer
    bool silent = false;  // no answer at all
};

SizeVerdict unknown_type_answer(CheckRun& run, std::size_t size) {
    std::vector<std::uint8_t> data(size);
    for (std::size_t i = 0; i < size; ++i) data[i] = static_cast<std::uint8_t>(i);
    data[0] = kUnknownType;
    const std::string what = std::to_string(size) + (size == 1 ? " byte: " : " bytes: ");
    for (int attempt = 0; attempt < kAttempts; ++attempt) {
        if (attempt > 0) run.session().wait(kResendDelay);
        const std::vector<Answer> a = send_raw(run, datagram_frames(run, data), false);
        if (a.empty()) return {Status::kFail, what + "no answer", true};
        if (a[0].ok) return {Status::kWarn, what + "Datagram Received OK"};
        if (a[0].code == base::to_u16(base::ErrorCode::kCommandUnknown)) return {};
        if (is_permanent(a[0].code)) return {Status::kPass, what + "rejected " + hex(a[0].code)};
        // DatagramTransportS §6 asks for an answer; a code of 0 is one (MessageNetworkS §3.5.5).
        if (!is_temporary(a[0].code)) return {Status::kWarn, what + describe(a[0])};
    }
    // §6.2 lets a node reject temporarily as often as it needs to: a note, not a failure.
    return {Status::kWarn, what + "rejected temporarily " + std::to_string(kAttempts) + " times"};
}

// "a; b; c" of the non-empty notes.
std::string join(const std::vector<std::string>& parts) {
    std::string out;
    for (const std::string& p : parts)
        if (!p.empty()) out += (out.empty() ? "" : "; ") + p;
    return out;
}

}  // namespace

// da30, da40: every complete datagram is answered (DatagramTransportS 6); one of no known
// content type with Datagram Rejected 0x1042.
void unknown_protocol(CheckRun& run, const CheckSpec& spec) {
    if (!claims_datagrams(run))
        return run.out(spec).skip("the node's PIP does not claim the datagram protocol");
    Status worst = Status::kPass;
    std::vector<std::string> notes;
    for (std::size_t size : kSizes) {
        const SizeVerdict v = unknown_type_answer(run, size);
        notes.push_back(v.note);
        if (v.status == Status::kFail || (v.status == Status::kWarn && worst == Status::kPass))
            worst = v.status;
        // A node that answers nothing need not be waited for twice more.
        if (v.silent && size != kSizes.back()) {
            notes.push_back("the larger ones not sent");
            break;
        }
    }
    const std::string head = "datagrams of 1, 10 and 72 bytes with content type " +
                             hex(kUnknownType, 2) + " (no known protocol)";
    const std::string list = join(notes);
    if (worst == Status::kFail)
        return run.out(spec).fail(head + ": " + list, "Datagram Rejected 0x1042 to each", list);
    if (worst == Status::kWarn)
        return run.out(spec).warn(head + ": " + list +
                                  " (0x1042 is the recommended answer, DatagramTransportTN)");
    run.out(spec).pass(
        head + " rejected with " +
        (list.empty() ? "0x1042" : "a permanent error (" + list + "; the standard gives 0x1042)"));
}

// The verdict on one frame that starts no datagram: "" when one 0x204x reject came.
std::pair<Status, std::string> lone_frame_answer(CheckRun& run, FrameFormat format,
                                                 const std::string& what) {
    const std::array<std::uint8_t, 8> data = {kUnknownType, 1, 2, 3, 4, 5, 6, 7};
    const CanFrame f = can::make_frame(
        can::addressed_header(format, run.alias(), run.session().tool_alias()), data);
    const std::vector<Answer> a = send_raw(run, {f}, true);
    if (a.empty()) return {Status::kFail, what + ": no answer"};
    if (a.size() > 1)
        return {Status::kFail, what + ": answered " + std::to_string(a.size()) + " times"};
    if (a[0].ok || is_permanent(a[0].code) || a[0].code == 0)
        return {Status::kFail, what + ": " + describe(a[0])};
    if (a[0].code == base::to_u16(base::ErrorCode::kMiddleOrLastWithoutFirst))
        return {Status::kPass, ""};
    // Another temporary code still tells the sender to resend; 0x2041 says why.
    const Status st = is_out_of_order(a[0].code) ? Status::kPass : Status::kWarn;
    return {st, what + ": " + describe(a[0]) + " (0x2041 names the case)"};
}

// A first frame, then a whole 2-frame datagram: the second first frame arrives while the first
// datagram is unfinished.
std::pair<Status, std::string> overlap_answer(CheckRun& run) {
    std::vector<std::uint8_t> second(12);
    for (std::size_t i = 0; i < second.size(); ++i) second[i] = static_cast<std::uint8_t>(0x80 + i);
    second[0] = kUnknownType;
    std::vector<CanFrame> frames = datagram_frames(run, second);
    frames.insert(frames.begin(), frames.front());  // the unfinished first datagram's first frame
    const std::vector<Answer> a = send_raw(run, frames, true);
    const std::string what = "a first frame while another datagram was unfinished";
    if (a.empty()) return {Status::kFail, what + ": no answer"};
    auto temporary = std::find_if(a.begin(), a.end(),
                                  [](const Answer& x) { return !x.ok && is_temporary(x.code); });
    if (temporary == a.end())
        return {Status::kFail, what + ": no temporary reject (" + describe(a[0]) + ")"};
    if (is_out_of_order(temporary->code)) return {Status::kPass, ""};
    return {Status::kWarn, what + ": " + describe(*temporary) + " (0x2042 names the case)"};
}

// DatagramTransportS 7.3.2: a frame sequence that is not a datagram gets a temporary reject
// (0x2041: middle or last without first; 0x2042: first before the previous one finished).
void out_of_order(CheckRun& run, const CheckSpec& spec) {
    if (!claims_datagrams(run))
        return run.out(spec).skip("the node's PIP does not claim the datagram protocol");
    // The last frame first: after a lone middle frame a node may rightly take a last frame as
    // the end of the datagram it is discarding.
    const std::array<std::pair<Status, std::string>, 3> v = {
        lone_frame_answer(run, FrameFormat::kDatagramLast, "a last frame alone"),
        lone_frame_answer(run, FrameFormat::kDatagramMiddle, "a middle frame alone"),
        overlap_answer(run)};
    Status worst = Status::kPass;
    std::vector<std::string> notes;
    for (const auto& [st, note] : v) {
        notes.push_back(note);
        if (st == Status::kFail || (st == Status::kWarn && worst == Status::kPass)) worst = st;
    }
    const std::string list = join(notes);
    if (worst == Status::kFail)
        return run.out(spec).fail("frames that are no datagram: " + list,
                                  "one temporary reject 0x2040-0x204F each", list);
    if (worst == Status::kWarn)
        return run.out(spec).warn(
            "frames that are no datagram rejected temporarily, not with the "
            "out-of-order codes: " +
            list);
    run.out(spec).pass(
        "a lone last frame, a lone middle frame and an overlapping first frame: one "
        "temporary reject 0x2040-0x204F each" +
        (list.empty() ? "" : " (" + list + ")"));
}

std::vector<CheckSpec> datagram_protocol_checks() {
    return {
        {"datagram.unknown-protocol", 530, C::kDatagram,
         "DatagramTransportS §6; MessageNetworkS §3.5.5", Strength::kShall,
         "every datagram is answered with OK or Rejected; 0x1042 is recommended, a 0x0000 code or "
         "repeated temporary rejects WARN",
         "da30, da40",
         "raw datagrams of 1, 10 and 72 bytes with content type 0x5A: Datagram Rejected 0x1042 "
         "(another permanent 0x1xxx passes, noted; Datagram Received OK: WARN; no answer: FAIL)",
         unknown_protocol},
        {"datagram.out-of-order", 540, C::kDatagram,
         "DatagramTransportS §7.3.2; MessageNetworkS §3.5.5", Strength::kShall,
         "a frame sequence that is not a datagram is rejected with a temporary error", "",
         "a lone last frame, a lone middle frame, then a first frame followed by a whole 2-frame "
         "datagram: one temporary reject 0x2040-0x204F for each (0x2041, 0x2041, 0x2042), since "
         "§7.3.2 rejects any frame sequence that is not a datagram; the overlapping second "
         "datagram may be answered too or dropped; another 0x2xxx: WARN",
         out_of_order},
    };
}

}  // namespace olcb::conform::checks
