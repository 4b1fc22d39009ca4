// A simulated OpenLCB node built from a CDI: a NodeStack answering Verify, PIP, SNIP, event
// identification and the whole Memory Configuration Protocol from NodeMemory, with the faults of
// docs/faults.md. Sans-I/O like the stack: drive stack() with SimNetwork or StackDriver.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "memory/memory_config_server.hpp"
#include "memory/snip.hpp"
#include "openlcb/node_id.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/pip.hpp"
#include "simnode/answer_delay.hpp"
#include "simnode/broadcast_clock.hpp"
#include "simnode/event_roles.hpp"
#include "simnode/faults.hpp"
#include "simnode/faults/fault_hooks.hpp"
#include "simnode/node_memory.hpp"
#include "simnode/train_node.hpp"

namespace olcb::simnode {

/// The four manufacturer strings of SNIP and ACDI space 252.
struct Identity {
    std::string manufacturer, model, hardware_version, software_version;
};

/// Everything a SimNode is built from.
struct NodeConfig {
    NodeId node_id;                    ///< must not be zero
    std::string cdi;                   ///< the CDI text as read from the file
    std::filesystem::path cdi_file;    ///< where it was read from (for messages; may be empty)
    std::filesystem::path image_dir;   ///< empty: RAM-only images (nothing persisted)
    std::optional<Identity> identity;  ///< default: from the CDI <identification>
    std::string user_name;             ///< initial 251 name, for a FRESH image only
    std::string user_description;      ///< initial 251 description, for a FRESH image only
    FaultSet faults;                   ///< misbehaviours (none by default)
    /// Cursor::path() of the variable abort-on-value and factory-reset-on-version-change watch
    /// ("" = the first <int> of space 253).
    std::string watch_variable;
    /// Streams on (PIP stream bit, Options "stream reads", Read Stream served, incoming streams
    /// accepted), as an OpenMRN node; false = datagram-only.
    bool streams = true;
    /// Memory Configuration and the CDI served (PIP bits, datagrams answered); false = a node
    /// that is no configurable node (a throttle): memory-config datagrams rejected 0x1042.
    bool memory_config = true;
    /// A train node (TrainControlS): PIP Traction Control (and FDI with an FDI text), the Is
    /// Train event, Traction Control Commands answered, the functions in 0xF9, the FDI in 0xFA,
    /// Train Search queries answered (TrainSearchS §6.1).
    std::optional<TrainConfig> train;
    /// A command station (TrainSearchS §6.2): an allocating Train Search creates a train node
    /// (see SimNode::set_train_factory) from this template; its node IDs follow this node's.
    std::optional<TrainConfig> command_station;
    /// Broadcast Time clocks the node runs (generators and consumers; docs/scenarios.md).
    std::vector<ClockConfig> clocks;
};

/// Counters of what a node did, for tests and the program's statistics.
struct NodeCounters {
    std::uint32_t reboots = 0;  ///< Reset/Reboot commands obeyed
    /// Factory resets done: Factory Reset commands and factory-reset-on-version-change.
    std::uint32_t factory_resets = 0;
    std::uint32_t aborts = 0;             ///< abort-on-value crashes
    std::uint32_t write_reboots = 0;      ///< reboot-on-write restarts
    std::uint64_t datagrams = 0;          ///< datagrams received
    std::uint64_t temporary_rejects = 0;  ///< datagrams rejected by reject-temporary
    std::uint32_t storage_errors = 0;     ///< factory reset or counter writes that failed
};

/// One simulated node.
class SimNode {
    class Life;  // what the faults' hooks may do to it (NodeLife)

public:
    /// Loads the CDI (parse + layout; a CDI that parses and lays out but fails validation is
    /// served as it is, see cdi_problem()), opens or creates the images, builds spaces; nullptr
    /// with `error` set on failure.
    static std::unique_ptr<SimNode> create(NodeConfig config, std::string& error);
    SimNode(const SimNode&) = delete;
    SimNode& operator=(const SimNode&) = delete;
    ~SimNode();

    /// The protocol stack; drive with SimNetwork (tests) or StackDriver (program).
    NodeStack& stack() { return stack_; }
    /// The protocol stack.
    const NodeStack& stack() const { return stack_; }
    /// The configuration the node was created with.
    const NodeConfig& config() const { return config_; }
    /// Our node ID.
    NodeId node_id() const { return config_.node_id; }
    /// The SNIP content the node sends now (faults included).
    memory::Snip snip() const;
    /// The SNIP reply payload the node sends now.
    std::vector<std::uint8_t> snip_payload() const;
    /// The protocols the node serves (what PIP announces, before pip-missing-bit).
    ProtocolSet served_protocols() const { return served_protocols_; }
    /// The node's memory spaces.
    NodeMemory& memory() { return *memory_; }
    /// The node's memory spaces.
    const NodeMemory& memory() const { return *memory_; }
    /// The Memory Configuration server.
    memory::MemoryConfigServer& server() { return server_; }
    /// Event IDs and roles the node advertises now (events-stale-after-write: those it had at
    /// its last start-up).
    std::vector<std::pair<EventId, EventRole>> events() const { return advertised_events(); }
    /// What the node did so far.
    const NodeCounters& counters() const { return counters_; }
    /// The node's Broadcast Time clocks, in NodeConfig::clocks order.
    const std::vector<BroadcastClock>& clocks() const { return clocks_; }
    /// Reset/Reboot commands obeyed.
    std::uint32_t reboot_count() const { return counters_.reboots; }
    /// The train (nullptr when the node is none).
    const TrainNode* train() const { return train_.get(); }
    /// Creates a node on the running segment, as a command station asks: false when it could
    /// not. Called from the node's timers: an owner that may not add nodes there must defer.
    using TrainFactory = std::function<bool(NodeConfig)>;
    /// Sets who creates the trains a command station allocates (unset: it creates none).
    void set_train_factory(TrainFactory factory) { train_factory_ = std::move(factory); }
    /// Trains this command station created, in order (their node IDs).
    const std::vector<NodeId>& created_trains() const { return created_; }
    /// Told a line (without "simnode: ") when storage fails; unset: the line goes to stderr.
    using LogHandler = std::function<void(const std::string&)>;
    /// Sets who is told of storage failures.
    void set_log_handler(LogHandler handler) { log_ = std::move(handler); }
    /// Reply datagrams sent or scheduled since creation.
    std::uint64_t replies() const { return replies_; }
    /// The first validation error of the served CDI ("" when it is valid).
    const std::string& cdi_problem() const { return memory().model().first_error; }
    /// Address of the variable the faults that watch one read (watch_variable, or the first
    /// <int> of 253 in document order); nullopt when no such fault is set or the CDI has no
    /// such int.
    std::optional<std::uint32_t> watched_address() const;
    /// Runs the CAN login again (CID..RID, AMD, Initialization Complete) as a node does when a
    /// TCP client connects to it; memory, lock and images stay, answers still held are dropped.
    void relogin(TimePoint now);
    /// A power cycle, as a Reset/Reboot command makes (not counted as one): RAM-only state is
    /// forgotten, the alias reserved again (as new-alias-on-reboot says) and Initialization
    /// Complete sent; the transport is untouched.
    void reboot(TimePoint now);
    /// Stores bytes as a Memory Configuration write of them is stored (the served space with its
    /// faults, on disk before it returns) and reacts as to one: the written event IDs are
    /// identified, a changed space 251 sends Initialization Complete again. kOk, or why nothing
    /// was stored (kOutOfBounds also for a space the node does not serve).
    memory::WriteStatus write_memory(std::uint8_t space, std::uint32_t address,
                                     std::span<const std::uint8_t> bytes);

private:
    SimNode(NodeConfig config, NodeStackConfig stack_config, std::unique_ptr<NodeMemory> memory,
            ProtocolSet served);
    bool on_message(const Message& msg);
    bool answer_message(const Message& msg);
    bool answer_builtin(const Message& msg);
    void answer_late(const Message& msg);
    void on_datagram(const ReceivedDatagram& datagram);
    void answer_datagram(const ReceivedDatagram& datagram);
    void after_write(const memory::WrittenRange& written);
    memory::Decision decide(std::uint16_t src, std::span<const std::uint8_t> payload);
    void send_answer(std::uint16_t src, memory::Decision& decision);
    void find_watched();
    bool watched_changed() const;
    void abort_node(std::chrono::milliseconds silence);
    bool factory_reset();
    void log(const std::string& line) const;
    void power_up(TimePoint now);
    void on_initialized();
    void advertise(const EventSlot* only_begin, const EventSlot* only_end);
    void advertise_all();
    void identified(EventId id, bool producer);
    void send_reply(std::uint16_t dest, std::vector<std::uint8_t> reply);
    std::vector<std::pair<EventId, EventRole>> advertised_events() const;
    void start_stream_read(std::uint16_t src, const memory::StreamRead& read);
    void on_stream_event(const StreamEvent& event);
    bool answer_train(const Message& msg);
    bool answer_search(const Message& msg);
    void allocate(train_search::Query query, EventId asked);
    bool send_message(Message msg);
    void clock_message(const Message& msg);
    void arm_clocks();

    // A Read Stream waiting for its stream to be accepted, or being sent.
    struct PendingStreamRead {
        std::uint16_t requester = 0;
        memory::StreamRead read;
    };

    NodeConfig config_;
    NodeStack stack_;
    std::unique_ptr<NodeMemory> memory_;
    memory::MemoryConfigServer server_;
    ProtocolSet served_protocols_;
    NodeCounters counters_;
    ActiveFaults faults_;                // the faults' hooks
    std::unique_ptr<Life> life_;         // handed to the hooks of the running node
    AnswerDelay answer_delay_;           // as the faults' latency hooks say
    std::uint64_t replies_ = 0;          // reply datagrams sent or scheduled
    std::uint64_t stored_writes_ = 0;    // writes stored (WriteTurn::index)
    std::uint32_t boot_generation_ = 0;  // delayed replies of an earlier boot are dropped
    bool started_ = false;               // the first Initialization Complete went out
    // A request hook's silence once this answer is out (RequestTurn::silence_after).
    std::chrono::milliseconds silence_after_answer_{0};
    bool unacknowledged_ = false;  // a fault keeps the current datagram's OK back
    std::uint8_t watched_space_ = 253;
    std::optional<std::uint32_t> watched_address_;  // see watched_address()
    std::vector<std::uint8_t> watched_snapshot_;    // its bytes when the node was created
    // Event IDs at the last start-up (events-stale-after-write identifies only these).
    std::vector<std::pair<EventId, EventRole>> startup_events_;
    std::map<std::uint32_t, PendingStreamRead> stream_reads_;  // by stream handle
    std::vector<BroadcastClock> clocks_;
    BroadcastClock::Send clock_send_;       // what the clocks send goes out through the stack
    std::optional<TimePoint> clock_timer_;  // when the clocks' scheduled poll runs
    LogHandler log_;
    std::unique_ptr<TrainNode> train_;  // the train of a train node
    TrainFactory train_factory_;
    std::vector<NodeId> created_;  // trains a command station created
    // Searches a command station was asked to allocate for, and whether a train answered them
    // in the 200 ms it waits (TrainSearchS §6.2).
    std::map<EventId, bool> allocating_;
};

}  // namespace olcb::simnode
