// One CAN bus as a schedule (sans-I/O): frames queued by their senders go on the wire one at a
// time at CAN bit timing and come off it when their transmission completes.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>

#include "openlcb/can_frame.hpp"
#include "openlcb/can_timing.hpp"

namespace olcb {

/// The arbitration and timing of one shared CAN bus, fed (frame, now) and asked what completed.
///
/// Each sender (an opaque Source key) sends its frames in order. When the bus falls idle the
/// lowest ID among the senders' oldest frames that were waiting by then wins arbitration (equal
/// IDs: the lower Source key); a frame occupies the bus for can_frame_time(len, bitrate) and
/// completes at its start plus that. The next frame is chosen lazily (by next_completion() or
/// pop()), so frames pushed at the same instant before that call all take part in the
/// arbitration. The schedule is kept on the bus's own clock: a caller that looks late gets what
/// completed meanwhile, and the bus time lost to its lateness is not added to later frames, up to
/// kMaxCatchUp: a caller stalled longer (a program building 1,000 nodes before its event loop
/// runs) would otherwise get every frame of the stall at once, a burst no bus carries, so the
/// bus time beyond it is lost and the waiting frames follow at the bit rate.
class BusPacer {
public:
    /// Bus time: any monotonic clock the caller uses for every call (simulated or steady).
    using Duration = std::chrono::nanoseconds;
    /// Who sent a frame (a port index, a client number); only compared.
    using Source = std::uint64_t;

    /// A frame whose transmission completed.
    struct Done {
        CanFrame frame;
        Source source = 0;
        Duration completed_at{0};
    };

    /// Most bus time a late caller's pop() makes up for (timer wake-ups late by a few ms lose
    /// nothing; a stall of seconds is not replayed as one burst).
    static constexpr Duration kMaxCatchUp = std::chrono::milliseconds(20);

    /// A bus at `bitrate` bit/s (0 is taken as 1).
    explicit BusPacer(std::uint32_t bitrate);

    /// The bit rate.
    std::uint32_t bitrate() const { return bitrate_; }
    /// Queues `frame` from `source`, ready to go on the wire at `now`.
    void push(Source source, const CanFrame& frame, Duration now);
    /// Completion time of the frame on the wire or next to go on it; nullopt when none waits.
    std::optional<Duration> next_completion();
    /// The frame on the wire if it completed by `now` (the bus is then free for the next). No
    /// frame starts before now - kMaxCatchUp.
    std::optional<Done> pop(Duration now);

    /// Frames of `source` waiting for the bus (not counting one on the wire).
    std::size_t queued(Source source) const;
    /// Frames pushed and not yet popped, the one on the wire included.
    std::size_t pending() const { return queued_ + (on_wire_ ? 1 : 0); }
    /// Accumulated time the bus carried frames (counted when a frame goes on the wire).
    Duration busy_time() const { return busy_time_; }
    /// Accumulated worst-case bits put on the wire.
    std::uint64_t bits_on_wire() const { return bits_on_wire_; }

private:
    struct Waiting {
        CanFrame frame;
        Duration ready_at;
    };

    bool start_next_frame();

    // Ordered by key, so arbitration ties go to the lower key; a sender's entry exists only
    // while it has frames waiting, so a bus of 1,000 quiet ports looks at the few busy ones.
    std::map<Source, std::deque<Waiting>> queues_;
    std::optional<Done> on_wire_;
    std::uint32_t bitrate_;
    std::size_t queued_ = 0;
    Duration free_at_{0};
    Duration busy_time_{0};
    std::uint64_t bits_on_wire_ = 0;
};

}  // namespace olcb
