// Which of many stacks on one CAN segment a frame can concern, found through indexes instead of
// asking every stack (issue 32): delivering each frame of a login burst to every one of N stacks
// made N nodes start in time N^2.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "base/node_id.hpp"
#include "openlcb/alias_cache.hpp"
#include "openlcb/can_frame.hpp"
#include "openlcb/node_stack.hpp"

namespace olcb {

/// The stacks of one interface (slots, as StackGroup numbers them) and, for each frame, the
/// stacks NodeStack::on_frame() would do anything with; the others may skip it. A frame
/// reaches the stacks that:
/// - have an inbound filter (it may act on any frame);
/// - hold the frame's source alias (a conflict, or a CID to defend against);
/// - are its destination (addressed message, datagram, stream data: by alias);
/// - carry the node ID it carries (AMD, Verified Node ID, AME for one node: duplicates, answers);
/// - take its global message (NodeStack::takes_global()), or, for Verify Node ID Global and
///   every AME, all of them (each answers, or notes when the AME came);
/// - wait for datagram acknowledgements, for AMD and Initialization Complete (a node that
///   re-initialized will not acknowledge);
/// - keep their own alias cache, for the frames that change it (without a shared cache).
/// With a shared cache the routes keep it: every frame routed is learned first.
///
/// What routes a frame to a stack can change in any call into it; refresh() the stack after each
/// (its alias, filter and datagrams; an old alias stays indexed until then).
class StackRoutes {
public:
    /// No sender: a frame from outside the interface.
    static constexpr std::size_t kNoSender = SIZE_MAX;

    /// Routes whose stacks keep their own alias caches, or share one the routes keep.
    explicit StackRoutes(bool share_alias_cache);
    ~StackRoutes();
    StackRoutes(const StackRoutes&) = delete;
    StackRoutes& operator=(const StackRoutes&) = delete;

    /// Takes stack into the next slot (and hands it the shared cache); returns the slot.
    std::size_t add(NodeStack& stack);
    /// Forgets the stack of slot (it gets a cache of its own again); the slot stays empty.
    void remove(std::size_t slot);
    /// Re-reads what routes frames to the stack of slot; no effect on an empty slot.
    void refresh(std::size_t slot);
    /// The stack of slot; nullptr once removed.
    NodeStack* stack(std::size_t slot) const { return entries_[slot].stack; }
    /// Slots handed out so far, empty ones included.
    std::size_t slots() const { return entries_.size(); }

    /// Learns the frame into the shared cache, then returns the slots it must reach, ascending,
    /// never `sender`'s; valid until the next call.
    const std::vector<std::size_t>& route(const CanFrame& frame, std::size_t sender = kNoSender);
    /// The cache the stacks share (nullptr when each keeps its own).
    const AliasCache* shared_cache() const { return shared_.get(); }

private:
    using Slots = std::vector<std::size_t>;
    struct Entry {
        NodeStack* stack = nullptr;
        std::uint16_t alias = 0;
        bool filtered = false;
        bool sending = false;
        bool all_globals = false;
        std::vector<std::uint16_t> globals;
    };

    void index(std::size_t slot, Entry& e, bool on);
    void index_globals(std::size_t slot, const Entry& e, bool on);
    void route_control(const CanFrame& frame);
    void route_message(const CanFrame& frame);
    void route_global(const CanFrame& frame);
    void add_carried(const CanFrame& frame);
    void add(const Slots& slots) { hits_.insert(hits_.end(), slots.begin(), slots.end()); }

    std::shared_ptr<AliasCache> shared_;
    std::vector<Entry> entries_;
    std::size_t live_ = 0;
    std::array<Slots, 4096> by_alias_;                  // by the alias each stack holds
    std::unordered_map<NodeId, Slots> by_node_;         // by node ID
    std::unordered_map<std::uint16_t, Slots> globals_;  // by CAN-MTI taken
    Slots all_globals_;                                 // stacks taking every global message
    Slots filtered_;                                    // stacks with an inbound filter
    Slots sending_;   // stacks waiting for datagram acknowledgements
    Slots learners_;  // stacks keeping their own cache (all of them without a shared one)
    Slots hits_;
    bool everyone_ = false;
};

}  // namespace olcb
