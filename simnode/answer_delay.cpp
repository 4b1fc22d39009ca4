#include "simnode/answer_delay.hpp"

#include <algorithm>

namespace olcb::simnode {

AnswerDelay::AnswerDelay(std::chrono::milliseconds latency, std::chrono::milliseconds jitter,
                         std::uint64_t seed)
    : latency_(latency), jitter_(jitter), state_(seed) {}

// SplitMix64: the same sequence on every platform and standard library, unlike the <random>
// distributions, so a test's timing is reproducible anywhere.
std::uint64_t AnswerDelay::next_random() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

TimePoint AnswerDelay::answer_at(TimePoint arrived) {
    Duration delay = latency_;
    if (jitter_.count() > 0) {
        const auto span = static_cast<std::uint64_t>(jitter_.count()) + 1;
        delay += std::chrono::milliseconds(static_cast<std::int64_t>(next_random() % span));
    }
    last_ = std::max(last_, arrived + delay);
    return last_;
}

}  // namespace olcb::simnode
