// The points where a fault changes what a simulated node does (issue 29: misbehaviour is a
// layer). A fault's declaration (fault_catalog.hpp) names a function for each point it uses;
// SimNode calls the hooks of the faults that are on, in catalogue order, each with its value.
// The protocol core (openlcb/, memory/) offers typed hand-over points and knows no fault.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "memory/memory_config_codec.hpp"
#include "memory/memory_config_server.hpp"
#include "memory/memory_space.hpp"
#include "memory/snip.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/train_control.hpp"
#include "simnode/broadcast_clock.hpp"
#include "simnode/faults.hpp"

namespace olcb::cdi {
struct Element;
}

namespace olcb::simnode {

class NodeMemory;

/// What a fault may do to the running node it is part of (SimNode implements it).
class NodeLife {
public:
    virtual TimePoint now() const = 0;
    /// Runs fn at `at` (restarts do not cancel it).
    virtual void schedule(TimePoint at, std::function<void(TimePoint)> fn) = 0;
    /// True between Initialization Complete and a restart or abort.
    virtual bool initialized() const = 0;
    virtual void send(Message message) = 0;
    /// Silent for `silence`, then a restart: a firmware crash and its watchdog.
    virtual void abort(std::chrono::milliseconds silence) = 0;
    /// The watched variable (NodeConfig::watch_variable) differs from its value at creation.
    virtual bool watched_changed() const = 0;
    /// Restores every writable space to its factory content.
    virtual void factory_reset() = 0;
    virtual NodeMemory& memory() = 0;
    /// Counts a failed write to storage (NodeCounters::storage_errors).
    virtual void storage_error() = 0;

protected:
    ~NodeLife() = default;
};

/// The CDI a node serves in space 0xFF, before it becomes bytes.
struct ServedCdi {
    std::string xml;                    ///< the text up to its first NUL
    bool terminated = true;             ///< one NUL follows the text
    std::vector<std::uint8_t> trailer;  ///< bytes after that
};

/// The ACDI version bytes a node serves in 252 and stores in 251.
struct AcdiVersions {
    std::uint8_t fixed = 0;
    std::uint8_t user = 0;
};

/// One variable's bytes on their way into storage: a written value or a default.
struct StoredValue {
    const cdi::Element& element;
    std::span<std::uint8_t> bytes;
};

/// A layer a fault puts in front of a space; power_cycle() is told of every restart.
class SpaceLayer : public memory::ForwardingSpace {
public:
    using ForwardingSpace::ForwardingSpace;
    virtual void power_cycle() {}
};

/// A space being built, and the layers faults put in front of it. Storage layers lie under the
/// encoding faults (they keep what was encoded), acknowledging layers above them (they decide
/// what reaches storage at all).
struct SpaceBuild {
    using Make = std::unique_ptr<SpaceLayer> (*)(memory::MemorySpace& inner);
    std::uint8_t number = 0;
    bool constant = false;  ///< 0xFF and 252: fixed content, read-only
    std::vector<Make> storage;
    std::vector<Make> acknowledging;
};

/// Which event IDs the node identifies.
struct EventPolicy {
    bool frozen_at_start = false;  ///< those of the last start-up, whatever was written since
    /// Slots (document order) never identified; nullptr: none hidden.
    bool (*hidden)(std::size_t slot) = nullptr;
};

/// How long the node holds back each answer (AnswerDelay).
struct AnswerLatency {
    std::chrono::milliseconds latency{0};
    std::chrono::milliseconds jitter{0};
};

/// A datagram arrived; a hook may reject it before anything reads it.
struct DatagramTurn {
    std::uint64_t index = 0;              ///< datagrams this node received before this one
    std::optional<std::uint16_t> reject;  ///< the error code to reject it with
};

/// A memory-configuration request on its way to the server, decoded once.
struct RequestTurn {
    memory::DecodeResult& asked;  ///< a hook may change the request the server sees
    NodeLife& life;
    /// Set by a hook to answer in the server's place (a refusal); later hooks still see it.
    std::optional<memory::Decision> answer;
    /// Run once the server accepted the request (e.g. to store what a hook took out of it).
    std::function<void()> accepted;
    /// After answering, the node goes silent this long and restarts (0: it does not).
    std::chrono::milliseconds silence_after{0};
};

/// A write the node stored and is about to confirm.
struct WriteTurn {
    std::uint64_t index = 0;  ///< writes this node stored before this one
    bool restart = false;     ///< restart instead of sending the Write Reply
};

/// The node's answer to a request, typed: encoded once after every hook had its turn.
struct ReplyTurn {
    const memory::DecodeResult& asked;  ///< the request as the server saw it
    memory::Decision& decision;         ///< accepted or rejected; the reply, if any
    /// Set by a hook: no Datagram Received OK goes out, the node acts at once (a Reset it
    /// performs before acknowledging).
    bool unacknowledged = false;
};

/// When a reply datagram goes out, relative to the Datagram Received OK that announces it
/// (asked for every accepted datagram; index counts the reply datagrams sent before it).
struct AnswerPlan {
    std::uint64_t index = 0;   ///< reply datagrams this node sent before this one
    bool reply_first = false;  ///< the reply goes out before the OK
    bool no_ok = false;        ///< no Datagram Received OK at all; the reply still goes
    Duration delay{0};         ///< the reply is held back this long after the OK
};

/// A train node being built (TrainControlS): what its faults change of its behaviour.
struct TrainBuild {
    bool fdi_space = true;        ///< serve the FDI in 0xFA (the PIP claims FDI either way)
    bool heartbeat_stops = true;  ///< a missed heartbeat deadline stops the train (§6.6)
    /// A second Reserve is refused even from the node holding the reservation.
    bool reserve_exclusive = false;
};

/// A Traction Control Reply on its way out, typed: a hook may change it before it is encoded.
struct TrainReplyTurn {
    const train::Command& asked;
    train::Reply& reply;
};

/// A command the train is about to forward to one listener (§6.5); a hook may drop it.
struct TrainForwardTurn {
    const train::Command& command;
    NodeId listener;
    bool drop = false;
};

/// The filters and stream policy faults install on the node's NodeStack. Each fault adds its
/// own; install() composes them, since the stack takes one of each.
class StackHooks {
public:
    /// Like NodeStack::InboundFilter, with the stack to answer on.
    using Inbound = std::function<FrameRoute(NodeStack&, const CanFrame&, TimePoint)>;

    void add_inbound(Inbound filter) { inbound_.push_back(std::move(filter)); }
    void add_outbound(NodeStack::OutboundFilter filter) { outbound_.push_back(std::move(filter)); }
    /// The last policy set wins: two window faults cannot both hold.
    void set_window(StreamTransport::WindowPolicy policy) { window_ = std::move(policy); }
    /// Installs what was added (nothing when nothing was).
    void install(NodeStack& stack) const;

private:
    std::vector<Inbound> inbound_;
    std::vector<NodeStack::OutboundFilter> outbound_;
    StreamTransport::WindowPolicy window_;
};

/// The hook points; a fault sets the ones it needs, the others stay nullptr.
struct FaultHooks {
    // Building the node.
    /// What its NodeStack is configured with (its PIP, alias behaviour, built-in answers).
    void (*stack_config)(NodeStackConfig&, FaultValue) = nullptr;
    /// Filters on its frames and messages, its stream window.
    void (*stack)(StackHooks&, FaultValue) = nullptr;
    /// How long it holds back its answers.
    void (*latency)(AnswerLatency&, FaultValue) = nullptr;
    /// The CDI it serves in space 0xFF.
    void (*cdi)(ServedCdi&, FaultValue) = nullptr;
    /// The ACDI version bytes of 252 and 251.
    void (*acdi)(AcdiVersions&, FaultValue) = nullptr;
    /// The layers in front of each space.
    void (*space)(SpaceBuild&, FaultValue) = nullptr;
    /// How a variable's value is stored (writes and defaults; never in 251/252).
    void (*store)(StoredValue&, FaultValue) = nullptr;
    /// Which event IDs it identifies.
    void (*events)(EventPolicy&, FaultValue) = nullptr;
    /// How its Broadcast Time clocks break the standard.
    void (*clock)(ClockQuirks&, FaultValue) = nullptr;

    /// Its train behaviour (a train node only).
    void (*train)(TrainBuild&, FaultValue) = nullptr;

    // The running node.
    /// Its first Initialization Complete.
    void (*started)(NodeLife&, FaultValue) = nullptr;
    /// Each restart, before the stack logs in again.
    void (*powering_up)(NodeLife&, FaultValue) = nullptr;
    /// A message it is to answer; true when the fault took it (nothing else answers it).
    bool (*message)(NodeLife&, const Message&, FaultValue) = nullptr;
    /// The SNIP content it sends.
    void (*snip)(memory::Snip&, FaultValue) = nullptr;
    /// A datagram before anything reads it.
    void (*datagram)(DatagramTurn&, FaultValue) = nullptr;
    /// A memory-configuration request before the server sees it.
    void (*request)(RequestTurn&, FaultValue) = nullptr;
    /// The decision about a request before it is sent.
    void (*reply)(ReplyTurn&, FaultValue) = nullptr;
    /// A write that was stored, before its Write Reply.
    void (*written)(WriteTurn&, FaultValue) = nullptr;
    /// When a reply datagram goes out.
    void (*answer)(AnswerPlan&, FaultValue) = nullptr;
    /// A Traction Control Reply before it is sent.
    void (*train_reply)(TrainReplyTurn&, FaultValue) = nullptr;
    /// A command before it is forwarded to a listener.
    void (*train_forward)(TrainForwardTurn&, FaultValue) = nullptr;

    /// Same hooks (FaultHooks{}: none, a fault that would change nothing).
    friend bool operator==(const FaultHooks&, const FaultHooks&) = default;
};

struct FaultDecl;

/// The faults of one node that are on, with their values, in catalogue order: what SimNode
/// calls at each hook point.
class ActiveFaults {
public:
    explicit ActiveFaults(const FaultSet& faults);

    /// True when a fault that is on reads the watched variable.
    bool watches() const;

    void stack_config(NodeStackConfig& config) const;
    /// Installs the faults' stack hooks on stack (which must outlive nothing it captures: the
    /// hooks own their state).
    void attach(NodeStack& stack) const;
    AnswerLatency latency() const;
    /// The bytes of space 0xFF for the CDI text (up to its first NUL, then one NUL).
    std::vector<std::uint8_t> served_cdi(std::string_view text) const;
    void acdi(AcdiVersions& versions) const;
    void space(SpaceBuild& build) const;
    /// True when a fault changes how values are stored.
    bool stores() const;
    void store(const cdi::Element& element, std::span<std::uint8_t> bytes) const;
    EventPolicy events() const;
    ClockQuirks clock() const;

    void started(NodeLife& life) const;
    void powering_up(NodeLife& life) const;
    bool message(NodeLife& life, const Message& message) const;
    void snip(memory::Snip& snip) const;
    void datagram(DatagramTurn& turn) const;
    void request(RequestTurn& turn) const;
    /// True when the answer goes out without its Datagram Received OK.
    bool reply(const memory::DecodeResult& asked, memory::Decision& decision) const;
    void written(WriteTurn& turn) const;
    void answer(AnswerPlan& plan) const;
    TrainBuild train() const;
    void train_reply(TrainReplyTurn& turn) const;
    void train_forward(TrainForwardTurn& turn) const;

private:
    struct Active {
        const FaultDecl* decl;
        FaultValue value;
    };
    std::vector<Active> on_;
};

}  // namespace olcb::simnode
