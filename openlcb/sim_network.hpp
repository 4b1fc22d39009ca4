// A deterministic simulated CAN segment: an InProcessBus on a simulated clock plus NodeStacks and
// raw endpoints, driven from deadline to deadline. For tests and in-process conformance runs.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/in_process_bus.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/transport.hpp"

namespace olcb {

/// One frame as it went over the simulated bus.
struct LoggedFrame {
    TimePoint at;    ///< simulated time of delivery
    CanFrame frame;  ///< the frame
};

/// Simulated network: every stack and endpoint is one port of the bus, frames are delivered one
/// at a time in a fixed order, and the clock jumps to the next deadline of any stack (or, with
/// bus timing, the next frame completion) when nothing is left to deliver. Same inputs, same
/// output, every run.
class SimNetwork {
public:
    /// Called with each frame another port sent and the simulated time of delivery.
    using EndpointHandler = std::function<void(const CanFrame&, TimePoint)>;

    /// A network whose clock starts at epoch (any value; the default is far from zero so code
    /// that treats TimePoint{} specially is exercised honestly).
    explicit SimNetwork(TimePoint epoch = TimePoint{} + std::chrono::hours(24 * 365));
    SimNetwork(const SimNetwork&) = delete;
    SimNetwork& operator=(const SimNetwork&) = delete;
    ~SimNetwork();

    /// Models 29-bit CAN frame times at bitrate bit/s (call before any frame is sent).
    void enable_timing(std::uint32_t bitrate = 125000) { bus_.enable_timing(bitrate); }
    /// The modelled bit rate (0 without the timing model: frames arrive at once).
    std::uint32_t bitrate() const { return bus_.bitrate(); }
    /// Attaches stack as a new port (not started: call start_all() or stack.start(now())). The
    /// stack must stay alive while the network runs; its output handler is taken over (and
    /// becomes a no-op once the network is destroyed).
    void add_stack(NodeStack& stack);
    /// Adds a raw port (frame injection with send(), observation through handler).
    Transport& add_endpoint(EndpointHandler handler = {});
    /// Starts every attached stack at now().
    void start_all();

    /// Runs until pred() holds (checked after every delivered frame and every clock step) or the
    /// clock has advanced by max; returns whether pred() held. The clock never passes now()+max.
    bool run_until(const std::function<bool()>& pred, Duration max);
    /// Runs for exactly d of simulated time.
    void run_for(Duration d) { run_until({}, d); }
    /// Current simulated time.
    TimePoint now() const { return epoch_ + bus_.now(); }
    /// The underlying bus (timing statistics).
    InProcessBus& bus() { return bus_; }

    /// Every delivered frame so far (bounded by max_log; older entries are kept, newer dropped).
    const std::vector<LoggedFrame>& log() const { return log_; }
    /// The log as GridConnect text, one frame per entry.
    std::vector<std::string> log_text() const;
    /// The log entries from index first on as GridConnect text.
    std::vector<std::string> log_text(std::size_t first) const;
    /// Empties the log.
    void clear_log() { log_.clear(); }
    /// Turns logging on or off (on by default).
    void set_logging(bool on) { logging_ = on; }
    /// Largest number of logged frames kept.
    void set_max_log(std::size_t n) { max_log_ = n; }

    /// Upper bound on loop iterations of one run_until() (guards against endless same-instant
    /// ping-pong between endpoints); hitting it makes run_until() return false.
    void set_max_steps(std::uint64_t n) { max_steps_ = n; }
    /// True when the last run_until() stopped because of the step bound.
    bool step_limit_hit() const { return step_limit_hit_; }

private:
    struct StackPort {
        NodeStack* stack;
        Transport* port;
        bool dirty = false;
    };

    void pump(std::size_t index);
    void pump_dirty();
    void poll_due();
    std::optional<TimePoint> earliest_deadline() const;
    std::optional<TimePoint> next_event();

    TimePoint epoch_;
    InProcessBus bus_;
    std::vector<StackPort> stacks_;
    std::vector<std::size_t> dirty_;
    std::vector<LoggedFrame> log_;
    bool logging_ = true;
    std::size_t max_log_ = 1'000'000;
    std::uint64_t max_steps_ = 100'000'000;
    bool step_limit_hit_ = false;
    std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace olcb
