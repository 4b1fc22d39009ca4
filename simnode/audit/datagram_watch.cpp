#include "simnode/audit/datagram_watch.hpp"

#include <algorithm>
#include <chrono>
#include <string>

#include "base/error_codes.hpp"
#include "base/hex.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/datagram_defs.hpp"
#include "openlcb/mti.hpp"
#include "simnode/audit/audit_limits.hpp"

namespace olcb::simnode::audit {
namespace {

// Exchanges followed at once; beyond, new pairs are ignored (a flood from made-up aliases must
// not grow the audit without bound).
constexpr std::size_t kMaxPairs = 65536;

std::optional<Mti> addressed_mti(const CanFrame& frame) {
    if (!can::is_message(frame.id) ||
        can::frame_format(frame.id) != can::FrameFormat::kGlobalAddressed || frame.len < 2) {
        return std::nullopt;
    }
    return static_cast<Mti>(can::can_mti(frame.id));
}

std::vector<CanFrame> joined(std::span<const CanFrame> a, std::span<const CanFrame> b) {
    std::vector<CanFrame> out(a.begin(), a.end());
    out.insert(out.end(), b.begin(), b.end());
    return out;
}

std::string ms(Duration d) {
    return std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(d).count()) + " ms";
}

}  // namespace

DatagramWatch::Step DatagramWatch::assemble(Assembly& a, const CanFrame& frame, std::string& why) {
    const std::span<const std::uint8_t> data(frame.data.data(), frame.len);
    switch (can::frame_format(frame.id)) {
        case can::FrameFormat::kDatagramOnly:
        case can::FrameFormat::kDatagramFirst: {
            const bool only = can::frame_format(frame.id) == can::FrameFormat::kDatagramOnly;
            const bool broke = a.open;
            if (broke) why = "a first or only frame before the last frame of the previous datagram";
            a = Assembly{{frame}, {data.begin(), data.end()}, !only, broke};
            return only ? Step::kComplete : Step::kMore;
        }
        case can::FrameFormat::kDatagramMiddle:
        case can::FrameFormat::kDatagramLast: {
            const bool last = can::frame_format(frame.id) == can::FrameFormat::kDatagramLast;
            if (!a.open) {
                why = last ? "a last frame without a first" : "a middle frame without a first";
                a = Assembly{{frame}, {}, false, false};
                return Step::kBroken;
            }
            a.frames.push_back(frame);
            a.bytes.insert(a.bytes.end(), data.begin(), data.end());
            if (!last && data.empty()) why = "an empty middle frame";
            if (a.bytes.size() > datagram::kMaxSize) why = "more than 72 bytes in one datagram";
            if (!why.empty()) {
                a.open = false;
                return Step::kBroken;
            }
            a.open = !last;
            return last ? Step::kComplete : Step::kMore;
        }
        default:
            return Step::kMore;
    }
}

void DatagramWatch::on_client_frame(const CanFrame& frame, std::uint16_t node, TimePoint now) {
    const std::uint16_t client = can::source_alias(frame.id);
    const std::uint32_t key = pair_key(client, node);
    if (!pairs_.contains(key) && pairs_.size() >= kMaxPairs) return;
    Pair& p = pairs_[key];
    if (can::is_datagram_format(can::frame_format(frame.id))) {
        on_client_datagram_frame(p, frame, client, node, now);
        return;
    }
    const auto mti = addressed_mti(frame);
    if (mti == Mti::kDatagramReceivedOk || mti == Mti::kDatagramRejected) {
        on_client_ack(p, frame, client, node, now);
    } else if (mti == Mti::kSnipRequest) {
        on_snip_request(p, frame, client, node, now);
    }
}

void DatagramWatch::on_node_frame(const CanFrame& frame, std::uint16_t client, TimePoint now) {
    const std::uint16_t node = can::source_alias(frame.id);
    const std::uint32_t key = pair_key(client, node);
    if (!pairs_.contains(key) && pairs_.size() >= kMaxPairs) return;
    Pair& p = pairs_[key];
    if (can::is_datagram_format(can::frame_format(frame.id))) {
        on_node_datagram_frame(p, frame, now);
        return;
    }
    const auto mti = addressed_mti(frame);
    if (mti == Mti::kDatagramReceivedOk || mti == Mti::kDatagramRejected) {
        on_node_answer(p, frame, now);
    } else if (mti == Mti::kSnipReply) {
        const auto framing = can::addressed_framing(frame.data[0]);
        if (framing == can::AddressedFraming::kOnly || framing == can::AddressedFraming::kLast)
            p.snip_due.reset();
    }
}

void DatagramWatch::on_client_datagram_frame(Pair& p, const CanFrame& frame, std::uint16_t client,
                                             std::uint16_t node, TimePoint now) {
    std::vector<CanFrame> unfinished =
        p.from_client.open ? p.from_client.frames : std::vector<CanFrame>{};
    std::string why;
    const Step step = assemble(p.from_client, frame, why);
    if (!why.empty()) {
        // A broken datagram shows its own frames; a new one cutting in, the one it cut off.
        std::vector<CanFrame> frames = step == Step::kBroken ? p.from_client.frames : unfinished;
        if (step != Step::kBroken) frames.push_back(frame);
        ctx_.report(RuleId::kDatagramFrameSequence, client, node,
                    "datagram frames out of sequence: " + why, frames, "", now);
    }
    if (step == Step::kComplete) judge_datagram(p, client, node, now);
}

void DatagramWatch::judge_datagram(Pair& p, std::uint16_t client, std::uint16_t node,
                                   TimePoint now) {
    const Assembly& a = p.from_client;
    if (p.last && !p.last->broken) judge_against_last(p, client, node, now);
    judge_resend(p, a.bytes, client, node, a.frames, now);
    p.last = Sent{a.bytes, a.frames, now, Answer::kNone, a.broken};
    p.pending.reset();
    p.reply_seen = false;
    sink_(client, node, a.bytes, a.frames, now);
}

// The datagram just completed, judged against the client's previous one to the node.
void DatagramWatch::judge_against_last(Pair& p, std::uint16_t client, std::uint16_t node,
                                       TimePoint now) {
    const Sent& last = *p.last;
    const bool same = last.payload == p.from_client.bytes;
    const auto frames = joined(last.frames, p.from_client.frames);
    const std::string since = ms(now - last.at);
    if (last.answer == Answer::kNone && now - last.at < kRequesterTimeout) {
        ctx_.report(
            same ? RuleId::kDatagramResendWithoutReject : RuleId::kDatagramOverlap, client, node,
            same ? "sent the same datagram again " + since + " later, before the node answered it"
                 : "sent another datagram " + since +
                       " after the previous one, before the node answered it",
            frames, "", now);
    } else if (last.answer == Answer::kOk && p.pending && !p.reply_seen) {
        judge_while_pending(p, same, frames, client, node, now);
    } else if (last.answer == Answer::kPermanent && same) {
        ctx_.report(RuleId::kDatagramResendAfterPermanent, client, node,
                    "sent the same datagram again " + since +
                        " after the node rejected it with a permanent error",
                    frames, "", now);
    }
}

// A datagram while the reply the node announced is still to come. The same one again is a
// timeout: no shorter than 3 s (MessageNetworkS §3.7), or the 2^N s the OK promised when that
// is shorter (MemoryConfigurationS §4.4, §4.8 allow a repeat once it elapsed). Another one is
// allowed, but worth a note.
void DatagramWatch::judge_while_pending(const Pair& p, bool same, std::span<const CanFrame> frames,
                                        std::uint16_t client, std::uint16_t node, TimePoint now) {
    const Pending& w = *p.pending;
    const std::string waited = ms(now - w.ok_at);
    if (!same) {
        if (now >= w.due) return;
        ctx_.report(RuleId::kMemoryRequestBeforeReply, client, node,
                    "sent another datagram " + waited +
                        " after the node accepted the previous one with Reply Pending; its "
                        "reply had not come yet",
                    frames, "", now);
        return;
    }
    if (w.exponent == 0) {
        if (now - w.ok_at >= kRequesterTimeout) return;
        ctx_.report(RuleId::kDatagramResendAfterOk, client, node,
                    "sent the same datagram again " + waited +
                        " after the node accepted it with Reply Pending (no time stated, so "
                        "a requester waits at least 3 s); its reply had not come yet",
                    frames, "", now);
        return;
    }
    const Duration promised = std::chrono::seconds(1u << w.exponent);
    if (now - w.ok_at >= std::min(promised, kRequesterTimeout)) return;
    const std::string flags = base::hex(datagram::ok_flags(true, w.exponent), 2);
    ctx_.report(RuleId::kDatagramResendBeforeTimeout, client, node,
                "sent the same datagram again " + waited +
                    " after the node's Datagram Received OK (flags " + flags +
                    ") promised the reply within 2^" + std::to_string(w.exponent) +
                    " s = " + std::to_string(1u << w.exponent) + " s; its reply had not come yet",
                frames, "", now);
}

void DatagramWatch::judge_resend(Pair& p, const std::vector<std::uint8_t>& payload,
                                 std::uint16_t client, std::uint16_t node,
                                 std::span<const CanFrame> frames, TimePoint now) {
    if (!p.last || p.last->answer != Answer::kTemporary || p.last->payload != payload) {
        p.resends.clear();
        return;
    }
    p.resends.push_back(now);
    while (now - p.resends.front() > kStormWindow) p.resends.pop_front();
    if (p.resends.size() > kStormResends) {
        ctx_.report(RuleId::kDatagramRetryStorm, client, node,
                    std::to_string(p.resends.size()) +
                        " resends of one datagram within 1 s after temporary rejects",
                    frames, "", now);
    }
}

void DatagramWatch::on_client_ack(Pair& p, const CanFrame& frame, std::uint16_t client,
                                  std::uint16_t node, TimePoint now) {
    if (!p.unacknowledged) return;
    const Duration took = now - p.unacknowledged->at;
    if (took > kAnswerDue) {
        ctx_.report(RuleId::kDatagramReplyAckLate, client, node,
                    "answered the node's datagram " + ms(took) +
                        " after its last frame (due within " + ms(kAnswerDue) + ")",
                    joined(p.unacknowledged->frames, std::span(&frame, 1)), "", now);
    }
    p.unacknowledged.reset();
}

void DatagramWatch::on_snip_request(Pair& p, const CanFrame& frame, std::uint16_t client,
                                    std::uint16_t node, TimePoint now) {
    if (p.snip_due && now < *p.snip_due) {
        ctx_.report(RuleId::kSnipRequestBeforeReply, client, node,
                    "asked for SNIP again before the whole reply to its previous request came",
                    std::span(&frame, 1), "", now);
    }
    p.snip_due = now + kRequesterTimeout;
}

void DatagramWatch::on_node_answer(Pair& p, const CanFrame& frame, TimePoint now) {
    // An answer to nothing outstanding answers a broken frame sequence, not a datagram.
    if (!p.last || p.last->answer != Answer::kNone) return;
    if (addressed_mti(frame) == Mti::kDatagramReceivedOk) {
        const std::uint8_t flags = frame.len > 2 ? frame.data[2] : 0;
        p.last->answer = Answer::kOk;
        if (datagram::is_reply_pending(flags) && !p.reply_seen) {
            const auto announced = datagram::reply_timeout(flags);
            p.pending = Pending{now, datagram::timeout_exponent(flags),
                                now + (announced ? Duration(*announced) : kRequesterTimeout)};
        }
        return;
    }
    // Missing error code bits read as zero (DatagramTransportS §4.3); only the permanent flag
    // forbids a resend.
    const std::uint16_t code = static_cast<std::uint16_t>((frame.len > 2 ? frame.data[2] << 8 : 0) |
                                                          (frame.len > 3 ? frame.data[3] : 0));
    p.last->answer = base::is_permanent(code) ? Answer::kPermanent : Answer::kTemporary;
}

void DatagramWatch::on_node_datagram_frame(Pair& p, const CanFrame& frame, TimePoint now) {
    std::string why;  // the node's own sequencing is not the audit's business
    if (assemble(p.from_node, frame, why) != Step::kComplete) return;
    p.unacknowledged = Reply{p.from_node.frames, now};
    p.reply_seen = true;
    p.pending.reset();
}

void DatagramWatch::node_restarted(std::uint16_t node) {
    std::erase_if(pairs_, [node](const auto& entry) { return pair_node(entry.first) == node; });
}

void DatagramWatch::report_unacknowledged(Pair& p, std::uint16_t client, std::uint16_t node,
                                          const char* why, TimePoint now) {
    ctx_.report(
        RuleId::kDatagramReplyUnacknowledged, client, node,
        std::string("the node's datagram got neither Datagram Received OK nor Rejected ") + why,
        p.unacknowledged->frames, "", now);
    p.unacknowledged.reset();
}

void DatagramWatch::client_gone(std::uint16_t client, TimePoint now) {
    for (auto it = pairs_.begin(); it != pairs_.end();) {
        if (pair_client(it->first) != client) {
            ++it;
            continue;
        }
        if (it->second.unacknowledged) {
            report_unacknowledged(it->second, client, pair_node(it->first),
                                  "before the client's connection ended", now);
        }
        it = pairs_.erase(it);
    }
}

void DatagramWatch::poll(TimePoint now) {
    for (auto& [key, p] : pairs_) {
        if (p.unacknowledged && now - p.unacknowledged->at >= kRequesterTimeout)
            report_unacknowledged(p, pair_client(key), pair_node(key), "within 3 s", now);
        if (p.pending && now >= p.pending->due) p.pending.reset();
        if (p.snip_due && now >= *p.snip_due) p.snip_due.reset();
    }
}

std::optional<TimePoint> DatagramWatch::next_deadline() const {
    std::optional<TimePoint> next;
    const auto consider = [&next](TimePoint t) {
        if (!next || t < *next) next = t;
    };
    for (const auto& [key, p] : pairs_) {
        if (p.unacknowledged) consider(p.unacknowledged->at + kRequesterTimeout);
        if (p.pending) consider(p.pending->due);
        if (p.snip_due) consider(*p.snip_due);
    }
    return next;
}

}  // namespace olcb::simnode::audit
