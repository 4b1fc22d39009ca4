#include "openlcb/alias_generator.hpp"

#include <gtest/gtest.h>

#include <random>

namespace olcb {
namespace {

// The TN's 24+24-bit formulation, to cross-check the 64-bit step.
std::uint64_t step_24(std::uint64_t x) {
    std::uint64_t hi = x >> 24;
    std::uint64_t lo = x & 0xFFFFFF;
    const std::uint64_t t1 = ((hi << 9) | ((lo >> 15) & 0x1FF)) & 0xFFFFFF;
    const std::uint64_t t2 = (lo << 9) & 0xFFFFFF;
    lo = lo + t2 + 0x7A4BA9;
    hi = hi + t1 + 0x1B0CA3;
    hi = (hi & 0xFFFFFF) + (lo >> 24);
    lo &= 0xFFFFFF;
    return (hi & 0xFFFFFF) << 24 | lo;
}

TEST(AliasGenerator, TnCheckVectorsFromZeroSeed) {
    EXPECT_EQ(AliasGenerator::alias_of(0), 0x000);
    EXPECT_EQ(AliasGenerator::step(0), 0x1B0CA37A4BA9u);
    EXPECT_EQ(AliasGenerator::alias_of(0x1B0CA37A4BA9), 0x11E);
    EXPECT_EQ(AliasGenerator::step(0x1B0CA37A4BA9), 0x4F603B8BE952u);
    EXPECT_EQ(AliasGenerator::alias_of(0x4F603B8BE952), 0x521);
    EXPECT_EQ(AliasGenerator::step(0x4F603B8BE952), 0x2AE3F6D8D8FBu);
    EXPECT_EQ(AliasGenerator::alias_of(0x2AE3F6D8D8FB), 0x42E);
}

TEST(AliasGenerator, ZeroSeedSkipsZeroAlias) {
    AliasGenerator gen{NodeId(0)};
    EXPECT_EQ(gen.next(), 0x11E);
    EXPECT_EQ(gen.next(), 0x521);
    EXPECT_EQ(gen.next(), 0x42E);
}

TEST(AliasGenerator, TnCheckVectorsCloseSeeds) {
    const std::pair<std::uint64_t, std::uint16_t> cases[] = {
        {0x020121000012, 0x62D},
        {0x020112000021, 0xA24},
        {0x020111000022, 0x625},
        {0x020122000011, 0xA2C},
    };
    for (const auto& [seed, second] : cases) {
        AliasGenerator gen{NodeId(seed)};
        EXPECT_EQ(gen.next(), 0x113) << std::hex << seed;
        EXPECT_EQ(gen.next(), second) << std::hex << seed;
    }
}

TEST(AliasGenerator, WorkedExampleSequence) {
    AliasGenerator gen{NodeId(0x050101012200)};
    EXPECT_EQ(gen.next(), 0x343);
    EXPECT_EQ(gen.state(), 0x050101012200u);  // un-stepped first value
    EXPECT_EQ(gen.next(), 0xBD9);
    EXPECT_EQ(gen.state(), 0x220FA6BF6DA9u);
    EXPECT_EQ(gen.next(), 0x60D);
    EXPECT_EQ(gen.state(), 0x5C69C9150B52u);
    EXPECT_EQ(gen.next(), 0xC82);
    EXPECT_EQ(gen.state(), 0x4B0896A5FAFBu);
    EXPECT_EQ(AliasGenerator{NodeId(0x02010D000001)}.next(), 0x12C);
}

TEST(AliasGenerator, StepMatchesTwentyFourBitForm) {
    std::mt19937_64 rng(42);
    for (int i = 0; i < 10000; ++i) {
        const std::uint64_t x = rng() & NodeId::kMask;
        ASSERT_EQ(AliasGenerator::step(x), step_24(x)) << std::hex << x;
    }
}

}  // namespace
}  // namespace olcb
