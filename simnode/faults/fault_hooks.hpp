// The points where a fault changes what a simulated node does (issue 29: misbehaviour is a
// layer). A fault's declaration (fault_catalog.hpp) names a function for each point it uses;
// SimNode calls the hooks of the faults that are on, in catalogue order, each with its value.
// The protocol core (openlcb/, memory/) offers typed hand-over points and knows no fault.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "memory/memory_config_codec.hpp"
#include "memory/memory_config_server.hpp"
#include "memory/snip.hpp"
#include "openlcb/node_stack.hpp"
#include "simnode/faults.hpp"

namespace olcb::simnode {

/// A memory-configuration request on its way to the server, decoded once.
struct RequestTurn {
    memory::DecodeResult& asked;  ///< a hook may change the request the server sees
    /// Set by a hook to answer in the server's place (a refusal); later hooks still see it.
    std::optional<memory::Decision> answer;
};

/// The node's answer to a request, typed: encoded once after every hook had its turn.
struct ReplyTurn {
    const memory::DecodeResult& asked;  ///< the request as the server saw it
    memory::Decision& decision;         ///< accepted or rejected; the reply, if any
};

/// When a reply datagram goes out, relative to the Datagram Received OK that announces it.
struct AnswerPlan {
    std::uint64_t index = 0;   ///< reply datagrams this node sent before this one
    bool reply_first = false;  ///< the reply goes out before the OK
    Duration delay{0};         ///< the reply is held back this long after the OK
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
    /// Building the node: what its NodeStack is configured with (its PIP, alias behaviour).
    void (*stack_config)(NodeStackConfig&, FaultValue) = nullptr;
    /// Building the node: filters on its frames and messages, its stream window.
    void (*stack)(StackHooks&, FaultValue) = nullptr;
    /// The SNIP content the node sends.
    void (*snip)(memory::Snip&, FaultValue) = nullptr;
    /// A memory-configuration request before the server sees it.
    void (*request)(RequestTurn&, FaultValue) = nullptr;
    /// The decision about a request before it is sent.
    void (*reply)(ReplyTurn&, FaultValue) = nullptr;
    /// When a reply datagram goes out.
    void (*answer)(AnswerPlan&, FaultValue) = nullptr;
};

struct FaultDecl;

/// The faults of one node that are on, with their values, in catalogue order: what SimNode
/// calls at each hook point.
class ActiveFaults {
public:
    explicit ActiveFaults(const FaultSet& faults);

    void stack_config(NodeStackConfig& config) const;
    /// Installs the faults' stack hooks on stack (which must outlive nothing it captures: the
    /// hooks own their state).
    void attach(NodeStack& stack) const;
    void snip(memory::Snip& snip) const;
    /// nullopt: the server decides; else the answer a fault gave in its place.
    std::optional<memory::Decision> request(memory::DecodeResult& asked) const;
    void reply(const memory::DecodeResult& asked, memory::Decision& decision) const;
    void answer(AnswerPlan& plan) const;

private:
    struct Active {
        const FaultDecl* decl;
        FaultValue value;
    };
    std::vector<Active> on_;
};

}  // namespace olcb::simnode
