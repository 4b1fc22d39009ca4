#include "simnode/train_node.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include "base/error_codes.hpp"
#include "simnode/node_memory.hpp"

namespace olcb::simnode {
namespace {

// Other function numbers a train remembers (those past 0xF9's bytes); more are not stored.
constexpr std::size_t kMaxOtherFunctions = 64;
// A forward to a listener whose alias is not known yet is tried once more after this.
constexpr auto kForwardRetry = std::chrono::milliseconds(300);

// The alias node ID `named` is on when the message naming it came from it: its source is that
// node, or a node the stack's alias cache does not know (a global AME emptied it), which on a
// bus of throttles naming themselves is the same; 0 otherwise.
std::uint16_t alias_if_self(const Message& msg, NodeId named) {
    return msg.source.id == named || msg.source.id.is_zero() ? msg.source.alias : 0;
}

bool same_node(const NodeHandle& a, const NodeHandle& b) {
    if (!a.id.is_zero() && !b.id.is_zero()) return a.id == b.id;
    return a.alias != 0 && a.alias == b.alias;
}

Message oir(const Message& msg, base::ErrorCode code) {
    Message m;
    m.mti = Mti::kOptionalInteractionRejected;
    m.destination = msg.source;
    const auto c = base::to_u16(code);
    const auto mti = to_u16(msg.mti);
    m.payload = {static_cast<std::uint8_t>(c >> 8), static_cast<std::uint8_t>(c & 0xFF),
                 static_cast<std::uint8_t>(mti >> 8), static_cast<std::uint8_t>(mti & 0xFF)};
    return m;
}

}  // namespace

TrainNode::TrainNode(TrainConfig config, NodeId self, NodeLife& life, const ActiveFaults& faults,
                     Send send)
    : config_(std::move(config)),
      self_(self),
      life_(life),
      faults_(faults),
      send_(std::move(send)),
      build_(faults.train()) {}

void TrainNode::power_up() {
    set_ = train::Speed{};
    estop_ = global_stop_ = global_off_ = false;
    controller_ = NodeId{};
    controller_alias_ = 0;
    listeners_.clear();
    reserved_by_.reset();
    ++heartbeat_generation_;
    awaiting_heartbeat_ = false;
}

void TrainNode::on_command(const Message& msg) {
    const auto decoded = train::decode_command(msg.payload);
    if (!decoded.ok()) {
        send_(oir(msg, base::ErrorCode::kInvalidArguments));
        return;
    }
    const train::Command& command = *decoded.value;
    heard_from(msg.source);
    if (std::holds_alternative<train::AssignController>(command.body) ||
        std::holds_alternative<train::ReleaseController>(command.body) ||
        std::holds_alternative<train::QueryController>(command.body) ||
        std::holds_alternative<train::ControllerChangingNotify>(command.body)) {
        controller_config(msg, command);
    } else if (std::holds_alternative<train::AttachListener>(command.body) ||
               std::holds_alternative<train::DetachListener>(command.body) ||
               std::holds_alternative<train::QueryListeners>(command.body)) {
        listener_config(msg, command);
    } else if (std::holds_alternative<train::Reserve>(command.body) ||
               std::holds_alternative<train::Release>(command.body) ||
               std::holds_alternative<train::Noop>(command.body)) {
        management(msg, command);
    } else {
        operate(msg, command);
    }
}

void TrainNode::operate(const Message& msg, const train::Command& command) {
    if (const auto* s = std::get_if<train::SetSpeed>(&command.body)) {
        estop_ = false;  // any Set Speed leaves the Emergency Stop state (§5)
        set_speed(s->speed);
        forward(command, msg.source);
    } else if (const auto* f = std::get_if<train::SetFunction>(&command.body)) {
        set_function(f->address, f->value);
        forward(command, msg.source);
    } else if (std::holds_alternative<train::EmergencyStop>(command.body)) {
        estop_ = true;
        set_speed(set_.stopped());
        forward(command, msg.source);
    } else if (std::holds_alternative<train::QuerySpeeds>(command.body)) {
        const std::uint8_t status = estop_ ? train::kStatusEmergencyStop : 0;
        reply(msg, command, train::SpeedsReply{set_, status, commanded(), train::Speed::unknown()});
    } else if (const auto* q = std::get_if<train::QueryFunction>(&command.body)) {
        reply(msg, command, train::FunctionReply{q->address, function(q->address)});
    }
}

void TrainNode::controller_config(const Message& msg, const train::Command& command) {
    if (const auto* a = std::get_if<train::AssignController>(&command.body)) {
        const NodeId previous = controller_;
        if (!previous.is_zero() && previous != a->controller) {
            // The previous controller is told; this train does not wait for its answer (§6.1).
            send_command(previous, {train::ControllerChangingNotify{0, a->controller}});
        }
        controller_ = a->controller;
        controller_alias_ = alias_if_self(msg, a->controller);
        last_heard_ = life_.now();
        reply(msg, command, train::AssignReply{train::assign_result::kOk});
        arm_heartbeat();
    } else if (const auto* r = std::get_if<train::ReleaseController>(&command.body)) {
        // Only the controller itself releases the train (§6.1); no reply is defined.
        if (r->controller == controller_) {
            controller_ = NodeId{};
            controller_alias_ = 0;
        }
        arm_heartbeat();
    } else if (std::holds_alternative<train::QueryController>(command.body)) {
        reply(msg, command, train::ControllerReply{0, controller_});
    }
    // A Controller Changing Notify is for throttles: a train has nothing to say to it.
}

void TrainNode::listener_config(const Message& msg, const train::Command& command) {
    if (const auto* a = std::get_if<train::AttachListener>(&command.body)) {
        std::uint16_t code = 0;
        const auto it = std::find_if(listeners_.begin(), listeners_.end(),
                                     [&](const Listener& l) { return l.node == a->listener; });
        if (a->listener == self_ || a->listener.is_zero()) {
            code = train::error::kAlreadyExists;
        } else if (it != listeners_.end()) {
            it->flags = a->flags;  // an update keeps the listener's place (§5)
        } else if (listeners_.size() >= kMaxListeners) {
            code = base::to_u16(base::ErrorCode::kPermanent);
        } else {
            listeners_.push_back({a->listener, a->flags, alias_if_self(msg, a->listener)});
        }
        reply(msg, command,
              train::ListenerChangeReply{train::ListenerOp::kAttach, a->listener, code});
    } else if (const auto* d = std::get_if<train::DetachListener>(&command.body)) {
        const auto n =
            std::erase_if(listeners_, [&](const Listener& l) { return l.node == d->listener; });
        reply(msg, command,
              train::ListenerChangeReply{train::ListenerOp::kDetach, d->listener,
                                         n > 0 ? std::uint16_t{0} : train::error::kNotFound});
    } else if (const auto* q = std::get_if<train::QueryListeners>(&command.body)) {
        train::ListenersReply r{static_cast<std::uint8_t>(listeners_.size()), std::nullopt};
        if (q->index && *q->index < listeners_.size()) {
            const Listener& l = listeners_[*q->index];
            r.entry = train::ListenerEntry{*q->index, l.flags, l.node};
        }
        reply(msg, command, r);
    }
}

void TrainNode::management(const Message& msg, const train::Command& command) {
    if (std::holds_alternative<train::Reserve>(command.body)) {
        std::uint8_t result = 0;
        if (reserved_by_) {
            const bool holder = same_node(*reserved_by_, msg.source);
            result = holder && !build_.reserve_exclusive ? 0 : 1;
        } else {
            reserved_by_ = msg.source;
        }
        reply(msg, command, train::ReserveReply{result});
    } else if (std::holds_alternative<train::Release>(command.body)) {
        if (reserved_by_ && same_node(*reserved_by_, msg.source)) reserved_by_.reset();
    }
    // No-op: heard_from() already took it as the controller's sign of life.
}

void TrainNode::on_event(EventId id) {
    if (id == train::kEmergencyStopAll) global_stop_ = true;
    if (id == train::kClearEmergencyStopAll) global_stop_ = false;
    if (id == train::kEmergencyOffAll) global_off_ = true;
    if (id == train::kClearEmergencyOffAll) global_off_ = false;
}

train::Speed TrainNode::commanded() const {
    return estop_ || global_stop_ || global_off_ ? set_.stopped() : set_;
}

void TrainNode::set_speed(train::Speed speed) {
    set_ = speed;
    arm_heartbeat();
}

void TrainNode::set_function(std::uint32_t address, std::uint16_t value) {
    if (address < kFunctionSpaceSize) {
        // The space holds one byte per function; larger values are not specified (TN §2.7.1).
        const std::array<std::uint8_t, 1> b{
            static_cast<std::uint8_t>(std::min<unsigned>(value, 255))};
        if (auto* space = life_.memory().space(train::kFunctionSpace)) space->write(address, b);
        return;
    }
    for (auto& [a, v] : other_functions_) {
        if (a == address) {
            v = value;
            return;
        }
    }
    if (other_functions_.size() < kMaxOtherFunctions) other_functions_.emplace_back(address, value);
}

std::uint16_t TrainNode::function(std::uint32_t address) const {
    if (address < kFunctionSpaceSize) {
        const auto b = life_.memory().read(train::kFunctionSpace, address, 1);
        return b.empty() ? 0 : b[0];
    }
    for (const auto& [a, v] : other_functions_)
        if (a == address) return v;
    return 0;
}

void TrainNode::forward(const train::Command& command, const NodeHandle& from) {
    for (const Listener& l : listeners_) {
        // Never back to where it came from (§6.5): that would loop.
        if (same_node(NodeHandle{l.node, l.alias}, from)) continue;
        train::Command out = command;
        out.forwarded = true;
        if (auto* s = std::get_if<train::SetSpeed>(&out.body)) {
            if ((l.flags & train::listener_flags::kReverse) != 0) s->speed = s->speed.flipped();
        } else if (const auto* f = std::get_if<train::SetFunction>(&out.body)) {
            const std::uint8_t link =
                f->address == 0 ? train::listener_flags::kLinkF0 : train::listener_flags::kLinkFn;
            if ((l.flags & link) == 0) continue;
        }
        TrainForwardTurn turn{out, l.node};
        faults_.train_forward(turn);
        if (!turn.drop) forward_to(out, NodeHandle{l.node, l.alias}, true);
    }
}

void TrainNode::forward_to(const train::Command& command, NodeHandle listener, bool retry) {
    Message m;
    m.mti = Mti::kTractionControlCommand;
    m.destination = listener;
    m.payload = train::encode(command);
    if (send_(m) || !retry) return;
    // Not known yet: ask who it is, then try once more (a real train looks the alias up too).
    Message verify;
    verify.mti = Mti::kVerifyNodeIdGlobal;
    const auto raw = listener.id.to_bytes();
    verify.payload.assign(raw.begin(), raw.end());
    send_(std::move(verify));
    life_.schedule(life_.now() + kForwardRetry, [this, command, id = listener.id](TimePoint) {
        forward_to(command, NodeHandle{id, 0}, false);
    });
}

void TrainNode::send_command(NodeId to, const train::Command& command) {
    Message m;
    m.mti = Mti::kTractionControlCommand;
    m.destination = NodeHandle{to, 0};
    m.payload = train::encode(command);
    send_(std::move(m));
}

void TrainNode::reply(const Message& msg, const train::Command& asked, train::Reply r) {
    TrainReplyTurn turn{asked, r};
    faults_.train_reply(turn);
    Message m;
    m.mti = Mti::kTractionControlReply;
    m.destination = msg.source;
    m.payload = train::encode(r);
    send_(std::move(m));
}

void TrainNode::heard_from(const NodeHandle& source) {
    if (controller_.is_zero() || !same_node(NodeHandle{controller_, controller_alias_}, source))
        return;
    last_heard_ = life_.now();
    arm_heartbeat();
}

void TrainNode::arm_heartbeat() {
    const std::uint32_t generation = ++heartbeat_generation_;
    awaiting_heartbeat_ = false;
    // No request while stopped (E-Stop included: it zeroes the Set Speed) or without a
    // controller (§6.6).
    if (config_.heartbeat == 0 || controller_.is_zero() || set_.is_zero()) return;
    const auto period = std::chrono::seconds(config_.heartbeat);
    life_.schedule(last_heard_ + period,
                   [this, generation](TimePoint) { heartbeat_due(generation); });
}

void TrainNode::heartbeat_due(std::uint32_t generation) {
    if (generation != heartbeat_generation_ || !life_.initialized()) return;
    awaiting_heartbeat_ = true;
    ++heartbeats_;
    Message m;
    m.mti = Mti::kTractionControlReply;
    m.destination = NodeHandle{controller_, controller_alias_};
    m.payload = train::encode(train::Reply{train::HeartbeatRequest{config_.heartbeat}});
    send_(std::move(m));
    life_.schedule(life_.now() + std::chrono::seconds(config_.heartbeat),
                   [this, generation](TimePoint) { heartbeat_missed(generation); });
}

void TrainNode::heartbeat_missed(std::uint32_t generation) {
    if (generation != heartbeat_generation_ || !awaiting_heartbeat_) return;
    if (!build_.heartbeat_stops) {
        // The fault: the train keeps running and asks again after another period.
        last_heard_ = life_.now();
        arm_heartbeat();
        return;
    }
    // Taken as a Set Speed 0, forwarded to every listener, the controller included (§6.6).
    const train::Command stop{train::SetSpeed{set_.stopped()}};
    set_speed(set_.stopped());
    forward(stop, NodeHandle{self_, 0});
}

}  // namespace olcb::simnode
