#include "simnode/faults/fault_hooks.hpp"

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

ActiveFaults::ActiveFaults(const FaultSet& faults) {
    for (const FaultDecl& d : fault_decls()) {
        const FaultValue v = fault_value(faults, d);
        if (v != FaultValue{}) on_.push_back({&d, v});
    }
}

void ActiveFaults::stack_config(NodeStackConfig& config) const {
    for (const Active& a : on_) {
        if (a.decl->hooks.stack_config != nullptr) a.decl->hooks.stack_config(config, a.value);
    }
}

void ActiveFaults::attach(NodeStack& stack) const {
    StackHooks hooks;
    for (const Active& a : on_) {
        if (a.decl->hooks.stack != nullptr) a.decl->hooks.stack(hooks, a.value);
    }
    hooks.install(stack);
}

void ActiveFaults::snip(memory::Snip& snip) const {
    for (const Active& a : on_) {
        if (a.decl->hooks.snip != nullptr) a.decl->hooks.snip(snip, a.value);
    }
}

std::optional<memory::Decision> ActiveFaults::request(memory::DecodeResult& asked) const {
    RequestTurn turn{asked, std::nullopt};
    for (const Active& a : on_) {
        if (a.decl->hooks.request != nullptr) a.decl->hooks.request(turn, a.value);
    }
    return std::move(turn.answer);
}

void ActiveFaults::reply(const memory::DecodeResult& asked, memory::Decision& decision) const {
    ReplyTurn turn{asked, decision};
    for (const Active& a : on_) {
        if (a.decl->hooks.reply != nullptr) a.decl->hooks.reply(turn, a.value);
    }
}

void ActiveFaults::answer(AnswerPlan& plan) const {
    for (const Active& a : on_) {
        if (a.decl->hooks.answer != nullptr) a.decl->hooks.answer(plan, a.value);
    }
}

}  // namespace olcb::simnode
