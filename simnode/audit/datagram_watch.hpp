// The datagram and request/reply rules of the client audit: frame sequences, one datagram at a
// time, resends, the node's reply datagrams and their acknowledgement, requests before replies
// (memory configuration and SNIP). Complete client datagrams go on to the memory rules.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "simnode/audit/audit_context.hpp"

namespace olcb::simnode::audit {

/// Receives each complete datagram a client sent one of simnode's nodes, with its frames.
using DatagramSink = std::function<void(std::uint16_t client, std::uint16_t node,
                                        std::span<const std::uint8_t> payload,
                                        std::span<const CanFrame> frames, TimePoint now)>;

/// Follows every (client alias, node alias) exchange.
class DatagramWatch {
public:
    /// A watch reporting to ctx; complete client datagrams go to sink.
    DatagramWatch(AuditContext& ctx, DatagramSink sink) : ctx_(ctx), sink_(std::move(sink)) {}

    /// A frame a client sent to node alias `node` (datagram frames and addressed messages).
    void on_client_frame(const CanFrame& frame, std::uint16_t node, TimePoint now);
    /// A frame node alias `node` sent to client alias `client`.
    void on_node_frame(const CanFrame& frame, std::uint16_t client, TimePoint now);
    /// The node at alias restarted or gave the alias up: its exchanges are void.
    void node_restarted(std::uint16_t node);
    /// A client alias is gone (its connection ended): what it left unacknowledged is judged.
    void client_gone(std::uint16_t client, TimePoint now);
    /// Judges the time limits.
    void poll(TimePoint now);
    /// When poll() next has something to judge.
    std::optional<TimePoint> next_deadline() const;

private:
    struct Assembly {
        std::vector<CanFrame> frames;
        std::vector<std::uint8_t> bytes;
        bool open = false;
        bool broken = false;  // started where a frame sequence broke: the node may drop it
    };
    enum class Answer : std::uint8_t { kNone, kOk, kTemporary, kPermanent };
    struct Sent {
        std::vector<std::uint8_t> payload;
        std::vector<CanFrame> frames;
        TimePoint at{};
        Answer answer = Answer::kNone;
        bool broken = false;
    };
    struct Reply {
        std::vector<CanFrame> frames;
        TimePoint at{};
    };
    // A Datagram Received OK with Reply Pending: what it promised and when.
    struct Pending {
        TimePoint ok_at{};
        std::uint8_t exponent = 0;  // N of "the reply within 2^N s"; 0: no time stated
        TimePoint due{};            // the reply may come until then (2^N s, else 3 s)
    };
    struct Pair {
        Assembly from_client;
        Assembly from_node;
        std::optional<Sent> last;             // the client's last complete datagram
        std::optional<Pending> pending;       // Reply Pending, its reply not come yet
        bool reply_seen = false;              // a node datagram came after the client's last
        std::deque<TimePoint> resends;        // resends after temporary rejects (storms)
        std::optional<Reply> unacknowledged;  // a node datagram the client has not answered
        std::optional<TimePoint> snip_due;    // a SNIP request whose reply is not complete
    };
    enum class Step : std::uint8_t { kMore, kComplete, kBroken };

    static Step assemble(Assembly& a, const CanFrame& frame, std::string& why);
    void on_client_datagram_frame(Pair& p, const CanFrame& frame, std::uint16_t client,
                                  std::uint16_t node, TimePoint now);
    void judge_datagram(Pair& p, std::uint16_t client, std::uint16_t node, TimePoint now);
    void judge_against_last(Pair& p, std::uint16_t client, std::uint16_t node, TimePoint now);
    void judge_while_pending(const Pair& p, bool same, std::span<const CanFrame> frames,
                             std::uint16_t client, std::uint16_t node, TimePoint now);
    void judge_resend(Pair& p, const std::vector<std::uint8_t>& payload, std::uint16_t client,
                      std::uint16_t node, std::span<const CanFrame> frames, TimePoint now);
    void on_client_ack(Pair& p, const CanFrame& frame, std::uint16_t client, std::uint16_t node,
                       TimePoint now);
    void on_snip_request(Pair& p, const CanFrame& frame, std::uint16_t client, std::uint16_t node,
                         TimePoint now);
    void on_node_answer(Pair& p, const CanFrame& frame, TimePoint now);
    void on_node_datagram_frame(Pair& p, const CanFrame& frame, TimePoint now);
    void report_unacknowledged(Pair& p, std::uint16_t client, std::uint16_t node, const char* why,
                               TimePoint now);

    AuditContext& ctx_;
    DatagramSink sink_;
    std::unordered_map<std::uint32_t, Pair> pairs_;  // by pair_key(client, node)
};

}  // namespace olcb::simnode::audit
