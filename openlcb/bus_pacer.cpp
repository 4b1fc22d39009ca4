#include "openlcb/bus_pacer.hpp"

#include <algorithm>

namespace olcb {

BusPacer::BusPacer(std::uint32_t bitrate) : bitrate_(bitrate == 0 ? 1 : bitrate) {}

void BusPacer::push(Source source, const CanFrame& frame, Duration now) {
    queues_[source].push_back({frame, now});
    ++queued_;
}

std::size_t BusPacer::queued(Source source) const {
    const auto it = queues_.find(source);
    return it == queues_.end() ? 0 : it->second.size();
}

bool BusPacer::start_next_frame() {
    if (on_wire_) return true;
    if (queues_.empty()) return false;
    Duration earliest = Duration::max();
    for (const auto& [source, q] : queues_) earliest = std::min(earliest, q.front().ready_at);
    const Duration start = std::max(free_at_, earliest);
    // Arbitration among every sender that had a frame ready when the bus became free.
    auto winner = queues_.end();
    for (auto it = queues_.begin(); it != queues_.end(); ++it) {
        const Waiting& head = it->second.front();
        if (head.ready_at > start) continue;
        if (winner == queues_.end() || head.frame.id < winner->second.front().frame.id) {
            winner = it;
        }
    }
    const CanFrame frame = winner->second.front().frame;
    const Source source = winner->first;
    winner->second.pop_front();
    if (winner->second.empty()) queues_.erase(winner);
    --queued_;
    const Duration length = can_frame_time(frame.len, bitrate_);
    on_wire_ = Done{frame, source, start + length};
    free_at_ = start + length;
    busy_time_ += length;
    bits_on_wire_ += can_frame_bits(frame.len);
    return true;
}

std::optional<BusPacer::Duration> BusPacer::next_completion() {
    if (!start_next_frame()) return std::nullopt;
    return on_wire_->completed_at;
}

std::optional<BusPacer::Done> BusPacer::pop(Duration now) {
    if (!on_wire_ && now - free_at_ > kMaxCatchUp) free_at_ = now - kMaxCatchUp;
    if (!start_next_frame() || on_wire_->completed_at > now) return std::nullopt;
    std::optional<Done> done = on_wire_;
    on_wire_.reset();
    return done;
}

}  // namespace olcb
