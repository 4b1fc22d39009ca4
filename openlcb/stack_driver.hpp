// Runs NodeStacks on real time: frames between a Transport and the stacks, one steady_timer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>

#include "openlcb/asio.hpp"
#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/stack_group.hpp"
#include "openlcb/transport.hpp"

namespace olcb {

/// Attaches NodeStacks to one Transport (in-process bus port, hub local endpoint, TCP client,
/// SocketCAN) on an io_context. The attached stacks share the transport's segment: frames from
/// the transport go to the stacks, a frame a stack emits goes to the transport and to the other
/// attached stacks (transports never echo); a StackGroup decides which stacks a frame concerns
/// and keeps the deadlines. One steady_timer is armed at the earliest deadline of all stacks,
/// re-armed once per batch of work (posted, coalesced), not once per frame.
class StackDriver {
public:
    /// Counters since construction.
    struct Stats {
        std::uint64_t frames_in = 0;   ///< frames received from the transport
        std::uint64_t frames_out = 0;  ///< frames the stacks emitted (sent to the transport)
        std::uint64_t polls = 0;       ///< NodeStack::poll() calls made on timer expiry
        std::uint64_t timer_arms = 0;  ///< times the timer was (re)armed
        std::uint64_t deliveries = 0;  ///< NodeStack::on_frame() calls made
    };

    /// A driver on io using transport (its frame handler is taken over); the transport must
    /// outlive the driver. options: StackGroupOptions (simnode's stacks share one alias cache).
    StackDriver(boost::asio::io_context& io, Transport& transport, StackGroupOptions options = {});
    /// Clears the transport handler; stacks still attached become undriven (their output
    /// handlers turn into no-ops), whether they are destroyed before or after the driver.
    ~StackDriver();
    StackDriver(const StackDriver&) = delete;
    StackDriver& operator=(const StackDriver&) = delete;

    /// Attaches stack (it must stay alive while the driver runs, or be detached first); its
    /// output handler is taken over. Start it with stack.start(Clock::now()) or start_all().
    void attach(NodeStack& stack);
    /// Detaches stack; its pending output stays in it.
    void detach(NodeStack& stack);
    /// Starts every attached stack now.
    void start_all();
    /// Flushes output and re-arms the timer soon; owners never need it (stacks notify the
    /// driver of new output), but it is harmless.
    void kick();
    /// Delivers every stack's pending output now (to the transport and the other stacks), so an
    /// owner can detach a stack right after its last frame (an AMR) went; no effect inside a
    /// driver callback, where the running batch delivers it.
    void flush();
    /// Number of attached stacks.
    std::size_t size() const { return group_.size(); }
    /// Counters.
    Stats stats() const;
    /// The stacks and what routes frames to them.
    const StackGroup& group() const { return group_; }
    /// The io_context it runs on (owners post work there that may not run inside its callbacks,
    /// e.g. attaching a stack).
    boost::asio::io_context& io() { return io_; }

private:
    void on_transport_frame(const CanFrame& frame);
    void process();
    void post_once(bool& pending, void (StackDriver::*step)());
    void post_rearm();
    void schedule();
    void rearm();
    void on_timer();

    boost::asio::io_context& io_;
    Transport& transport_;
    boost::asio::steady_timer timer_;
    std::optional<TimePoint> armed_at_;
    StackGroup group_;
    std::deque<CanFrame> incoming_;
    bool busy_ = false;
    bool posted_ = false;
    bool rearm_posted_ = false;
    Stats stats_;
    std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace olcb
