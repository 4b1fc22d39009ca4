#include "simnode/faults/fault_hooks.hpp"

#include <algorithm>

#include "simnode/faults/fault_catalog.hpp"

namespace olcb::simnode {

void StackHooks::install(NodeStack& stack) const {
    if (!inbound_.empty()) {
        // A frame goes to a layer only when every fault lets it.
        stack.set_inbound_filter([&stack, filters = inbound_](const CanFrame& f, TimePoint now) {
            FrameRoute route;
            for (const Inbound& filter : filters) {
                const FrameRoute one = filter(stack, f, now);
                route.alias = route.alias && one.alias;
                route.messages = route.messages && one.messages;
            }
            return route;
        });
    }
    if (!outbound_.empty()) {
        stack.set_outbound_filter([filters = outbound_](Message& m) {
            for (const NodeStack::OutboundFilter& filter : filters) {
                if (!filter(m)) return false;
            }
            return true;
        });
    }
    if (window_) stack.streams().set_window_policy(window_);
}

namespace {

// Calls one hook of every fault that is on and has it, in catalogue order.
template <class Hook, class... Args>
void each(const auto& on, Hook FaultHooks::*point, Args&&... args) {
    for (const auto& a : on) {
        if (const Hook hook = a.decl->hooks.*point) hook(args..., a.value);
    }
}

}  // namespace

ActiveFaults::ActiveFaults(const FaultSet& faults) {
    for (const FaultDecl& d : fault_decls()) {
        const FaultValue v = fault_value(faults, d);
        if (v != FaultValue{}) on_.push_back({&d, v});
    }
}

bool ActiveFaults::watches() const {
    return std::any_of(on_.begin(), on_.end(), [](const Active& a) { return a.decl->watches; });
}

void ActiveFaults::stack_config(NodeStackConfig& config) const {
    each(on_, &FaultHooks::stack_config, config);
}

void ActiveFaults::attach(NodeStack& stack) const {
    StackHooks hooks;
    each(on_, &FaultHooks::stack, hooks);
    hooks.install(stack);
}

AnswerLatency ActiveFaults::latency() const {
    AnswerLatency latency;
    each(on_, &FaultHooks::latency, latency);
    return latency;
}

std::vector<std::uint8_t> ActiveFaults::served_cdi(std::string_view text) const {
    ServedCdi cdi{std::string(text.substr(0, std::min(text.size(), text.find('\0')))), true, {}};
    each(on_, &FaultHooks::cdi, cdi);
    std::vector<std::uint8_t> bytes(cdi.xml.begin(), cdi.xml.end());
    if (cdi.terminated) bytes.push_back(0);
    bytes.insert(bytes.end(), cdi.trailer.begin(), cdi.trailer.end());
    return bytes;
}

void ActiveFaults::acdi(AcdiVersions& versions) const {
    each(on_, &FaultHooks::acdi, versions);
}

void ActiveFaults::space(SpaceBuild& build) const {
    each(on_, &FaultHooks::space, build);
}

bool ActiveFaults::stores() const {
    return std::any_of(on_.begin(), on_.end(),
                       [](const Active& a) { return a.decl->hooks.store != nullptr; });
}

void ActiveFaults::store(const cdi::Element& element, std::span<std::uint8_t> bytes) const {
    StoredValue value{element, bytes};
    each(on_, &FaultHooks::store, value);
}

EventPolicy ActiveFaults::events() const {
    EventPolicy policy;
    each(on_, &FaultHooks::events, policy);
    return policy;
}

ClockQuirks ActiveFaults::clock() const {
    ClockQuirks quirks;
    each(on_, &FaultHooks::clock, quirks);
    return quirks;
}

void ActiveFaults::started(NodeLife& life) const {
    each(on_, &FaultHooks::started, life);
}

void ActiveFaults::powering_up(NodeLife& life) const {
    each(on_, &FaultHooks::powering_up, life);
}

bool ActiveFaults::message(NodeLife& life, const Message& message) const {
    for (const Active& a : on_) {
        if (a.decl->hooks.message != nullptr && a.decl->hooks.message(life, message, a.value)) {
            return true;
        }
    }
    return false;
}

void ActiveFaults::snip(memory::Snip& snip) const {
    each(on_, &FaultHooks::snip, snip);
}

void ActiveFaults::datagram(DatagramTurn& turn) const {
    each(on_, &FaultHooks::datagram, turn);
}

void ActiveFaults::request(RequestTurn& turn) const {
    each(on_, &FaultHooks::request, turn);
}

bool ActiveFaults::reply(const memory::DecodeResult& asked, memory::Decision& decision) const {
    ReplyTurn turn{asked, decision};
    each(on_, &FaultHooks::reply, turn);
    return turn.unacknowledged;
}

void ActiveFaults::written(WriteTurn& turn) const {
    each(on_, &FaultHooks::written, turn);
}

void ActiveFaults::answer(AnswerPlan& plan) const {
    each(on_, &FaultHooks::answer, plan);
}

TrainBuild ActiveFaults::train() const {
    TrainBuild build;
    each(on_, &FaultHooks::train, build);
    return build;
}

void ActiveFaults::train_reply(TrainReplyTurn& turn) const {
    each(on_, &FaultHooks::train_reply, turn);
}

void ActiveFaults::train_forward(TrainForwardTurn& turn) const {
    each(on_, &FaultHooks::train_forward, turn);
}

}  // namespace olcb::simnode
