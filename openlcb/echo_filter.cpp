#include "openlcb/echo_filter.hpp"

namespace olcb {

namespace {

// Bytes past len do not take part in frame equality, so they must not take part in the hash.
std::uint64_t frame_hash(const CanFrame& frame) {
    std::uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a
    const auto mix = [&h](std::uint64_t v) {
        h ^= v;
        h *= 0x100000001b3ull;
    };
    mix(frame.id);
    mix(std::uint64_t{frame.len} | std::uint64_t{frame.extended} << 8 |
        std::uint64_t{frame.remote} << 9);
    const std::size_t len = frame.len > 8 ? 8 : frame.len;
    for (std::size_t i = 0; i < len; ++i) mix(frame.data[i]);
    return h;
}

}  // namespace

EchoFilter::EchoFilter(std::size_t capacity, Duration window)
    : capacity_(capacity), window_(window) {}

void EchoFilter::sent(const CanFrame& frame, TimePoint now) {
    if (capacity_ == 0) return;
    expire(now);
    while (sent_.size() >= capacity_) pop_front();
    const auto hash = frame_hash(frame);
    sent_.push_back(Sent{frame, now, hash, false});
    ++live_[hash];
}

bool EchoFilter::is_echo(const CanFrame& frame, TimePoint now) {
    if (sent_.empty()) return false;
    expire(now);
    const auto hash = frame_hash(frame);
    const auto live = live_.find(hash);
    if (live == live_.end()) return false;
    // Echoes come back in the order sent, so the match is normally at the front.
    for (auto& s : sent_) {
        if (s.consumed || s.hash != hash || !(s.frame == frame)) continue;
        s.consumed = true;
        if (--live->second == 0) live_.erase(live);
        ++echoes_;
        while (!sent_.empty() && sent_.front().consumed) sent_.pop_front();
        return true;
    }
    return false;  // a hash collision with another frame
}

void EchoFilter::expire(TimePoint now) {
    while (!sent_.empty() && (sent_.front().consumed || now - sent_.front().at > window_)) {
        pop_front();
    }
}

void EchoFilter::pop_front() {
    const auto& s = sent_.front();
    if (!s.consumed) {
        const auto live = live_.find(s.hash);
        if (live != live_.end() && --live->second == 0) live_.erase(live);
    }
    sent_.pop_front();
}

}  // namespace olcb
