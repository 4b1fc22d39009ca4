// When a node with the latency fault sends each answer: a fixed delay plus a deterministic
// uniform jitter, never earlier than the answer before it (so answers keep their order).
#pragma once

#include <chrono>
#include <cstdint>

#include "openlcb/clock.hpp"

namespace olcb::simnode {

/// The answer schedule of one node (sans-I/O: fed the arrival time of each request).
class AnswerDelay {
public:
    /// Delays of latency + 0..jitter (inclusive), drawn from a generator seeded with seed.
    AnswerDelay(std::chrono::milliseconds latency, std::chrono::milliseconds jitter,
                std::uint64_t seed);
    /// True when answers are delayed at all.
    bool active() const { return latency_.count() > 0 || jitter_.count() > 0; }
    /// When the answer to a request that arrived at `arrived` goes out.
    TimePoint answer_at(TimePoint arrived);
    /// Forgets the previous answer time (a restart drops every answer still held).
    void reset() { last_ = TimePoint{}; }

private:
    std::uint64_t next_random();

    std::chrono::milliseconds latency_;
    std::chrono::milliseconds jitter_;
    std::uint64_t state_;
    TimePoint last_{};
};

}  // namespace olcb::simnode
