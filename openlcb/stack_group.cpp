#include "openlcb/stack_group.hpp"

#include <algorithm>

namespace olcb {

StackGroup::StackGroup(StackGroupOptions options) : routes_(options.share_alias_cache) {}

StackGroup::~StackGroup() = default;

void StackGroup::attach(NodeStack& stack) {
    const std::size_t slot = routes_.add(stack);
    deadlines_.emplace_back();
    dirty_flags_.push_back(0);
    ++count_;
    stack.set_output_handler([this, slot, alive = std::weak_ptr<bool>(alive_)] {
        if (!alive.expired()) mark_dirty(slot);
    });
    refresh(slot);
    if (stack.has_output()) mark_dirty(slot);
}

void StackGroup::detach(NodeStack& stack) {
    for (std::size_t slot = 0; slot < routes_.slots(); ++slot) {
        if (routes_.stack(slot) != &stack) continue;
        stack.set_output_handler({});
        routes_.remove(slot);  // an empty slot keeps the other slots' numbers
        deadlines_[slot].reset();
        --count_;
    }
}

void StackGroup::start_all(TimePoint now) {
    for (std::size_t slot = 0; slot < routes_.slots(); ++slot) {
        if (NodeStack* s = routes_.stack(slot)) {
            s->start(now);
            refresh(slot);
        }
    }
}

void StackGroup::mark_dirty(std::size_t slot) {
    // Called from outside any group call too (an owner restarted the stack, set a timer): what
    // routes frames to it and its deadline may have changed.
    refresh(slot);
    if (dirty_flags_[slot] == 0) {
        dirty_flags_[slot] = 1;
        dirty_.push_back(slot);
    }
    if (notice_) notice_();
}

// What routes frames to the stack, and its deadline, as they are now.
void StackGroup::refresh(std::size_t slot) {
    const NodeStack* s = routes_.stack(slot);
    if (!s) return;
    routes_.refresh(slot);
    const std::optional<TimePoint> d = s->next_deadline();
    if (d == deadlines_[slot]) return;
    deadlines_[slot] = d;
    if (!d) return;
    heap_.emplace(*d, slot);
    if (heap_.size() > 2 * count_ + 64) compact_deadlines();
}

// A stack with output may have been changed by its owner since the group last looked: an owner
// call that adds to output already there tells nobody.
void StackGroup::refresh_dirty() {
    for (const std::size_t slot : dirty_) refresh(slot);
}

void StackGroup::deliver(const CanFrame& frame, TimePoint now) {
    refresh_dirty();
    to_stacks(frame, now, StackRoutes::kNoSender);
}

void StackGroup::to_stacks(const CanFrame& frame, TimePoint now, std::size_t sender) {
    // Index loop over the routes' own list: refresh() changes the indexes, never this list.
    const std::vector<std::size_t>& hits = routes_.route(frame, sender);
    for (std::size_t k = 0; k < hits.size(); ++k) {
        const std::size_t slot = hits[k];
        routes_.stack(slot)->on_frame(frame, now);
        ++stats_.deliveries;
        refresh(slot);
    }
}

std::size_t StackGroup::flush(TimePoint now, const Sink& sink, std::size_t max_frames) {
    refresh_dirty();
    std::size_t sent = 0;
    // Index loop: delivering to the other stacks may append to dirty_. Answers can go on for
    // ever (more nodes than aliases contend endlessly), so the caller's bound is kept.
    std::size_t d = 0;
    for (; d < dirty_.size() && sent < max_frames; ++d) {
        const std::size_t slot = dirty_[d];
        dirty_flags_[slot] = 0;
        NodeStack* s = routes_.stack(slot);
        if (!s) continue;
        scratch_.clear();
        s->drain(scratch_);
        for (const CanFrame& f : scratch_) {
            ++stats_.frames_out;
            ++sent;
            if (sink) sink(f);
            to_stacks(f, now, slot);
        }
    }
    dirty_.erase(dirty_.begin(), dirty_.begin() + static_cast<std::ptrdiff_t>(d));
    return sent;
}

void StackGroup::poll(TimePoint now) {
    std::vector<std::size_t> due;
    while (!heap_.empty() && heap_.top().first <= now) {
        const auto [at, slot] = heap_.top();
        heap_.pop();
        if (deadlines_[slot] != at) continue;  // stale: the deadline moved since
        deadlines_[slot].reset();              // taken: refresh() records the next one
        due.push_back(slot);
    }
    std::sort(due.begin(), due.end());  // in slot order, as every stack were asked in turn
    for (const std::size_t slot : due) {
        NodeStack* s = routes_.stack(slot);
        if (!s) continue;
        s->poll(now);
        ++stats_.polls;
        refresh(slot);
    }
}

std::optional<TimePoint> StackGroup::next_deadline() {
    while (!heap_.empty() && deadlines_[heap_.top().second] != heap_.top().first) heap_.pop();
    if (heap_.empty()) return std::nullopt;
    return heap_.top().first;
}

// Stale entries pile up while deadlines move: rebuilt from the recorded ones.
void StackGroup::compact_deadlines() {
    std::vector<Deadline> live;
    live.reserve(count_);
    for (std::size_t slot = 0; slot < deadlines_.size(); ++slot) {
        if (deadlines_[slot]) live.emplace_back(*deadlines_[slot], slot);
    }
    heap_ = decltype(heap_)(std::greater<>{}, std::move(live));
}

}  // namespace olcb
