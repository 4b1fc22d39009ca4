// Many NodeStacks behind one interface on a CAN segment, sans-I/O: their frames to each other
// and out, frames from the segment in, their timers. StackDriver runs one on an io_context;
// tests run one on a simulated clock.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <queue>
#include <utility>
#include <vector>

#include "openlcb/alias_cache.hpp"
#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/stack_routes.hpp"

namespace olcb {

/// How a StackGroup treats its stacks.
struct StackGroupOptions {
    /// The stacks look alias mappings up in one cache the group learns from every frame (as the
    /// virtual nodes of one interface share its cache), instead of each keeping its own from
    /// every frame: N caches of up to 4,095 mappings each, each taught every announcement.
    bool share_alias_cache = false;
};

/// The attached stacks share one segment: a frame from outside (deliver()) goes to every stack
/// it concerns, a frame a stack sends (flush()) goes out through the sink and to every other
/// stack it concerns. Which stacks a frame concerns is StackRoutes' answer, so a frame costs
/// in proportion to the stacks that act on it, not to all of them; the deadlines are kept in a
/// heap for the same reason. Stacks are given frames in the order they were attached, and
/// flushed in the order they got output, exactly as if every stack were given every frame.
class StackGroup {
public:
    /// Counters since construction.
    struct Stats {
        std::uint64_t frames_out = 0;  ///< frames the stacks sent (each counted once)
        std::uint64_t deliveries = 0;  ///< NodeStack::on_frame() calls made
        std::uint64_t polls = 0;       ///< NodeStack::poll() calls made
    };
    /// Where frames the stacks send leave the group.
    using Sink = std::function<void(const CanFrame&)>;
    /// Told when a stack got output or a new timer (to flush and re-arm soon).
    using Notice = std::function<void()>;

    explicit StackGroup(StackGroupOptions options = {});
    /// Stacks still attached become undriven (their output handlers turn into no-ops),
    /// whether they are destroyed before or after the group.
    ~StackGroup();
    StackGroup(const StackGroup&) = delete;
    StackGroup& operator=(const StackGroup&) = delete;

    /// Sets who is told of new output and timers.
    void set_notice(Notice notice) { notice_ = std::move(notice); }
    /// Attaches stack (it must stay alive while attached); its output handler is taken over.
    void attach(NodeStack& stack);
    /// Detaches stack; its pending output stays in it (and it keeps its own cache again).
    void detach(NodeStack& stack);
    /// Starts every attached stack at now.
    void start_all(TimePoint now);
    /// A frame from the segment outside the group: to every stack it concerns.
    void deliver(const CanFrame& frame, TimePoint now);
    /// Sends the output of the stacks that have some, oldest first: each frame to sink, then to
    /// the other stacks it concerns, whose answers are sent in the same call, until about
    /// max_frames went (a stack's output goes whole); returns the frames sent. Not re-entrant
    /// (a stack callback must not call it).
    std::size_t flush(TimePoint now, const Sink& sink, std::size_t max_frames = SIZE_MAX);
    /// True when a stack has output for flush().
    bool has_output() const { return !dirty_.empty(); }
    /// Polls every stack whose deadline has come.
    void poll(TimePoint now);
    /// The earliest deadline of any stack.
    std::optional<TimePoint> next_deadline();
    /// Number of attached stacks.
    std::size_t size() const { return count_; }
    /// Counters.
    const Stats& stats() const { return stats_; }
    /// The cache the stacks share (nullptr without StackGroupOptions::share_alias_cache).
    const AliasCache* shared_alias_cache() const { return routes_.shared_cache(); }

private:
    using Deadline = std::pair<TimePoint, std::size_t>;

    void mark_dirty(std::size_t slot);
    void refresh(std::size_t slot);
    void refresh_dirty();
    void to_stacks(const CanFrame& frame, TimePoint now, std::size_t sender);
    void compact_deadlines();

    StackRoutes routes_;
    std::vector<std::optional<TimePoint>> deadlines_;  // by slot, as last read
    std::vector<char> dirty_flags_;                    // by slot
    std::vector<std::size_t> dirty_;                   // slots with output, in order
    // Earliest first; an entry whose time is no longer its slot's deadline is stale.
    std::priority_queue<Deadline, std::vector<Deadline>, std::greater<>> heap_;
    std::vector<CanFrame> scratch_;
    std::size_t count_ = 0;
    Stats stats_;
    Notice notice_;
    std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);
};

}  // namespace olcb
