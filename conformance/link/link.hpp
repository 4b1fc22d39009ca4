// Where the runner's own node lives: a NodeStack on a simulated or real CAN segment, plus a tap
// that sees every frame and can put raw frames on the segment (for the frame-level checks).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "openlcb/can_frame.hpp"
#include "openlcb/can_timing.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/node_id.hpp"
#include "openlcb/node_stack.hpp"

namespace olcb {
class SimNetwork;
}

namespace olcb::conform {

/// Called with every frame seen on the segment (received, sent by our stack, or injected).
using FrameObserver = std::function<void(const CanFrame&, TimePoint)>;

/// The runner's node on one segment; the factories start its stack.
class Link {
public:
    virtual ~Link() = default;
    /// The runner's NodeStack (own node ID and alias).
    virtual NodeStack& stack() = 0;
    /// Current time of the segment (simulated or steady clock).
    virtual TimePoint now() = 0;
    /// Drives the network (simulated clock, or the io_context in real time) until pred() is true or
    /// `max` elapses; returns pred()'s final value. Every wait of the runner goes through this.
    virtual bool run_until(const std::function<bool()>& pred, Duration max) = 0;
    /// Puts a raw frame on the segment; our own stack does not see it (as with a real transport).
    virtual void send_frame(const CanFrame& frame) = 0;
    /// Sets the observer of every frame (replaces any previous one).
    virtual void set_frame_observer(FrameObserver observer) = 0;

    /// The bit rate of the segment behind the link: answer and silence windows start once our
    /// frames could be through it (0: frames arrive at once, as on an unpaced simulation). A
    /// real segment (a hub, an adapter, SocketCAN) may be a 125 kbit/s CAN bus.
    virtual std::uint32_t bus_bitrate() { return kLccBitrate; }
    /// True while the transport under the link works (adapter present, hub connected).
    virtual bool up() { return true; }
    /// Times the transport went away since the link was opened.
    virtual std::uint64_t losses() { return 0; }
    /// Why the transport last went away ("" when it never did).
    virtual std::string loss_reason() { return {}; }
};

/// In-process link on a simulated network (tests); the stack starts at network.now(). On an
/// unpaced network it reports `assumed_bitrate` as its bus speed (0: none), as a TCP link does
/// for a bus it cannot see.
std::unique_ptr<Link> make_sim_link(SimNetwork& network, NodeId tool_id,
                                    std::uint32_t assumed_bitrate = 0);
/// GridConnect TCP link to a hub; nullptr with `error` set when the connection fails (2 s).
std::unique_ptr<Link> connect_tcp(const std::string& host, std::uint16_t port, NodeId tool_id,
                                  std::string& error);
/// Serial line settings of open_serial.
struct SerialSettings {
    unsigned baud = 115200;  ///< bits per second
    bool rtscts = false;     ///< hardware flow control
};
/// GridConnect link through a USB/serial CAN adapter at `device`; nullptr with `error` set when
/// it cannot be opened. A lost adapter is reopened in the background (see Link::up()).
std::unique_ptr<Link> open_serial(const std::string& device, SerialSettings settings,
                                  NodeId tool_id, std::string& error);
/// SocketCAN link on `interface`; nullptr with `error` set when it cannot be opened.
std::unique_ptr<Link> open_socketcan(const std::string& interface, NodeId tool_id,
                                     std::string& error);

/// The NodeStack configuration the runner's node uses (datagram resends, acks).
NodeStackConfig tool_stack_config(NodeId tool_id);

}  // namespace olcb::conform
