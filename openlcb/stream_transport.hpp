// Stream transport (StreamTransportS), sans-I/O, at the message level: both ends of any number of
// concurrent streams, keyed by (remote alias, SID, DID). Messages in (on_message), messages out
// (pop_message; Data Send is framed as CAN format 7 by encode_message), events for the owner
// (pop_event), time only through the TimePoint arguments.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "base/timings.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/message.hpp"
#include "openlcb/stream_defs.hpp"

namespace olcb {

/// Tunables of StreamTransport.
struct StreamTransportConfig {
    /// Incoming Initiate Requests nobody announced with expect() are accepted (data discarded
    /// after counting); false rejects them with stream::kRejectNotAccepted.
    bool accept_unsolicited = false;
    /// Largest buffer the sink grants (the granted one is the smaller of this and the proposed).
    std::uint16_t sink_max_buffer = 1024;
    /// Streams open at once (both directions); beyond this requests are rejected 0x2020.
    std::size_t max_streams = 8;
    /// Window a source proposes when open() is given 0.
    std::uint16_t source_buffer = stream::kMaxBufferSize;
    Duration initiate_timeout = base::kStreamInitiateTimeout;  ///< source: wait for the reply
    Duration proceed_timeout = base::kStreamProceedTimeout;    ///< source: wait for Data Proceed
    Duration idle_timeout = base::kStreamIdleTimeout;          ///< sink: wait for the next data
};

/// Something the owner must know about one stream.
struct StreamEvent {
    enum class Kind : std::uint8_t {
        kOpened,      ///< source: accepted by the sink; sink: an incoming stream was accepted
        kRejected,    ///< source: Initiate Reply with an error code, or OIR (code holds it)
        kData,        ///< sink: data bytes arrived (data holds them)
        kWindowFull,  ///< sink, manual proceed: a buffer is full, call proceed()
        kCompleted,   ///< sink: Data Complete arrived; source: Data Complete was sent
        kTerminated,  ///< Terminate Due to Error from the remote
        kTimedOut,    ///< no reply / Proceed / data in time; the stream is dropped
    };
    Kind kind = Kind::kOpened;
    std::uint32_t id = 0;   ///< the stream's handle (open() or the kOpened event)
    bool outgoing = false;  ///< we are the source
    NodeHandle remote;      ///< the other end
    std::uint8_t source_id = 0;
    std::uint8_t dest_id = 0;
    std::uint16_t buffer = 0;            ///< granted window
    std::uint16_t code = 0;              ///< reject / terminate error code
    std::vector<std::uint8_t> data;      ///< kData: the bytes
    std::uint64_t bytes = 0;             ///< payload bytes moved so far
    std::optional<std::uint32_t> count;  ///< kCompleted: the count the Complete carried
};

/// Counters of one stream (see StreamTransport::info).
struct StreamInfo {
    bool outgoing = false;
    NodeHandle remote;
    std::uint8_t source_id = 0;
    std::uint8_t dest_id = 0;
    std::uint16_t proposed = 0;       ///< buffer in the Initiate Request
    std::uint16_t buffer = 0;         ///< granted buffer
    std::uint64_t bytes = 0;          ///< payload bytes sent / received
    std::uint64_t data_frames = 0;    ///< Data Send messages sent / received
    std::uint64_t proceeds = 0;       ///< Data Proceed messages sent / received
    std::uint64_t max_in_window = 0;  ///< sink: most bytes received between two Proceeds
    bool open = false;                ///< accepted and not yet completed
};

/// Both ends of the stream transport for one node.
class StreamTransport {
public:
    /// A transport with the given limits.
    explicit StreamTransport(StreamTransportConfig config = {}) : config_(config) {}

    /// True for the MTIs this transport consumes (stream MTIs; OIR/TDE are offered too).
    static bool handles(Mti mti);
    /// Processes one message addressed to us; true when it belonged to a stream of ours.
    bool on_message(const Message& msg, TimePoint now);
    /// Handles timeouts.
    void poll(TimePoint now);
    /// When poll() next has work.
    std::optional<TimePoint> next_deadline() const;
    /// Drops every stream silently (node restarted).
    void reset();

    // ---- source ----
    /// Sends an Initiate Request to dest proposing buffer (0 = config source_buffer) and
    /// suggesting dest_id; returns the stream's handle, or nullopt when max_streams are open.
    std::optional<std::uint32_t> open(NodeHandle dest, std::uint16_t buffer,
                                      std::uint8_t suggested_dest_id, TimePoint now);
    /// Queues bytes on an outgoing stream (sent as the window allows); false for unknown ids.
    bool write(std::uint32_t id, std::span<const std::uint8_t> data);
    /// Sends Data Complete with the total count once everything queued went out.
    bool close(std::uint32_t id);

    // ---- sink ----
    /// Announces an Initiate Request from remote_alias suggesting dest_id (0xFF: any): it is
    /// accepted with a buffer of at most max_buffer; with auto_proceed false the owner gets
    /// kWindowFull and must call proceed().
    void expect(std::uint16_t remote_alias, std::uint8_t dest_id, std::uint16_t max_buffer,
                bool auto_proceed = true);
    /// Sends Data Proceed on an incoming stream; false for unknown ids.
    bool proceed(std::uint32_t id);
    /// Forgets an incoming or outgoing stream without a message (the owner gave up on it).
    void drop(std::uint32_t id);

    // ---- output and state ----
    /// Next message to send (source is filled in by the node stack).
    std::optional<Message> pop_message();
    /// True when pop_message() would return a message now.
    bool has_output() const;
    /// Next event for the owner.
    std::optional<StreamEvent> pop_event();
    /// Counters of a stream still known (open, or kept after it ended until reset()).
    std::optional<StreamInfo> info(std::uint32_t id) const;
    /// Streams open now.
    std::size_t open_streams() const;
    /// The configuration (may be changed at run time).
    StreamTransportConfig& config() { return config_; }

    /// How many bytes a source may send for one grant of `buffer` bytes (the Initiate Reply's
    /// buffer, then again per Data Proceed). The standard's answer is `buffer`, the default; an
    /// owner that must overrun a sink on purpose (simnode's faults) returns more, up to
    /// kUnlimitedWindow (never wait for a Proceed).
    using WindowPolicy = std::function<std::uint64_t(std::uint16_t buffer)>;
    /// A window no stream exhausts.
    static constexpr std::uint64_t kUnlimitedWindow = std::uint64_t{1} << 62;
    /// Sets the window policy (none: exactly the granted buffer).
    void set_window_policy(WindowPolicy policy) { window_policy_ = std::move(policy); }

private:
    enum class State : std::uint8_t { kInitiating, kOpen, kClosed };
    // The window one grant of `buffer` opens (window_policy_, bounded by kUnlimitedWindow).
    std::uint64_t grant(std::uint16_t buffer) const;
    struct Stream {
        StreamInfo info;
        State state = State::kInitiating;
        TimePoint deadline{};
        std::deque<std::uint8_t> queue;  // source: bytes not yet sent
        std::uint64_t window = 0;        // source: bytes allowed before the next Proceed
        std::uint64_t in_window = 0;     // sink: bytes since the last Proceed
        bool closing = false;            // source: Complete once the queue is empty
        bool auto_proceed = true;        // sink
    };
    struct Expectation {
        std::uint16_t remote = 0;
        std::uint8_t dest_id = stream::kInvalidStreamId;
        std::uint16_t max_buffer = 0;
        bool auto_proceed = true;
    };

    void on_initiate_request(const Message& msg, TimePoint now);
    bool on_initiate_reply(const Message& msg, TimePoint now);
    bool on_data(const Message& msg, TimePoint now);
    bool on_proceed(const Message& msg, TimePoint now);
    bool on_complete(const Message& msg, TimePoint now);
    bool on_reject(const Message& msg);
    Stream* find_outgoing(std::uint16_t remote, std::uint8_t sid);
    Stream* find_incoming(std::uint16_t remote, std::uint8_t did);
    std::uint8_t free_dest_id(std::uint16_t remote, std::uint8_t suggested) const;
    std::uint8_t free_source_id(std::uint16_t remote);
    void maybe_complete(Stream& s);
    void prune();
    void send(Mti mti, const NodeHandle& to, std::vector<std::uint8_t> payload);
    void emit(StreamEvent::Kind kind, std::uint32_t id, const Stream& s);
    std::optional<Message> next_data();
    bool ready_to_send(const Stream& s) const;

    StreamTransportConfig config_;
    std::uint32_t next_id_ = 1;
    std::map<std::uint32_t, Stream> streams_;
    std::vector<Expectation> expected_;
    std::deque<Message> control_;
    WindowPolicy window_policy_;
    std::deque<StreamEvent> events_;
    std::uint32_t round_robin_ = 0;  // id after which next_data() looks first
    std::uint8_t next_sid_ = 1;
    TimePoint now_{};
};

}  // namespace olcb
