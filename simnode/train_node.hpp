// The train of a simulated train node (TrainControlS): speed and direction, functions (stored in
// space 0xF9), the three emergency stop states, the controller, listeners and the forwarding to
// them, the reservation and the heartbeat. Sans-I/O: SimNode hands it each Traction Control
// Command and event report; it answers through the node's NodeLife, as the faults' hooks say.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "openlcb/message.hpp"
#include "openlcb/train_control.hpp"
#include "openlcb/train_search.hpp"
#include "simnode/faults/fault_hooks.hpp"

namespace olcb::simnode {

/// What makes a node a train (scenario keys train-address, train-protocol, fdi, heartbeat).
struct TrainConfig {
    /// Address and protocol; the name the search matches is the node's SNIP user name.
    train_search::TrainIdentity identity;
    /// Seconds: the idle period after which the controller is asked for a sign of life, and the
    /// deadline the request gives it; 0 = no heartbeats.
    std::uint8_t heartbeat = 0;
    std::string fdi;                 ///< the FDI XML served in 0xFA ("" = none, no FDI bit)
    std::filesystem::path fdi_file;  ///< where it was read from (for messages; may be empty)
    /// Announced with Producer Identified Valid once the node is up: the search that made a
    /// command station create it (TrainSearchS §6.2).
    std::optional<EventId> created_by;
};

/// Listeners a train keeps; an Attach beyond is refused.
inline constexpr std::size_t kMaxListeners = 16;
/// Bytes of the function space 0xF9 a train serves: F0-F68 (TrainControlS §7.1).
inline constexpr std::uint32_t kFunctionSpaceSize = train::kLastBasicFunction + 1;

/// One train's state and behaviour.
class TrainNode {
public:
    /// Sends a message; false when its destination is not known (no alias for the node ID).
    using Send = std::function<bool(Message)>;

    TrainNode(TrainConfig config, NodeId self, NodeLife& life, const ActiveFaults& faults,
              Send send);

    /// A Traction Control Command addressed to the node.
    void on_command(const Message& msg);
    /// A Producer/Consumer Event Report (the global emergency events).
    void on_event(EventId id);
    /// A power cycle: stopped, no controller, no listeners, not reserved.
    void power_up();

    /// The behaviour its faults build.
    const TrainBuild& build() const { return build_; }
    const TrainConfig& config() const { return config_; }
    train::Speed set_speed() const { return set_; }
    bool emergency_stopped() const { return estop_; }
    bool global_stop() const { return global_stop_; }
    bool global_off() const { return global_off_; }
    NodeId controller() const { return controller_; }
    struct Listener {
        NodeId node;
        std::uint8_t flags = 0;
        std::uint16_t alias = 0;  ///< when it attached itself: where forwards go without a lookup
    };
    const std::vector<Listener>& listeners() const { return listeners_; }
    /// Heartbeat Requests sent so far.
    std::uint32_t heartbeats() const { return heartbeats_; }
    /// A function's value, as Query Function answers it.
    std::uint16_t function(std::uint32_t address) const;

private:
    void operate(const Message& msg, const train::Command& command);
    void controller_config(const Message& msg, const train::Command& command);
    void listener_config(const Message& msg, const train::Command& command);
    void management(const Message& msg, const train::Command& command);
    void set_speed(train::Speed speed);
    void set_function(std::uint32_t address, std::uint16_t value);
    void forward(const train::Command& command, const NodeHandle& from);
    void forward_to(const train::Command& command, NodeHandle listener, bool retry);
    void reply(const Message& msg, const train::Command& asked, train::Reply reply);
    void send_command(NodeId to, const train::Command& command);
    void heard_from(const NodeHandle& source);
    void arm_heartbeat();
    void heartbeat_due(std::uint32_t generation);
    void heartbeat_missed(std::uint32_t generation);
    train::Speed commanded() const;

    TrainConfig config_;
    NodeId self_;
    NodeLife& life_;
    const ActiveFaults& faults_;
    Send send_;
    TrainBuild build_;
    train::Speed set_;
    bool estop_ = false;
    bool global_stop_ = false;
    bool global_off_ = false;
    NodeId controller_;
    std::uint16_t controller_alias_ = 0;  // the alias it assigned itself from (0: not known)
    std::vector<Listener> listeners_;
    std::optional<NodeHandle> reserved_by_;
    std::vector<std::pair<std::uint32_t, std::uint16_t>> other_functions_;  // beyond 0xF9's bytes
    TimePoint last_heard_{};                  // the controller's last command
    std::uint32_t heartbeat_generation_ = 0;  // a later arming cancels the timers before it
    bool awaiting_heartbeat_ = false;
    std::uint32_t heartbeats_ = 0;
};

}  // namespace olcb::simnode
