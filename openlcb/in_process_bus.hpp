// Many ports in one process forming one CAN segment, optionally with CAN bit timing.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "openlcb/asio_fwd.hpp"
#include "openlcb/bus_pacer.hpp"
#include "openlcb/can_timing.hpp"
#include "openlcb/transport.hpp"

namespace olcb {

/// An in-process CAN segment: frames one port sends reach every other port in a fixed order.
///
/// Without an io_context the owner drives it: deliver() (no timing model) or advance_to() on the
/// bus's simulated clock. With an io_context deliveries are posted to it (and, with the timing
/// model, happen when the steady clock reaches each frame's completion time). With the timing
/// model the bus is serialised like real CAN: one frame at a time; when the bus falls idle the
/// lowest ID among the ports' oldest waiting frames wins arbitration; each port sends in order
/// (the schedule is a BusPacer, the same one the TCP hub's --bitrate uses). The bus picks the
/// next frame lazily (on advance_to() or next_completion()), so frames sent at the same
/// simulated instant before that call all take part in the arbitration.
class InProcessBus {
public:
    /// Bus time: simulated (manual bus) or steady-clock time since construction (io_context bus).
    using Duration = std::chrono::nanoseconds;

    /// A bus driven by explicit deliver()/advance_to() calls; no I/O, fully deterministic.
    InProcessBus();
    /// A bus whose deliveries run as handlers on `io`.
    explicit InProcessBus(boost::asio::io_context& io);
    ~InProcessBus();
    InProcessBus(const InProcessBus&) = delete;
    InProcessBus& operator=(const InProcessBus&) = delete;

    /// Adds a port to the segment; it lives as long as the bus.
    Transport& add_endpoint(FrameHandler handler = {});

    /// Turns on the bit-timing model at `bitrate` bit/s; call before any frame is sent.
    void enable_timing(std::uint32_t bitrate = 125000);
    /// True when the bit-timing model is on.
    bool timing_enabled() const { return pacer_.has_value(); }
    /// The modelled bit rate (0 without the timing model).
    std::uint32_t bitrate() const { return pacer_ ? pacer_->bitrate() : 0; }

    /// Delivers frames whose time has come (all queued ones without the timing model), including
    /// frames handlers send meanwhile, up to `max_frames`; returns how many were delivered.
    std::size_t deliver(std::size_t max_frames = SIZE_MAX);
    /// Moves the simulated clock to `t` (never backwards), delivering every frame completed by
    /// then.
    std::size_t advance_to(Duration t, std::size_t max_frames = SIZE_MAX);
    /// Moves the simulated clock forward by `d`.
    std::size_t advance(Duration d) { return advance_to(now_ + d); }
    /// Runs the simulated clock from completion to completion until no frame is left.
    std::size_t run_until_idle(std::size_t max_frames = SIZE_MAX);

    /// Current bus time.
    Duration now() const;
    /// Completion time of the frame on the wire or next to go on it (timing model only).
    std::optional<Duration> next_completion();
    /// Accumulated time the bus carried frames (timing model only).
    Duration busy_time() const { return pacer_ ? pacer_->busy_time() : Duration{0}; }
    /// Accumulated worst-case bits put on the wire (timing model only).
    std::uint64_t bits_on_wire() const { return pacer_ ? pacer_->bits_on_wire() : 0; }
    /// Frames delivered so far (each counted once, however many ports received it).
    std::uint64_t frames_delivered() const { return frames_delivered_; }
    /// Frames sent but not yet delivered.
    std::size_t pending() const;

private:
    class Port;

    void enqueue(std::size_t sender, const CanFrame& frame);
    void fan_out(std::size_t sender, const CanFrame& frame);
    void schedule_io();
    void on_io_wakeup();

    std::vector<std::unique_ptr<Port>> ports_;
    std::deque<std::pair<std::size_t, CanFrame>> fifo_;  // untimed mode
    std::optional<BusPacer> pacer_;                      // timed mode; sources = port indices
    Duration now_{0};
    std::uint64_t frames_delivered_ = 0;
    bool delivering_ = false;

    struct Timer;  // the steady timer of the timing model on an io_context

    boost::asio::io_context* io_ = nullptr;
    std::unique_ptr<Timer> timer_;
    std::chrono::steady_clock::time_point epoch_;
    bool wakeup_posted_ = false;
    std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace olcb
