// Alias reservation, defence and release on one CAN segment (fact sheet 1.3-1.6), sans-I/O:
// fed frames and time, it queues the frames to send and reports what happened.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>

#include "base/node_id.hpp"
#include "base/timings.hpp"
#include "openlcb/alias_cache.hpp"
#include "openlcb/alias_generator.hpp"
#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"

namespace olcb {

/// Something the owner of an AliasAllocator must know about.
struct AliasEvent {
    enum class Kind : std::uint8_t {
        kPermitted,        ///< AMD sent: the node may now send Initialization Complete
        kReserved,         ///< RID sent, AMD not yet (only when auto_permit is off)
        kConflictRestart,  ///< tentative/reserved alias abandoned; reserving the next one
        kAliasLost,        ///< active alias hit by another node: AMR sent, now Inhibited
        kDuplicateNodeId,  ///< another node sent AMD, or Verified Node ID, with our node ID
    };
    Kind kind;
    std::uint16_t alias;  ///< the alias the event is about

    /// Same kind and alias.
    friend bool operator==(const AliasEvent&, const AliasEvent&) = default;
};

/// Tunables of the allocator.
struct AliasAllocatorConfig {
    /// Wait between CID4 and RID (the standard's minimum; OpenMRN uses exactly this).
    Duration reservation_wait = base::kAliasReservationWait;
    /// Send AMD right after RID; when false the owner calls permit().
    bool auto_permit = true;
    /// On a duplicate node ID (an AMD carrying our ID, or a Verified Node ID carrying it from
    /// another alias while we are Permitted): when true, send the duplicate-node-ID PCER (if
    /// Permitted) and then stay silent until start() is called again; when false only report the
    /// event.
    bool halt_on_duplicate = false;
};

/// One node's alias state machine: CID7..4, wait, RID, AMD; RID defence; AMR on conflict; AME
/// answers; alias cache of other nodes; duplicate node ID detection.
class AliasAllocator {
public:
    /// Lifecycle states; every state but kPermitted is "Inhibited" on the link.
    enum class State : std::uint8_t { kIdle, kChecking, kReserved, kPermitted, kHalted };

    /// Allocator for node; aliases come from AliasGenerator(node).
    explicit AliasAllocator(NodeId node, AliasAllocatorConfig config = {});
    /// Allocator for node whose aliases continue generator's sequence (a node that takes a new
    /// alias at every start-up instead of starting over from its first one).
    AliasAllocator(NodeId node, AliasAllocatorConfig config, AliasGenerator generator);

    /// Starts (or, after halt/release, restarts) reservation with the next generator alias.
    void start(TimePoint now);
    /// Processes one received frame.
    void on_frame(const CanFrame& frame, TimePoint now);
    /// Advances timers (sends RID/AMD once the wait has passed).
    void poll(TimePoint now);
    /// When poll() next needs to run, if anything is pending.
    std::optional<TimePoint> next_deadline() const;
    /// The CAN driver failed to send a frame: a tentative alias is abandoned (fact sheet 1.4 b).
    void on_transmit_error(TimePoint now);
    /// Sends AMD for a reserved alias (only needed when auto_permit is off).
    void permit();
    /// Gives the alias up: AMR when Permitted, then Idle.
    void release();

    /// Next frame to transmit, oldest first.
    std::optional<CanFrame> pop_frame();
    /// Next event for the owner, oldest first.
    std::optional<AliasEvent> pop_event();
    /// Frames waiting to be transmitted.
    const std::deque<CanFrame>& pending_frames() const { return outbox_; }
    /// True when pop_event() would return an event.
    bool has_events() const { return !events_.empty(); }

    /// Current state.
    State state() const { return state_; }
    /// True when the node may send OpenLCB messages.
    bool permitted() const { return state_ == State::kPermitted; }
    /// The alias held (tentative, reserved or active); 0 when none.
    std::uint16_t alias() const { return alias_; }
    /// Our node ID.
    NodeId node_id() const { return node_; }
    /// Mappings learned about other nodes (the shared cache when one is set).
    const AliasCache& cache() const { return shared_ ? *shared_ : cache_; }
    /// Looks mappings up in `cache` instead of its own, which it then stops keeping: the owner of
    /// a cache several nodes share learns it from every frame (AliasCache::learn). nullptr: its
    /// own cache again, empty. Reservation still skips only aliases of other node IDs.
    void share_cache(std::shared_ptr<const AliasCache> cache);
    /// The cache set by share_cache(), if any.
    const std::shared_ptr<const AliasCache>& shared_cache() const { return shared_; }
    /// Number of reservations begun (1 + restarts).
    std::uint32_t attempts() const { return attempts_; }
    /// The alias generator; the next reservation takes the alias after its current state's.
    const AliasGenerator& generator() const { return generator_; }

private:
    void begin_reservation(TimePoint now);
    void handle_own_alias_hit(const CanFrame& frame, bool is_cid, TimePoint now);
    void handle_control(const CanFrame& frame);
    void learn_from_message(const CanFrame& frame);
    void on_duplicate();
    void send(const CanFrame& frame) { outbox_.push_back(frame); }
    void report(AliasEvent::Kind kind);

    NodeId node_;
    AliasAllocatorConfig config_;
    AliasGenerator generator_;
    AliasCache cache_;                          // kept only without shared_
    std::shared_ptr<const AliasCache> shared_;  // kept by its owner
    State state_ = State::kIdle;
    std::uint16_t alias_ = 0;
    TimePoint deadline_{};
    std::uint32_t attempts_ = 0;
    std::deque<CanFrame> outbox_;
    std::deque<AliasEvent> events_;
};

}  // namespace olcb
