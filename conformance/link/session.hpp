// Synchronous-looking operations on a Link: discovery, messages, SNIP, PIP and the memory
// configuration client the checks are written with. Everything received is recorded.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "base/timings.hpp"
#include "conformance/link/link.hpp"
#include "conformance/link/write_ledger.hpp"
#include "memory/memory_config_codec.hpp"
#include "openlcb/datagram_transport.hpp"
#include "openlcb/message.hpp"
#include "openlcb/pip.hpp"

namespace olcb::conform {

/// lcc-conform's own node IDs: 05.01.01.01.3F.01 to .FE (the self-assigned experimental range),
/// one per run.
inline constexpr std::uint64_t kToolIdBase = 0x0501'0101'3F00ull;
/// True when id is one an lcc-conform run takes.
constexpr bool is_tool_id(NodeId id) {
    return (id.value() & ~std::uint64_t{0xFF}) == kToolIdBase;
}

/// A node found on the segment.
struct NodeInfo {
    NodeId id;
    std::uint16_t alias = 0;
};

/// Outcome of one memory-configuration exchange.
struct MemResult {
    bool ok = false;                 ///< reply OK (read data / write done)
    std::uint16_t error = 0;         ///< reject or fail code when !ok (0x2010 on timeout)
    bool rejected = false;           ///< Datagram Rejected (vs Reply Fail)
    bool timed_out = false;          ///< no answer in time
    std::vector<std::uint8_t> data;  ///< read data
    bool datagram_ok_seen = false;   ///< Datagram Received OK arrived (before the reply, if any)
    bool reply_pending = false;      ///< its Reply Pending flag
    /// The reply timeout the OK announced (reply within 2^N s; 0 = none); the largest of a range.
    std::uint8_t reply_timeout_exponent = 0;
    bool reply_in_request_form = true;  ///< reply used the same short/byte-6 form as the request
    Duration reply_latency{};           ///< request sent -> reply datagram received
    unsigned temporary_rejects = 0;     ///< 0x2xxx rejects that were retried
    bool restarted = false;  ///< the node re-initialized before acknowledging: no answer comes
    /// No answer came from a node noted as never acknowledging (NodeTrack::never_acks): whether
    /// it took the request is unknown (timed_out is set too).
    bool unacknowledged = false;
    /// A write the ledger's gate kept back: nothing was sent (not_sent says why).
    std::string not_sent;
};

/// Buffer lcc-conform grants a node's stream by default: the largest, so a CDI read needs no
/// Data Proceed round trip (the node's own proposal caps it).
inline constexpr std::uint16_t kToolStreamBuffer = 0xFFFF;
/// Read Stream count lcc-conform sends for "to the end": every server cuts a read at the end of
/// the space, while count 0 (the standard's "to the end") reads nothing on OpenMRN.
inline constexpr std::uint32_t kStreamToEnd = 0xFFFF'FFFF;

/// How Session::read_stream reads.
struct StreamReadOptions {
    std::uint16_t buffer = kToolStreamBuffer;  ///< the most we grant
    std::uint32_t count = kStreamToEnd;        ///< Read Stream count
    /// 0: Proceed at once. Otherwise each full buffer is held this long before the Proceed,
    /// and data arriving meanwhile is counted (a source must wait for Proceed).
    Duration hold{};
    memory::SpaceForm form = memory::SpaceForm::kAuto;
    Duration idle_timeout = base::kRequesterTimeout;  ///< no progress this long: timed out
    /// More bytes than this end the read (the stream is dropped, `cut` set): the node's own end
    /// of the space is what normally ends it, so this only bounds a node that never stops.
    std::size_t max_bytes = SIZE_MAX;
    std::function<void(std::size_t)> progress;  ///< called with the bytes so far as data comes
};

/// Outcome of one memory-config stream read.
struct StreamReadResult {
    MemResult mem;               ///< ok, error, data (the stream's bytes), Datagram OK flags
    bool initiated = false;      ///< the node sent a Stream Initiate Request we accepted
    std::uint16_t proposed = 0;  ///< buffer the node proposed
    std::uint16_t granted = 0;   ///< buffer we granted
    std::optional<memory::ReadStreamReply> reply;  ///< the Read Stream Reply OK
    bool completed = false;                        ///< Data Complete arrived
    std::optional<std::uint32_t> complete_count;   ///< the count it carried
    std::uint64_t max_in_window = 0;               ///< most bytes between two of our Proceeds
    std::uint64_t during_hold = 0;  ///< bytes that arrived while a full buffer was held
    std::uint64_t data_frames = 0;  ///< Data Send frames received
    std::uint64_t proceeds = 0;     ///< Data Proceed messages we sent
    Duration elapsed{};             ///< request sent -> Complete (or the end of the wait)
    bool cut = false;               ///< the node sent more than max_bytes (data holds max_bytes)
};

/// What the session has seen of one node.
struct NodeTrack {
    std::uint16_t alias = 0;            ///< current alias (0: never seen)
    std::uint32_t initializations = 0;  ///< Initialization Complete messages seen from it
    /// Alias reservations seen: an AMD with its node ID from an alias that sent RID since that
    /// alias's previous AMD (AMDs answering an AME do not count), less those a check excused
    /// (Session::excuse_reservations).
    std::uint32_t reservations = 0;
    TimePoint last_heard{};  ///< time of the last frame from its current alias
    /// A datagram of ours whose reply came got no Datagram Received OK (nor Rejected) within
    /// the sender's timeout: the node is noted once as not acknowledging, and from then on each
    /// reply ends its datagram's wait (the next request goes at once).
    bool never_acks = false;
    /// Datagrams answered by their reply without an OK: the one that timed out, then the settled.
    std::uint32_t unacknowledged = 0;

    /// An Initialization Complete or an alias reservation since `before` was taken.
    bool restarted_since(const NodeTrack& before) const {
        return initializations != before.initializations || reservations != before.reservations;
    }
};

/// A Read Reply OK that carried fewer bytes than asked.
struct ShortRead {
    NodeId node;                ///< the node that answered
    std::uint8_t space = 0;     ///< space read
    std::uint32_t address = 0;  ///< address read
    std::uint8_t asked = 0;     ///< count asked
    std::size_t got = 0;        ///< bytes returned
    bool continued = false;     ///< a later read at address+got returned data
    bool at_end = false;        ///< a later read at address+got failed 0x1082 or returned nothing
};

/// One received message with its arrival time.
struct ReceivedMessage {
    Message message;
    TimePoint at;
};

/// Blocking-style client on a Link; all waits go through Link::run_until.
class Session {
public:
    /// Hooks into the link's stack (message, datagram and outcome handlers) and frame tap.
    explicit Session(Link& link);
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    /// Waits for our alias and Initialization Complete.
    bool start(Duration timeout = std::chrono::seconds(2));
    /// Sends Verify Node ID global (again while nothing answers) until no new node appeared for
    /// `quiet`, at most `max`; every node seen (Verified Node ID, Initialization Complete, AMD).
    std::vector<NodeInfo> discover(Duration max = std::chrono::seconds(3),
                                   Duration quiet = std::chrono::milliseconds(500));
    /// Every node seen so far on the segment (ours excepted), by node ID.
    std::vector<NodeInfo> nodes_seen() const;
    std::size_t nodes_seen_count() const;
    /// Another lcc-conform run seen on the segment (a node of the tools' ID range, not ours).
    std::optional<NodeId> other_tool() const;  // nodes_seen().size() without building the list
    /// Sends Verify Node ID global with id every 500 ms until that node answers or announces
    /// itself (Initialization Complete), at most `timeout`.
    std::optional<NodeInfo> find_node(NodeId id, Duration timeout = std::chrono::seconds(1));
    /// Time from a Verify Node ID addressed to the node's Verified Node ID; nullopt on timeout.
    std::optional<Duration> round_trip(const NodeInfo& node, Duration timeout);

    /// What the session has seen of node id (a default NodeTrack when never seen).
    NodeTrack track(NodeId id) const;
    /// Takes n alias reservations of node id out of track(id).reservations: ones a check
    /// provoked (an alias collision it staged, a Reset it sent), which the node watch must not
    /// take for a restart nobody asked for.
    void excuse_reservations(NodeId id, std::uint32_t n);
    /// The node's current alias as tracked from the traffic, else node.alias.
    std::uint16_t alias_of(const NodeInfo& node) const;
    /// Verify Node ID addressed to the node's current alias; when no answer in half the timeout,
    /// Verify Node ID global carrying its node ID; true when it answered.
    bool ping(const NodeInfo& node, Duration timeout);
    /// Every Read Reply OK shorter than asked, in arrival order (bounded).
    const std::vector<ShortRead>& short_reads() const { return short_reads_; }
    /// Read requests answered with a Read Reply (OK or Fail), per node and space.
    std::uint64_t reads(NodeId node, std::uint8_t space) const;

    /// Sends a message from our node.
    SendStatus send(Message msg);
    /// Every message arriving (from now on) within window that matches.
    std::vector<Message> collect(const std::function<bool(const Message&)>& match, Duration window);
    /// The first message arriving (from now on) within timeout that matches.
    std::optional<Message> wait_for(const std::function<bool(const Message&)>& match,
                                    Duration timeout);
    /// Frames seen on the segment since a mark (ours, received and injected).
    std::vector<CanFrame> frames_since(std::size_t mark) const;
    /// Aliases other than ours that sent datagram frames to alias `to`, among the frames recorded
    /// so far, each once with the node ID it announced (nullopt: none seen).
    std::vector<std::pair<std::uint16_t, std::optional<NodeId>>> datagram_senders_to(
        std::uint16_t to) const;
    /// Mark for frames_since().
    std::size_t frame_mark() const { return frames_.size(); }
    /// Messages received since a mark (see message_mark()).
    std::vector<ReceivedMessage> messages_since(std::size_t mark) const;
    /// Mark for messages_since().
    std::size_t message_mark() const { return messages_.size(); }
    /// Puts a raw frame on the segment (our own stack does not see it, nor does node tracking).
    void inject(const CanFrame& frame);
    /// Drives the network for d after the frames we queued are through (silence windows).
    void wait(Duration d) { link_.run_until({}, d + backlog()); }
    /// Drives the network until pred() or `window` after the frames we queued are through: an
    /// answer or silence window on a CAN segment starts when our request is on the wire.
    bool run_until(const std::function<bool()>& pred, Duration window);
    /// How long the frames we sent still need on the link's bus (worst-case frame lengths),
    /// counted from each frame's sending: zero once the bus could have carried them all.
    Duration backlog();
    /// The link under this session.
    Link& link() { return link_; }
    /// Our node ID.
    NodeId tool_id() { return link_.stack().node_id(); }
    /// Our alias.
    std::uint16_t tool_alias() { return link_.stack().alias(); }

    /// Protocol Support Inquiry -> the reply's flags; nullopt without a reply.
    std::optional<ProtocolSet> protocol_support(const NodeInfo& node);
    /// SNIP request -> the reassembled payload (multi-frame or legacy); nullopt without a reply.
    std::optional<std::vector<std::uint8_t>> snip_payload(const NodeInfo& node);
    /// Reads count (1..64) bytes.
    MemResult read(const NodeInfo& node, memory::Space space, std::uint32_t address,
                   std::uint8_t count, memory::SpaceForm form = memory::SpaceForm::kAuto);
    /// Writes 1..64 bytes.
    MemResult write(const NodeInfo& node, memory::Space space, std::uint32_t address,
                    std::span<const std::uint8_t> data,
                    memory::SpaceForm form = memory::SpaceForm::kAuto);
    /// Any memory-config command; returns the decoded reply datagram when one came.
    MemResult command(const NodeInfo& node, std::span<const std::uint8_t> payload,
                      memory::Message* reply = nullptr);
    /// Reads [address, address+length) in reads of up to 64 bytes, each going on where the
    /// previous reply's data ended (a short reply is not the end); stops at a NUL (stop_at_nul;
    /// the NUL is kept as the last data byte), an empty reply or 0x1082 (the end of the space: ok
    /// stays true with what was read), or any other error; progress(bytes_so_far) is called after
    /// each read.
    MemResult read_range(const NodeInfo& node, memory::Space space, std::uint32_t address,
                         std::uint32_t length, bool stop_at_nul,
                         const std::function<void(std::size_t)>& progress = {});

    /// Reads [address, address + count) of space through a memory-config stream (Read Stream,
    /// Datagram OK, Stream Initiate Request accepted, Read Stream Reply, data, Data Complete).
    StreamReadResult read_stream(const NodeInfo& node, memory::Space space, std::uint32_t address,
                                 const StreamReadOptions& options = {});

    /// Every write this session sent or was asked to send (its gate decides which go out).
    WriteLedger& ledger() { return ledger_; }
    const WriteLedger& ledger() const { return ledger_; }

    /// How long to wait for the reply datagram after Datagram Received OK.
    void set_reply_timeout(Duration d) { reply_timeout_ = d; }
    /// How long to wait for the reply datagram after Datagram Received OK.
    Duration reply_timeout() const { return reply_timeout_; }
    /// How long to wait for a Protocol Support Reply or a SNIP reply.
    void set_answer_timeout(Duration d) { answer_timeout_ = d; }
    /// How long to wait for a Protocol Support Reply or a SNIP reply.
    Duration answer_timeout() const { return answer_timeout_; }

private:
    struct Event {
        Message message;
        TimePoint at;
        std::uint64_t seq = 0;
    };
    struct OutcomeRecord {
        DatagramOutcome outcome;
        TimePoint at;
        std::uint64_t seq = 0;
    };

    // What the session knows of one alias seen on the segment.
    struct AliasState {
        std::optional<NodeId> owner;  // node whose AMD, Initialization Complete or Verified came
        // The node ID bits of the CID7..CID4 frames from it since its last AMD (a reservation
        // under way carries its whole node ID in the four of them).
        std::uint64_t cid_bits = 0;
        std::uint8_t cid_parts = 0;         // bit n-4 set: CIDn seen
        std::optional<NodeId> rid_pending;  // RID of a reservation by this node ID
    };
    using ReadKey = std::tuple<std::uint64_t, std::uint8_t, std::uint32_t>;

    MemResult exchange(const NodeInfo& node, std::span<const std::uint8_t> payload,
                       bool always_reply, memory::Message* reply);
    /// True when the exchange is over without a reply (result says why): the datagram was
    /// rejected, or the node restarted (back_elsewhere: on another alias) and will not answer.
    bool ended_unanswered(const OutcomeRecord* oc, std::span<const std::uint8_t> payload,
                          bool back_elsewhere, MemResult& result) const;
    /// True when node id announced itself again (Initialization Complete) since it had
    /// `initializations`, on another alias than `alias`.
    bool came_back_elsewhere(NodeId id, std::uint32_t initializations, std::uint16_t alias) const;
    MemResult send_exchange(const NodeInfo& node, std::span<const std::uint8_t> payload,
                            bool always_reply, memory::Message* reply);
    const OutcomeRecord* outcome_of(std::uint32_t datagram_id) const;
    /// The reply to datagram_id came: when its OK has not, either the node is known not to
    /// acknowledge (the datagram is settled now) or the outcome handler decides when it ends.
    void replied(std::uint32_t datagram_id, NodeId node);
    /// Sends a datagram once the previous one to alias has ended, so it leaves (and its reply
    /// is timed) now; nullopt when the stack refused it.
    std::optional<std::uint32_t> send_datagram_after(std::uint16_t alias,
                                                     std::span<const std::uint8_t> payload);
    void on_outcome(const DatagramOutcome& o);
    /// Whether the reply's OK came first, the request's retries and its latency.
    void time_reply(const OutcomeRecord* oc, const Event& reply, TimePoint sent_at,
                    MemResult& result) const;
    /// A request to a node that never acknowledges ended without an answer.
    static MemResult unacknowledged_result();
    /// A datagram to a node that never acknowledges got neither reply nor reject in time: ended
    /// now (or by the sender's timeout already); false when it was answered after all.
    bool no_answer_settled(std::uint32_t datagram_id);
    struct StreamWait;  // session_stream.cpp
    bool stream_progress(StreamWait& w);
    void stream_event(StreamWait& w, const StreamEvent& e);
    void stream_hold(StreamWait& w);
    void observe(const CanFrame& frame, TimePoint at);
    void queue_on_wire(const CanFrame& frame, TimePoint at);
    /// An answer to the last frame we queued came: the frames before it are through.
    void backlog_through();
    void observe_control(const CanFrame& frame, TimePoint at);
    void set_alias(NodeId id, std::uint16_t alias);
    NodeTrack* track_for(NodeId id);
    void record_read(const NodeInfo& node, std::uint8_t space, std::uint32_t address,
                     std::uint8_t count, const MemResult& r);

    Link& link_;
    std::vector<StreamEvent> stream_events_;  // every stream event of our stack, in order
    std::uint8_t next_stream_id_ = 0x40;
    std::vector<Event> messages_;
    std::vector<CanFrame> frames_;
    std::map<std::uint32_t, OutcomeRecord> outcomes_;
    std::map<std::uint32_t, NodeId> replied_unacked_;  // replied datagrams waiting for their OK
    std::map<std::uint16_t, std::uint32_t> last_datagram_;  // the latest datagram to each alias
    std::uint64_t seq_ = 0;
    bool injecting_ = false;  // frames we inject are not the node's: tracking skips them
    std::map<NodeId, NodeTrack> tracks_;
    std::map<std::uint16_t, AliasState> aliases_;
    std::vector<ShortRead> short_reads_;
    std::multimap<ReadKey, std::size_t> open_short_reads_;  // keyed by where the data ended
    std::map<std::pair<std::uint64_t, std::uint8_t>, std::uint64_t> reads_;
    WriteLedger ledger_;
    TimePoint backlog_end_{};
    std::map<NodeId, TimePoint>
        excused_until_;  // restarts allowed after an Update Complete  // when the frames we sent
                         // are through the link's bus
    Duration reply_timeout_ = base::kRequesterTimeout;
    Duration answer_timeout_ = std::chrono::seconds(1);
};

}  // namespace olcb::conform
