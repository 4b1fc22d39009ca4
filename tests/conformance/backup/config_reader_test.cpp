// The reads of a configuration backup: used ranges merged into as few 64-byte reads as one
// request per range would need, and a failed range read again variable by variable.
#include "conformance/backup/config_reader.hpp"
#include "conformance/conform_test_util.hpp"

#include <gtest/gtest.h>

#include "cdi/parser.hpp"
#include "conformance/fake_memory.hpp"

namespace olcb::conform {
namespace {

// FakeMemory that counts reads and their bytes, and refuses any read touching a hole.
struct CountingMemory : testing::FakeMemory {
    std::size_t reads = 0;
    std::size_t bytes = 0;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> holes;  // [begin, end) of space 253
    AccessResult read(std::uint8_t space, std::uint32_t address, std::size_t count) override {
        ++reads;
        bytes += count;
        for (auto [b, e] : holes) {
            if (space == 253 && address < e && address + count > b) return {false, 0x1081, {}};
        }
        return FakeMemory::read(space, address, count);
    }
};

ConfigEntry at(std::uint32_t space, std::uint64_t address, std::uint64_t size) {
    return {"k", nullptr, space, address, size};
}

TEST(ConfigReader, MergesRangesWhenItCostsNoExtraRead) {
    const std::vector<ReadSpan> spans = plan_config_reads({
        at(253, 100, 1),                 // one read alone; with [0,1) 101 bytes = 2 reads: merged
        at(253, 0, 1), at(253, 300, 2),  // [0,101) + [300,302) would be 5 reads instead of 3: apart
        at(253, 301, 8),                 // overlaps: merged
        at(251, 0, 63), at(252, 0, 8), at(256, 0, 1),  // no such space: left out
        at(253, 0xFFFFFFFF, 2),                        // past the 32-bit address range: left out
    });
    EXPECT_EQ(spans,
              (std::vector<ReadSpan>{{251, 0, 63}, {252, 0, 8}, {253, 0, 101}, {253, 300, 309}}));
}

constexpr const char* kCdi = R"(<?xml version="1.0"?>
<cdi><segment space="253"><name>S</name>
<group replication="40"><name>G</name><int size="1"><name>A</name></int>
<string size="7"><name>B</name></string></group>
<int size="2" offset="1000"><name>Far</name></int>
</segment></cdi>)";

class ConfigReaderTest : public ::testing::Test {
protected:
    void SetUp() override {
        load_cdi(kCdi, doc_, layout_);
        entries_ = config_entries(*layout_);
        memory_.spaces[253] = std::vector<std::uint8_t>(1322, 0);
        memory_.spaces[253][0] = 7;
        memory_.spaces[253][1320] = 0x12;
    }
    cdi::Document doc_;
    std::optional<cdi::Layout> layout_;
    std::vector<ConfigEntry> entries_;
    CountingMemory memory_;
};

TEST_F(ConfigReaderTest, ReadsEachUsedRangeOnceNotEachVariable) {
    const std::vector<ConfigValue> values = read_config_values(entries_, memory_);
    ASSERT_EQ(values.size(), 81u);
    EXPECT_EQ(values[0].text, "7");
    EXPECT_EQ(values[1].text, "");
    EXPECT_EQ(values[80].text, std::to_string(0x1200));
    // [0, 320) and [1320, 1322): two requests (7 datagrams), not 81, and the gap is not read.
    EXPECT_EQ(memory_.reads, 2u);
    EXPECT_EQ(memory_.bytes, 322u);
}

TEST_F(ConfigReaderTest, AFailedRangeIsReadAgainOneVariableAtATime) {
    memory_.holes = {{16, 17}};  // the third replica's A cannot be read
    const std::vector<ConfigValue> values = read_config_values(entries_, memory_);
    EXPECT_FALSE(values[4].text);
    EXPECT_NE(values[4].error.find("read failed (error 0x1081)"), std::string::npos)
        << values[4].error;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i == 4) continue;
        EXPECT_TRUE(values[i].text) << i << ": " << values[i].error;
    }
    EXPECT_EQ(memory_.reads, 2u + 80u);  // the failed span, its 80 variables, the far int
}

TEST_F(ConfigReaderTest, AReadEndingShortIsFinishedVariableByVariable) {
    memory_.spaces[253].resize(200);  // the space ends inside the group: FakeMemory refuses
    const std::vector<ConfigValue> values = read_config_values(entries_, memory_);
    EXPECT_TRUE(values[0].text);
    EXPECT_FALSE(values[79].text);
    EXPECT_FALSE(values[80].text);
}

}  // namespace
}  // namespace olcb::conform
