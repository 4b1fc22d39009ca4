#include "openlcb/sim_network.hpp"

#include <algorithm>

#include "openlcb/gridconnect.hpp"

namespace olcb {

SimNetwork::SimNetwork(TimePoint epoch) : epoch_(epoch) {
    // A silent port that sees every frame: the log.
    bus_.add_endpoint([this](const CanFrame& f) {
        if (logging_ && log_.size() < max_log_) log_.push_back({now(), f});
    });
}

SimNetwork::~SimNetwork() = default;

void SimNetwork::add_stack(NodeStack& stack) {
    const std::size_t index = stacks_.size();
    Transport& port = bus_.add_endpoint([this, index](const CanFrame& f) {
        stacks_[index].stack->on_frame(f, now());
        pump(index);  // replies queue right behind the frame that caused them
    });
    stacks_.push_back({&stack, &port});
    // The weak token makes a stack that outlives the network harmless (declaration order of
    // tests varies); the network never touches a stack after its own destruction began.
    auto mark_dirty = [this, index, alive = std::weak_ptr<bool>(alive_)] {
        if (alive.expired()) return;
        if (!stacks_[index].dirty) {
            stacks_[index].dirty = true;
            dirty_.push_back(index);
        }
    };
    if (stack.has_output()) mark_dirty();
    stack.set_output_handler(mark_dirty);
}

Transport& SimNetwork::add_endpoint(EndpointHandler handler) {
    if (!handler) return bus_.add_endpoint();
    return bus_.add_endpoint([this, h = std::move(handler)](const CanFrame& f) { h(f, now()); });
}

void SimNetwork::start_all() {
    for (auto& s : stacks_) s.stack->start(now());
}

void SimNetwork::pump(std::size_t index) {
    StackPort& s = stacks_[index];
    while (auto f = s.stack->pop_frame()) s.port->send(*f);
}

void SimNetwork::pump_dirty() {
    // Index loop: pumping never adds to dirty_ (output handlers fire on new output only).
    for (std::size_t i = 0; i < dirty_.size(); ++i) {
        stacks_[dirty_[i]].dirty = false;
        pump(dirty_[i]);
    }
    dirty_.clear();
}

std::optional<TimePoint> SimNetwork::earliest_deadline() const {
    std::optional<TimePoint> best;
    for (const auto& s : stacks_) {
        if (auto d = s.stack->next_deadline(); d && (!best || *d < *best)) best = d;
    }
    return best;
}

// The earliest timer deadline or, with the timing model, frame completion on the bus.
std::optional<TimePoint> SimNetwork::next_event() {
    std::optional<TimePoint> next = earliest_deadline();
    if (!bus_.timing_enabled()) return next;
    if (auto c = bus_.next_completion()) {
        const TimePoint done = epoch_ + *c;
        if (!next || done < *next) next = done;
    }
    return next;
}

void SimNetwork::poll_due() {
    const TimePoint t = now();
    for (std::size_t i = 0; i < stacks_.size(); ++i) {
        if (auto d = stacks_[i].stack->next_deadline(); d && *d <= t) {
            stacks_[i].stack->poll(t);
            pump(i);
        }
    }
}

bool SimNetwork::run_until(const std::function<bool()>& pred, Duration max) {
    step_limit_hit_ = false;
    const TimePoint limit = now() + max;
    for (std::uint64_t steps = 0;; ++steps) {
        pump_dirty();
        if (pred && pred()) return true;
        if (steps >= max_steps_) {
            step_limit_hit_ = true;
            return false;
        }
        if (!bus_.timing_enabled() && bus_.deliver(1) > 0) continue;
        const std::optional<TimePoint> next = next_event();
        if (!next || *next > limit) {
            if (now() < limit) bus_.advance_to(limit - epoch_);
            pump_dirty();
            return pred && pred();
        }
        // Delivers at most the one frame completing at *next (timing model), then due timers.
        bus_.advance_to(std::max(*next, now()) - epoch_, 1);
        poll_due();
    }
}

std::vector<std::string> SimNetwork::log_text() const {
    return log_text(0);
}

std::vector<std::string> SimNetwork::log_text(std::size_t first) const {
    std::vector<std::string> out;
    for (std::size_t i = first; i < log_.size(); ++i)
        out.push_back(gridconnect::format(log_[i].frame));
    return out;
}

}  // namespace olcb
