// resident_memory: the process's VmRSS, which simnode's start-up report and the benchmarks quote.
#include "simnode/resident_memory.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>

namespace olcb::simnode {
namespace {

TEST(ResidentMemoryTest, GrowsByWhatTheProcessTouches) {
    const long before = resident_kib();
    ASSERT_GT(before, 0) << "/proc/self/status has no VmRSS";
    constexpr std::size_t kBytes = 64u << 20;
    const auto block = std::make_unique<char[]>(kBytes);
    std::memset(block.get(), 1, kBytes);  // touched pages are resident
    const long after = resident_kib();
    EXPECT_GE(after - before, static_cast<long>(kBytes / 1024 / 2)) << before << " -> " << after;
    EXPECT_EQ(block[kBytes - 1], 1);
}

}  // namespace
}  // namespace olcb::simnode
