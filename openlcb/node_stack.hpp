// One virtual OpenLCB node on a CAN segment, sans-I/O: alias allocation, Initialization Complete,
// message assembly and dispatch, datagram transport and the mandatory built-in answers.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "base/node_id.hpp"
#include "openlcb/addressed_framing.hpp"
#include "openlcb/alias_allocator.hpp"
#include "openlcb/alias_cache.hpp"
#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/datagram_transport.hpp"
#include "openlcb/message.hpp"
#include "openlcb/pip.hpp"
#include "openlcb/stream_transport.hpp"

namespace olcb {

/// Mandatory answers the stack gives by itself; each can be switched off for an owner that wants
/// to answer itself through on_message.
struct NodeBuiltins {
    /// Verify Node ID (global: empty or our ID; addressed: always) -> Verified Node ID.
    bool verify_node_id = true;
    /// Protocol Support Inquiry -> Protocol Support Reply with NodeStackConfig::protocols.
    bool protocol_support = true;
    /// Addressed message nobody handled -> Optional Interaction Rejected 0x1043 (see
    /// never_rejected()).
    bool reject_unknown_addressed = true;
    /// Datagram while no datagram handler is set -> OIR 0x1043 echoing MTI 0x1C48.
    bool reject_datagrams_without_handler = true;
    /// Another node claims our node ID (a Verified Node ID or AMD carrying it from another
    /// alias): send the duplicate-node-ID PCER (01.01.00.00.00.00.02.01), at most once per
    /// kDuplicatePcerInterval (a flood of duplicates gets one), and keep working. The PCER is
    /// optional (fact sheet 1.6); going silent as the standard then asks would stop a tool.
    bool duplicate_id_pcer = false;
};

/// Least time between two duplicate-node-ID PCERs (NodeBuiltins::duplicate_id_pcer).
inline constexpr Duration kDuplicatePcerInterval = std::chrono::seconds(1);

/// Which layers of the stack take in one incoming frame (NodeStack::set_inbound_filter).
struct FrameRoute {
    /// The alias allocator: RID on a CID for our alias, AMR and a new alias when another node
    /// uses it, AME answers, duplicate node IDs.
    bool alias = true;
    /// Message, datagram and stream assembly and their dispatch (an Initialized node only).
    bool messages = true;
};

/// Everything a NodeStack is built from.
struct NodeStackConfig {
    NodeId node_id;                            ///< our 48-bit node ID (must not be zero)
    ProtocolSet protocols;                     ///< what the node really supports (PSR contents)
    AliasAllocatorConfig alias;                ///< CID/RID timing, duplicate-ID policy
    DatagramSenderConfig datagram_sender;      ///< ack timeout, resends, queue bound
    DatagramReceiverConfig datagram_receiver;  ///< buffers, reassembly timeout
    MessageAssemblerConfig assembler;          ///< multi-frame limits (datagrams are ignored)
    NodeBuiltins builtins;                     ///< built-in answers switched on
    /// Stream transport on: stream messages go to NodeStack::streams() (off: Initiate Request
    /// gets OIR 0x1043 as from a node without streams).
    bool streams = false;
    StreamTransportConfig stream;  ///< limits and timeouts of the stream transport
    /// After an alias conflict took a new alias: send Initialization Complete again (and call
    /// on_initialized). Off by default, as OpenMRN: the node stays Initialized; AMD announces the
    /// new mapping.
    bool reinitialize_after_alias_change = false;
    /// restart() continues the alias generator's sequence, so the node comes back on a different
    /// alias (allowed: the alias is re-allocated at every start-up). Off by default: it starts
    /// over from the first generator alias.
    bool new_alias_on_restart = false;
    /// Messages send_message() holds while the node is not yet Initialized; more are refused.
    std::size_t max_pending_messages = 256;
    /// Frames held for pop_frame(); beyond this new frames are dropped (and counted).
    std::size_t max_output_frames = 4096;
};

/// Result of NodeStack::send_message().
enum class SendStatus : std::uint8_t {
    kSent,                ///< framed into the output
    kQueued,              ///< held until Initialization Complete has been sent
    kUnknownDestination,  ///< destination has neither an alias nor a node ID the cache knows
    kFramingError,        ///< payload too long for the MTI, or similar (see encode_message)
    kQueueFull,           ///< max_pending_messages reached
    kHalted,              ///< duplicate node ID detected: the node stays silent
    kSilent,              ///< go_silent(): nothing is sent or held until restart()
};

/// One node on one CAN segment. Feed it every frame of the segment (on_frame) and the time
/// (poll at next_deadline()); take its frames with pop_frame(). Nothing here blocks or reads a
/// clock. Frames are produced in the order they must go on the wire.
///
/// Lifecycle: start() reserves an alias (CID7..4, >= 200 ms, RID, AMD), then sends Initialization
/// Complete as the first message and calls on_initialized. Messages given to send_message()
/// earlier are held and sent right after it. Only an Initialized node dispatches messages.
///
/// When another node re-initializes (Initialization Complete, or an AMD not answering an AME),
/// every datagram queued or awaiting an ack for its alias ends as kAborted at once.
class NodeStack {
public:
    /// Receives every global message and every message addressed to us (datagrams excepted);
    /// returns true when it answered (or deliberately ignored) an addressed message, false lets
    /// the stack reject it with OIR.
    using MessageHandler = std::function<bool(const Message&)>;
    /// Receives each complete datagram; the owner must answer it with accept_datagram() or
    /// reject_datagram(), now or later (the buffer stays in use until then).
    using DatagramHandler = std::function<void(const ReceivedDatagram&)>;
    /// Receives the final result of each datagram given to send_datagram().
    using OutcomeHandler = std::function<void(const DatagramOutcome&)>;
    /// Called right after Initialization Complete went out (advertise events now).
    using InitializedHandler = std::function<void()>;
    /// Called for every alias allocator event (permitted, conflict, alias lost, duplicate ID).
    using AliasEventHandler = std::function<void(const AliasEvent&)>;
    /// Called when the output goes from empty to non-empty, or a timer was scheduled (for
    /// drivers, which then flush and re-arm; see StackDriver).
    using OutputHandler = std::function<void()>;
    /// Receives every stream event (opened, data, completed, ...; see StreamEvent).
    using StreamHandler = std::function<void(const StreamEvent&)>;
    /// An owner timer, called with the time of the poll() that runs it.
    using TimerHandler = std::function<void(TimePoint)>;
    /// Sees every incoming frame first (before the stack's own checks) and says which layers
    /// take it in. The core keeps no misbehaviour of its own: an owner that must break a rule on
    /// purpose (simnode's faults) hides frames from a layer here, or answers them itself.
    using InboundFilter = std::function<FrameRoute(const CanFrame&, TimePoint)>;
    /// Sees every message the stack frames (its own answers, the owner's, the stream
    /// transport's; datagrams go around it), its source filled in; may change it; false drops it.
    using OutboundFilter = std::function<bool(Message&)>;

    /// A stopped stack; call start().
    explicit NodeStack(NodeStackConfig config);
    NodeStack(const NodeStack&) = delete;
    NodeStack& operator=(const NodeStack&) = delete;

    // ---- owner callbacks ----
    /// Sets the message handler (replaces any previous one).
    void set_message_handler(MessageHandler handler) { on_message_ = std::move(handler); }
    /// Sets the datagram handler; without one, datagrams are answered with OIR 0x1043.
    void set_datagram_handler(DatagramHandler handler) { on_datagram_ = std::move(handler); }
    /// Sets the datagram outcome handler.
    void set_outcome_handler(OutcomeHandler handler) { on_outcome_ = std::move(handler); }
    /// Sets the handler called after each Initialization Complete.
    void set_initialized_handler(InitializedHandler handler) {
        on_initialized_ = std::move(handler);
    }
    /// Sets the alias event handler.
    void set_alias_event_handler(AliasEventHandler handler) {
        on_alias_event_ = std::move(handler);
    }
    /// Sets the stream event handler.
    void set_stream_handler(StreamHandler handler) { on_stream_ = std::move(handler); }
    /// Sets the inbound frame filter (none: every layer takes every frame).
    void set_inbound_filter(InboundFilter filter) { inbound_filter_ = std::move(filter); }
    /// Sets the outbound message filter (none: every message goes out as given).
    void set_outbound_filter(OutboundFilter filter) { outbound_filter_ = std::move(filter); }
    /// Sets the output notification (used by the driver running this stack).
    void set_output_handler(OutputHandler handler) { on_output_ = std::move(handler); }
    /// The global messages the message handler is given; the stack drops the others (Verify
    /// Node ID Global still gets the built-in answer), so a driver of many stacks need not
    /// deliver them at all (StackGroup). nullopt, the default: every global message.
    void set_global_messages(std::optional<std::vector<Mti>> mtis);
    /// The CAN-MTIs of the global messages the handler takes; nullopt: every one.
    const std::optional<std::vector<std::uint16_t>>& global_can_mtis() const {
        return global_can_mtis_;
    }
    /// True when the message handler takes global messages of this CAN-MTI.
    bool takes_global(std::uint16_t can_mti) const;
    /// Looks alias mappings up in `cache`, which its owner learns from every frame of the
    /// segment (the stacks of a StackGroup share one, as the virtual nodes of one interface do);
    /// the stack then keeps no cache of its own, and restart() leaves the shared one alone.
    /// nullptr: a cache of its own again, empty.
    void share_alias_cache(std::shared_ptr<const AliasCache> cache);

    // ---- lifecycle ----
    /// Begins alias reservation; no effect when already started or silent.
    void start(TimePoint now);
    /// A reboot: drops all reassembly, datagram and pending state (outstanding datagrams are
    /// reported kAborted), forgets its own alias cache (not a shared one), and runs start-up again
    /// from the first generator alias (the next one with NodeStackConfig::new_alias_on_restart). No
    /// AMR is sent: a rebooting node just goes silent and starts over. Frames already in the output
    /// stay there (they count as handed to the CAN controller). Ends silence.
    void restart(TimePoint now);
    /// A crash: drops all state as restart() does but starts nothing; until restart() every frame
    /// is ignored (no answer, no alias defence) and nothing is sent. Owner timers still run, so
    /// one of them may call restart() later. Frames already in the output stay there.
    void go_silent(TimePoint now);
    /// Leaves the segment for good, as a node being unplugged cleanly: AMR for the alias when
    /// Permitted (so others drop their mapping), then silent as go_silent(). The AMR stays in
    /// the output for the driver to send.
    void release(TimePoint now);
    /// Sends Initialization Complete again with the same alias (e.g. after SNIP data changed),
    /// abandons partial incoming messages and datagrams, and calls on_initialized. Ignored
    /// unless the node is Initialized.
    void reinitialize(TimePoint now);

    // ---- input ----
    /// Processes one frame of the segment (any frame: ours are filtered cheaply).
    void on_frame(const CanFrame& frame, TimePoint now);
    /// Runs the timers of every part; call at next_deadline() (calling earlier is harmless).
    void poll(TimePoint now);
    /// Earliest time poll() has work, if any.
    std::optional<TimePoint> next_deadline() const;
    /// The CAN driver failed to send a frame (a tentative alias is then abandoned).
    void on_transmit_error(TimePoint now);
    /// Runs fn at the first poll() at or after `at` (owner timers, e.g. delayed replies); timers
    /// due at the same time run in the order scheduled; they survive restart().
    void schedule(TimePoint at, TimerHandler fn);
    /// The latest time given to start(), restart(), reinitialize(), on_frame() or poll().
    TimePoint now() const { return now_; }
    /// Owner timers not yet run.
    std::size_t scheduled() const { return timers_.size(); }

    // ---- output ----
    /// Sends msg from this node; source is filled in. An addressed message needs the
    /// destination alias, or a node ID the alias cache knows. Before Initialization Complete
    /// the message is held (kQueued) and framed with the alias in use when it goes out.
    SendStatus send_message(Message msg);
    /// Queues a datagram (0..72 bytes) to dest_alias; returns its id, or nullopt when the node
    /// is not Initialized, the payload is too long or the sender queue is full.
    std::optional<std::uint32_t> send_datagram(std::uint16_t dest_alias,
                                               std::span<const std::uint8_t> payload,
                                               TimePoint now);
    /// Answers a delivered datagram from src with Datagram Received OK (flags: Reply Pending
    /// etc., see datagram::ok_flags); false when none from src was waiting (the OK still goes).
    bool accept_datagram(std::uint16_t src, std::uint8_t flags = 0);
    /// Answers a delivered datagram from src with Datagram Rejected code; false when none from
    /// src was waiting (the reject still goes).
    bool reject_datagram(std::uint16_t src, std::uint16_t code);
    /// Frees a delivered datagram from src without answering it (see DatagramReceiver::release).
    bool release_datagram(std::uint16_t src);
    /// Ends a sent datagram whose reply came without an OK (see DatagramSender::settle); its
    /// kUnacknowledged outcome goes to the outcome handler before this returns.
    bool settle_datagram(std::uint32_t id, TimePoint now);
    /// Opens an outgoing stream to dest (see StreamTransport::open); nullopt when streams are off,
    /// the node is not Initialized or too many streams are open.
    std::optional<std::uint32_t> open_stream(NodeHandle dest, std::uint16_t buffer,
                                             std::uint8_t suggested_dest_id);
    /// Queues bytes on an outgoing stream.
    bool write_stream(std::uint32_t id, std::span<const std::uint8_t> data);
    /// Ends an outgoing stream with Data Complete once its bytes went out.
    bool close_stream(std::uint32_t id);
    /// Announces an incoming stream (see StreamTransport::expect).
    void expect_stream(std::uint16_t remote_alias, std::uint8_t dest_id, std::uint16_t max_buffer,
                       bool auto_proceed = true);
    /// Sends Data Proceed on an incoming stream (manual proceed).
    bool proceed_stream(std::uint32_t id);
    /// The stream transport (counters, window policy); streams change through the calls above.
    StreamTransport& streams() { return streams_; }
    /// Next frame to transmit, oldest first.
    std::optional<CanFrame> pop_frame();
    /// Appends every pending frame to out; returns how many.
    std::size_t drain(std::vector<CanFrame>& out);
    /// True when pop_frame() would return a frame.
    bool has_output() const { return out_head_ < out_.size(); }

    // ---- state ----
    /// Our node ID.
    NodeId node_id() const { return config_.node_id; }
    /// Alias held now (tentative, reserved or active); 0 when none.
    std::uint16_t alias() const { return alias_.alias(); }
    /// True when the node is Initialized and Permitted, i.e. sends and answers messages now.
    bool initialized() const { return initialized_ && alias_.permitted(); }
    /// True after a duplicate node ID stopped the node (only with halt_on_duplicate).
    bool halted() const { return alias_.state() == AliasAllocator::State::kHalted; }
    /// True between go_silent() and the next restart().
    bool silent() const { return silent_; }
    /// True when an inbound filter is set (it must see every frame of the segment).
    bool has_inbound_filter() const { return static_cast<bool>(inbound_filter_); }
    /// True while datagrams it sent wait to go out or for their acknowledgement (then it must
    /// see every node's AMD and Initialization Complete, which end those to that node).
    bool sending_datagrams() const { return sender_.queued() != 0; }
    /// Mappings learned about other nodes (node ID <-> alias).
    const AliasCache& alias_cache() const { return alias_.cache(); }
    /// The alias state machine (state, attempts).
    const AliasAllocator& alias_allocator() const { return alias_; }
    /// Built-in answers, switchable at run time.
    NodeBuiltins& builtins() { return config_.builtins; }
    /// Protocols announced in the Protocol Support Reply.
    void set_protocols(ProtocolSet protocols) { config_.protocols = protocols; }
    /// Protocols announced in the Protocol Support Reply.
    ProtocolSet protocols() const { return config_.protocols; }
    /// The configuration (built-ins and protocols as changed since).
    const NodeStackConfig& config() const { return config_; }
    /// Frames dropped because the output exceeded max_output_frames.
    std::uint64_t dropped_frames() const { return dropped_frames_; }
    /// Number of times Initialization Complete was sent.
    std::uint32_t initializations() const { return initializations_; }
    /// When it last became Initialized after reserving an alias (a start-up or restart; not a
    /// reinitialize() on the same alias); the epoch before the first.
    TimePoint logged_in_at() const { return logged_in_at_; }

    /// True for MTIs never answered with OIR when unhandled: OIR and TDE themselves and the
    /// replies (PSR, SNIP reply, Datagram OK/Rejected, stream replies/data, traction reply).
    static bool never_rejected(std::uint16_t mti);

private:
    void dispatch(const Message& msg);
    bool handle_builtin(const Message& msg);
    void push_verified_node_id();
    void route_message_frame(const CanFrame& frame, TimePoint now);
    void announce_duplicate();
    void on_datagram_frame(const CanFrame& frame, TimePoint now);
    void on_addressed_frame(const CanFrame& frame, TimePoint now);
    void on_global_frame(const CanFrame& frame, TimePoint now);
    bool announces_reinitialization(const CanFrame& frame, bool control, TimePoint now) const;
    void send_oir(std::uint16_t dest, std::uint16_t code, std::uint16_t mti);
    void send_initialization_complete();
    void handle_alias_event(const AliasEvent& event);
    void enter_permitted();
    void flush_pending();
    SendStatus frame_message(Message& msg);
    void push_frame(const CanFrame& frame);
    // Moves the frames of one part that has no callbacks (cheaper than collect()).
    template <class Part>
    void take_frames(Part& part) {
        while (auto f = part.pop_frame()) push_frame(*f);
    }
    void collect();
    bool collect_streams();
    void run_timers(TimePoint now);
    void drop_state();

    NodeStackConfig config_;
    AliasAllocator alias_;
    MessageAssembler assembler_;
    DatagramSender sender_;
    DatagramReceiver receiver_;
    StreamTransport streams_;

    MessageHandler on_message_;
    DatagramHandler on_datagram_;
    OutcomeHandler on_outcome_;
    InitializedHandler on_initialized_;
    AliasEventHandler on_alias_event_;
    OutputHandler on_output_;
    StreamHandler on_stream_;
    InboundFilter inbound_filter_;
    OutboundFilter outbound_filter_;

    bool started_ = false;
    bool initialized_ = false;  // message layer; alias_.permitted() tells the link layer
    bool collecting_ = false;
    bool silent_ = false;
    std::uint16_t previous_alias_ = 0;  // alias before the last restart (new_alias_on_restart)
    std::vector<Message> pending_;
    std::vector<CanFrame> out_;  // out_[out_head_..] pending; reused to avoid allocation
    std::size_t out_head_ = 0;
    std::vector<CanFrame> encode_buf_;
    Message scratch_;  // single-frame global messages are decoded here without allocating
    std::uint64_t dropped_frames_ = 0;
    std::uint32_t initializations_ = 0;
    TimePoint logged_in_at_{};
    std::multimap<TimePoint, TimerHandler> timers_;
    TimePoint now_{};
    std::optional<TimePoint> last_ame_;  // AMDs right after an AME answer it (no re-init)
    std::optional<TimePoint> last_duplicate_pcer_;               // rate limit of duplicate_id_pcer
    std::optional<std::vector<std::uint16_t>> global_can_mtis_;  // set_global_messages()
};

}  // namespace olcb
