// MemoryAccess over a Session: reads go on past short replies to the count, writes longer than a
// datagram are split and land whole.
#include "conformance/link/session_memory.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "conformance/link_test_util.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

using memory::Space;
using testing::SimBench;

TEST(SessionMemoryTest, AWriteLongerThanADatagramLandsWholeAndReadsBack) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    SessionMemory memory(*b.session, *node);
    const AccessResult before = memory.read(0xFD, 0, 100);
    ASSERT_TRUE(before.ok) << before.error;
    ASSERT_EQ(before.data.size(), 100u);
    std::vector<std::uint8_t> bytes(100);
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        bytes[i] = static_cast<std::uint8_t>(before.data[i] ^ (i + 1));  // every byte differs
    }
    const AccessResult wrote = memory.write(0xFD, 0, bytes);
    ASSERT_TRUE(wrote.ok) << wrote.error << " " << wrote.not_sent;
    const AccessResult after = memory.read(0xFD, 0, 100);
    ASSERT_TRUE(after.ok) << after.error;
    EXPECT_EQ(after.data, bytes);
}

TEST(ShortReadTest, SessionMemoryReadsTheWholeUserBlock) {
    SimBench b({"field-reads-only"});
    auto node = b.start();
    ASSERT_TRUE(node);
    SessionMemory memory(*b.session, *node);
    AccessResult r = memory.read(0xFB, 0, 128);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.data, testing::reference_bytes(Space::kAcdiUser, 0, 128));
    const std::uint64_t reads = b.session->reads(kDut, 0xFB);
    EXPECT_GT(reads, 3u);    // 64-byte reads alone would be 2
    EXPECT_LE(reads, 128u);  // and never more than one per byte
}

}  // namespace
}  // namespace olcb::conform
