#include "openlcb/train_control.hpp"

#include <cmath>
#include <cstdio>
#include <type_traits>

#include "base/half_float.hpp"
#include "base/hex.hpp"

namespace olcb::train {
namespace {

using Bytes = std::vector<std::uint8_t>;

std::uint8_t u8(unsigned v) {
    return static_cast<std::uint8_t>(v & 0xFF);
}

void put16(Bytes& out, std::uint16_t v) {
    out.push_back(u8(v >> 8U));
    out.push_back(u8(v));
}

void put24(Bytes& out, std::uint32_t v) {
    out.push_back(u8(v >> 16U));
    out.push_back(u8(v >> 8U));
    out.push_back(u8(v));
}

void put_node(Bytes& out, NodeId id) {
    const auto raw = id.to_bytes();
    out.insert(out.end(), raw.begin(), raw.end());
}

std::uint16_t get16(std::span<const std::uint8_t> p, std::size_t at) {
    return static_cast<std::uint16_t>(p[at] << 8U | p[at + 1]);
}

std::uint32_t get24(std::span<const std::uint8_t> p, std::size_t at) {
    return static_cast<std::uint32_t>(p[at]) << 16U | static_cast<std::uint32_t>(p[at + 1]) << 8U |
           p[at + 2];
}

NodeId get_node(std::span<const std::uint8_t> p, std::size_t at) {
    return NodeId::from_bytes(p.subspan(at, NodeId::kSize)).value_or(NodeId{});
}

std::uint8_t byte_of(Instruction i) {
    return static_cast<std::uint8_t>(i);
}

template <typename E>
std::uint8_t op(E e) {
    return static_cast<std::uint8_t>(e);
}

// A node change request: instruction, sub-command, flags, node ID.
Bytes node_request(Instruction i, std::uint8_t sub, std::uint8_t flags, NodeId id) {
    Bytes out{byte_of(i), sub, flags};
    put_node(out, id);
    return out;
}

struct CommandEncoder {
    Bytes operator()(const SetSpeed& c) const {
        Bytes out{byte_of(Instruction::kSetSpeed)};
        put16(out, c.speed.bits());
        return out;
    }
    Bytes operator()(const SetFunction& c) const {
        Bytes out{byte_of(Instruction::kSetFunction)};
        put24(out, c.address);
        put16(out, c.value);
        return out;
    }
    Bytes operator()(const EmergencyStop&) const { return {byte_of(Instruction::kEmergencyStop)}; }
    Bytes operator()(const QuerySpeeds&) const { return {byte_of(Instruction::kQuerySpeeds)}; }
    Bytes operator()(const QueryFunction& c) const {
        Bytes out{byte_of(Instruction::kQueryFunction)};
        put24(out, c.address);
        return out;
    }
    Bytes operator()(const AssignController& c) const {
        return node_request(Instruction::kController, op(ControllerOp::kAssign), c.flags,
                            c.controller);
    }
    Bytes operator()(const ReleaseController& c) const {
        return node_request(Instruction::kController, op(ControllerOp::kRelease), c.flags,
                            c.controller);
    }
    Bytes operator()(const QueryController&) const {
        return {byte_of(Instruction::kController), op(ControllerOp::kQuery)};
    }
    Bytes operator()(const ControllerChangingNotify& c) const {
        return node_request(Instruction::kController, op(ControllerOp::kChangingNotify), c.flags,
                            c.new_controller);
    }
    Bytes operator()(const AttachListener& c) const {
        return node_request(Instruction::kListener, op(ListenerOp::kAttach), c.flags, c.listener);
    }
    Bytes operator()(const DetachListener& c) const {
        return node_request(Instruction::kListener, op(ListenerOp::kDetach), c.flags, c.listener);
    }
    Bytes operator()(const QueryListeners& c) const {
        Bytes out{byte_of(Instruction::kListener), op(ListenerOp::kQuery)};
        if (c.index) out.push_back(*c.index);
        return out;
    }
    Bytes operator()(const Reserve&) const {
        return {byte_of(Instruction::kManagement), op(ManagementOp::kReserve)};
    }
    Bytes operator()(const Release&) const {
        return {byte_of(Instruction::kManagement), op(ManagementOp::kRelease)};
    }
    Bytes operator()(const Noop&) const {
        return {byte_of(Instruction::kManagement), op(ManagementOp::kNoop)};
    }
};

struct ReplyEncoder {
    Bytes operator()(const SpeedsReply& r) const {
        Bytes out{byte_of(Instruction::kQuerySpeeds)};
        put16(out, r.set.bits());
        out.push_back(r.status);
        put16(out, r.commanded.bits());
        put16(out, r.actual.bits());
        return out;
    }
    Bytes operator()(const FunctionReply& r) const {
        Bytes out{byte_of(Instruction::kQueryFunction)};
        put24(out, r.address);
        put16(out, r.value);
        return out;
    }
    Bytes operator()(const AssignReply& r) const {
        return {byte_of(Instruction::kController), op(ControllerOp::kAssign), r.result};
    }
    Bytes operator()(const ControllerReply& r) const {
        return node_request(Instruction::kController, op(ControllerOp::kQuery), r.flags,
                            r.controller);
    }
    Bytes operator()(const ChangingNotifyReply& r) const {
        return {byte_of(Instruction::kController), op(ControllerOp::kChangingNotify), r.result};
    }
    Bytes operator()(const ListenerChangeReply& r) const {
        Bytes out{byte_of(Instruction::kListener), op(r.op)};
        put_node(out, r.listener);
        put16(out, r.code);
        return out;
    }
    Bytes operator()(const ListenersReply& r) const {
        Bytes out{byte_of(Instruction::kListener), op(ListenerOp::kQuery), r.count};
        if (r.entry) {
            out.push_back(r.entry->index);
            out.push_back(r.entry->flags);
            put_node(out, r.entry->node);
        }
        return out;
    }
    Bytes operator()(const ReserveReply& r) const {
        return {byte_of(Instruction::kManagement), op(ManagementOp::kReserve), r.result};
    }
    Bytes operator()(const HeartbeatRequest& r) const {
        return {byte_of(Instruction::kManagement), op(ManagementOp::kHeartbeatRequest), r.timeout};
    }
};

template <typename T>
Decoded<T> fail(std::string why) {
    return {std::nullopt, std::move(why)};
}

template <typename T, typename V>
Decoded<T> ok(V value) {
    return {T{std::move(value)}, {}};
}

// "" when the payload has at least `need` bytes; else why not ("3 bytes, Set Function needs 6").
std::string too_short(std::span<const std::uint8_t> p, std::size_t need, const char* what) {
    if (p.size() >= need) return {};
    return std::to_string(p.size()) + " bytes, " + what + " needs " + std::to_string(need);
}

Decoded<Command> decode_controller(std::span<const std::uint8_t> p) {
    if (auto e = too_short(p, 2, "Controller Configuration"); !e.empty()) return fail<Command>(e);
    switch (static_cast<ControllerOp>(p[1])) {
        case ControllerOp::kQuery:
            return ok<Command>(QueryController{});
        case ControllerOp::kAssign:
        case ControllerOp::kRelease:
        case ControllerOp::kChangingNotify:
            break;
        default:
            return fail<Command>("unknown Controller Configuration sub-command " +
                                 base::hex(p[1], 2));
    }
    if (auto e = too_short(p, 9, "a Controller Configuration change"); !e.empty())
        return fail<Command>(e);
    const NodeId id = get_node(p, 3);
    if (p[1] == op(ControllerOp::kAssign)) return ok<Command>(AssignController{p[2], id});
    if (p[1] == op(ControllerOp::kRelease)) return ok<Command>(ReleaseController{p[2], id});
    return ok<Command>(ControllerChangingNotify{p[2], id});
}

Decoded<Command> decode_listener(std::span<const std::uint8_t> p) {
    if (auto e = too_short(p, 2, "Listener Configuration"); !e.empty()) return fail<Command>(e);
    switch (static_cast<ListenerOp>(p[1])) {
        case ListenerOp::kQuery:
            return ok<Command>(QueryListeners{p.size() > 2 ? std::optional(p[2]) : std::nullopt});
        case ListenerOp::kAttach:
        case ListenerOp::kDetach: {
            if (auto e = too_short(p, 9, "Attach/Detach Node"); !e.empty()) return fail<Command>(e);
            if (p[1] == op(ListenerOp::kAttach))
                return ok<Command>(AttachListener{p[2], get_node(p, 3)});
            return ok<Command>(DetachListener{p[2], get_node(p, 3)});
        }
    }
    return fail<Command>("unknown Listener Configuration sub-command " + base::hex(p[1], 2));
}

Decoded<Command> decode_management(std::span<const std::uint8_t> p) {
    if (auto e = too_short(p, 2, "Train Control Management"); !e.empty()) return fail<Command>(e);
    switch (static_cast<ManagementOp>(p[1])) {
        case ManagementOp::kReserve:
            return ok<Command>(Reserve{});
        case ManagementOp::kRelease:
            return ok<Command>(Release{});
        case ManagementOp::kNoop:
            return ok<Command>(Noop{});
    }
    return fail<Command>("unknown Train Control Management sub-command " + base::hex(p[1], 2));
}

Decoded<Command> decode_operation(std::span<const std::uint8_t> p, Instruction i) {
    switch (i) {
        case Instruction::kSetSpeed:
            if (auto e = too_short(p, 3, "Set Speed"); !e.empty()) return fail<Command>(e);
            return ok<Command>(SetSpeed{Speed::from_bits(get16(p, 1))});
        case Instruction::kSetFunction:
            if (auto e = too_short(p, 6, "Set Function"); !e.empty()) return fail<Command>(e);
            return ok<Command>(SetFunction{get24(p, 1), get16(p, 4)});
        case Instruction::kEmergencyStop:
            return ok<Command>(EmergencyStop{});
        case Instruction::kQuerySpeeds:
            return ok<Command>(QuerySpeeds{});
        case Instruction::kQueryFunction:
            if (auto e = too_short(p, 4, "Query Function"); !e.empty()) return fail<Command>(e);
            return ok<Command>(QueryFunction{get24(p, 1)});
        default:
            return fail<Command>("unknown instruction " + base::hex(p[0], 2));
    }
}

Decoded<Reply> decode_controller_reply(std::span<const std::uint8_t> p) {
    if (auto e = too_short(p, 3, "a Controller Configuration Reply"); !e.empty())
        return fail<Reply>(e);
    switch (static_cast<ControllerOp>(p[1])) {
        case ControllerOp::kAssign:
            return ok<Reply>(AssignReply{p[2]});
        case ControllerOp::kChangingNotify:
            return ok<Reply>(ChangingNotifyReply{p[2]});
        case ControllerOp::kQuery:
            if (auto e = too_short(p, 9, "a Query Controller Reply"); !e.empty())
                return fail<Reply>(e);
            return ok<Reply>(ControllerReply{p[2], get_node(p, 3)});
        default:
            return fail<Reply>("unknown Controller Configuration Reply " + base::hex(p[1], 2));
    }
}

Decoded<Reply> decode_listener_reply(std::span<const std::uint8_t> p) {
    if (auto e = too_short(p, 3, "a Listener Configuration Reply"); !e.empty())
        return fail<Reply>(e);
    const auto which = static_cast<ListenerOp>(p[1]);
    switch (which) {
        case ListenerOp::kAttach:
        case ListenerOp::kDetach:
            if (auto e = too_short(p, 10, "an Attach/Detach Node Reply"); !e.empty())
                return fail<Reply>(e);
            return ok<Reply>(ListenerChangeReply{which, get_node(p, 2), get16(p, 8)});
        case ListenerOp::kQuery: {
            ListenersReply r{p[2], std::nullopt};
            if (p.size() == 3) return ok<Reply>(r);
            if (auto e = too_short(p, 11, "a Query Nodes Reply with its entry"); !e.empty())
                return fail<Reply>(e);
            r.entry = ListenerEntry{p[3], p[4], get_node(p, 5)};
            return ok<Reply>(r);
        }
    }
    return fail<Reply>("unknown Listener Configuration Reply " + base::hex(p[1], 2));
}

Decoded<Reply> decode_management_reply(std::span<const std::uint8_t> p) {
    if (auto e = too_short(p, 3, "a Train Control Management Reply"); !e.empty())
        return fail<Reply>(e);
    if (p[1] == op(ManagementOp::kReserve)) return ok<Reply>(ReserveReply{p[2]});
    if (p[1] == op(ManagementOp::kHeartbeatRequest)) return ok<Reply>(HeartbeatRequest{p[2]});
    return fail<Reply>("unknown Train Control Management Reply " + base::hex(p[1], 2));
}

std::string node_text(NodeId id) {
    return id.to_string();
}

struct CommandText {
    std::string operator()(const SetSpeed& c) const { return "Set Speed " + c.speed.to_string(); }
    std::string operator()(const SetFunction& c) const {
        return "Set Function " + std::to_string(c.address) + " = " + std::to_string(c.value);
    }
    std::string operator()(const EmergencyStop&) const { return "Emergency Stop"; }
    std::string operator()(const QuerySpeeds&) const { return "Query Speeds"; }
    std::string operator()(const QueryFunction& c) const {
        return "Query Function " + std::to_string(c.address);
    }
    std::string operator()(const AssignController& c) const {
        return "Assign Controller " + node_text(c.controller);
    }
    std::string operator()(const ReleaseController& c) const {
        return "Release Controller " + node_text(c.controller);
    }
    std::string operator()(const QueryController&) const { return "Query Controller"; }
    std::string operator()(const ControllerChangingNotify& c) const {
        return "Controller Changing Notify " + node_text(c.new_controller);
    }
    std::string operator()(const AttachListener& c) const {
        return "Attach Listener " + node_text(c.listener) + " flags " + base::hex(c.flags, 2);
    }
    std::string operator()(const DetachListener& c) const {
        return "Detach Listener " + node_text(c.listener);
    }
    std::string operator()(const QueryListeners& c) const {
        return "Query Listeners" + (c.index ? " index " + std::to_string(*c.index) : "");
    }
    std::string operator()(const Reserve&) const { return "Reserve"; }
    std::string operator()(const Release&) const { return "Release"; }
    std::string operator()(const Noop&) const { return "No-op"; }
};

struct ReplyText {
    std::string operator()(const SpeedsReply& r) const {
        return "Query Speeds Reply set " + r.set.to_string() + ", status " +
               base::hex(r.status, 2) + ", commanded " + r.commanded.to_string() + ", actual " +
               r.actual.to_string();
    }
    std::string operator()(const FunctionReply& r) const {
        return "Query Function Reply " + std::to_string(r.address) + " = " +
               std::to_string(r.value);
    }
    std::string operator()(const AssignReply& r) const {
        return "Assign Controller Reply " + base::hex(r.result, 2);
    }
    std::string operator()(const ControllerReply& r) const {
        return "Query Controller Reply flags " + base::hex(r.flags, 2) + ", controller " +
               node_text(r.controller);
    }
    std::string operator()(const ChangingNotifyReply& r) const {
        return "Controller Changing Notify Reply " + base::hex(r.result, 2);
    }
    std::string operator()(const ListenerChangeReply& r) const {
        return std::string(r.op == ListenerOp::kAttach ? "Attach" : "Detach") + " Node Reply " +
               node_text(r.listener) + " " + base::hex(r.code, 4);
    }
    std::string operator()(const ListenersReply& r) const {
        std::string s = "Query Nodes Reply count " + std::to_string(r.count);
        if (r.entry)
            s += ", index " + std::to_string(r.entry->index) + " " + node_text(r.entry->node) +
                 " flags " + base::hex(r.entry->flags, 2);
        return s;
    }
    std::string operator()(const ReserveReply& r) const {
        return "Reserve Reply " + base::hex(r.result, 2);
    }
    std::string operator()(const HeartbeatRequest& r) const {
        return "Heartbeat Request " + std::to_string(r.timeout) + " s";
    }
};

}  // namespace

Speed Speed::of(double value, bool reverse) {
    const std::uint16_t magnitude = base::half_from_double(std::fabs(value));
    return Speed(static_cast<std::uint16_t>(magnitude | (reverse ? 0x8000U : 0U)));
}

double Speed::magnitude() const {
    return base::half_to_double(static_cast<std::uint16_t>(bits_ & 0x7FFF));
}

std::string Speed::to_string() const {
    if (is_nan()) return "NaN (" + base::hex(bits_, 4) + ")";
    char number[32];
    std::snprintf(number, sizeof number, "%g", magnitude());
    return std::string(number) + (reverse() ? " reverse" : " forward");
}

std::vector<std::uint8_t> encode(const Command& command) {
    Bytes out = std::visit(CommandEncoder{}, command.body);
    if (command.forwarded) out[0] = u8(out[0] | kForwardedBit);
    return out;
}

std::vector<std::uint8_t> encode(const Reply& reply) {
    return std::visit(ReplyEncoder{}, reply);
}

Decoded<Command> decode_command(std::span<const std::uint8_t> p) {
    if (p.empty()) return fail<Command>("empty payload");
    const bool forwarded = (p[0] & kForwardedBit) != 0;
    const auto i = static_cast<Instruction>(p[0] & kInstructionMask);
    Decoded<Command> d;
    switch (i) {
        case Instruction::kController:
            d = decode_controller(p);
            break;
        case Instruction::kListener:
            d = decode_listener(p);
            break;
        case Instruction::kManagement:
            d = decode_management(p);
            break;
        default:
            d = decode_operation(p, i);
            break;
    }
    if (d.value) d.value->forwarded = forwarded;
    return d;
}

Decoded<Reply> decode_reply(std::span<const std::uint8_t> p) {
    if (p.empty()) return fail<Reply>("empty payload");
    switch (static_cast<Instruction>(p[0])) {
        case Instruction::kQuerySpeeds:
            if (auto e = too_short(p, 8, "a Query Speeds Reply"); !e.empty()) return fail<Reply>(e);
            return ok<Reply>(SpeedsReply{Speed::from_bits(get16(p, 1)), p[3],
                                         Speed::from_bits(get16(p, 4)),
                                         Speed::from_bits(get16(p, 6))});
        case Instruction::kQueryFunction:
            if (auto e = too_short(p, 6, "a Query Function Reply"); !e.empty())
                return fail<Reply>(e);
            return ok<Reply>(FunctionReply{get24(p, 1), get16(p, 4)});
        case Instruction::kController:
            return decode_controller_reply(p);
        case Instruction::kListener:
            return decode_listener_reply(p);
        case Instruction::kManagement:
            return decode_management_reply(p);
        default:
            return fail<Reply>("unknown reply " + base::hex(p[0], 2));
    }
}

std::string describe(const Command& command) {
    return std::visit(CommandText{}, command.body) + (command.forwarded ? " (forwarded)" : "");
}

std::string describe(const Reply& reply) {
    return std::visit(ReplyText{}, reply);
}

}  // namespace olcb::train
