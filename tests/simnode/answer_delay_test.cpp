// AnswerDelay: the time each answer goes out, deterministic for a seed, bounded by the delay and
// its jitter, and never before an earlier answer.
#include "simnode/answer_delay.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

namespace olcb::simnode {
namespace {

using std::chrono::milliseconds;

TEST(AnswerDelay, DeterministicBoundedAndInOrder) {
    const TimePoint t0 = TimePoint{} + std::chrono::hours(1);
    AnswerDelay a(milliseconds(50), milliseconds(30), 42);
    AnswerDelay b(milliseconds(50), milliseconds(30), 42);
    TimePoint previous{};
    bool varied = false;
    for (int i = 0; i < 200; ++i) {
        const TimePoint arrived = t0 + milliseconds(i);
        const TimePoint at = a.answer_at(arrived);
        EXPECT_EQ(at, b.answer_at(arrived));
        EXPECT_GE(at, previous);
        EXPECT_GE(at, arrived + milliseconds(50));
        EXPECT_LE(at, std::max(previous, arrived + milliseconds(80)));
        varied = varied || (previous != TimePoint{} && at - previous != milliseconds(1));
        previous = at;
    }
    EXPECT_TRUE(varied) << "no jitter seen";
    AnswerDelay other(milliseconds(50), milliseconds(30), 43);
    bool differs = false;
    AnswerDelay again(milliseconds(50), milliseconds(30), 42);
    for (int i = 0; i < 20; ++i) {
        differs = differs || other.answer_at(t0 + std::chrono::seconds(i)) !=
                                 again.answer_at(t0 + std::chrono::seconds(i));
    }
    EXPECT_TRUE(differs) << "the seed does not matter";
}

}  // namespace
}  // namespace olcb::simnode
