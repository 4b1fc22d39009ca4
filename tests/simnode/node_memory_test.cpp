// NodeMemory on its own: the spaces built from a CDI, and what the faults' memory hooks change of
// them (the served CDI bytes, ACDI versions, layers in front of a space, the event policy).
#include "simnode/node_memory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode {
namespace {

// A RAM-only NodeMemory of the default scenario's CDI with the named faults.
std::unique_ptr<NodeMemory> open_memory(const std::vector<std::string>& faults = {}) {
    std::string error;
    MemoryOptions options;
    options.model = load_cdi_model(test::default_cdi(), error);
    EXPECT_TRUE(options.model) << error;
    options.node_id = test::kNodeId;
    options.user_name = "Test node";
    options.faults = test::faults_of(faults);
    auto memory = NodeMemory::open(std::move(options), error);
    EXPECT_TRUE(memory) << error;
    return memory;
}

TEST(NodeMemoryTest, ServesTheCdiTextAndOneNulInSpaceFF) {
    const auto memory = open_memory();
    const std::string& text = test::default_cdi();
    const auto bytes = memory->read(0xFF, 0, static_cast<std::uint32_t>(text.size() + 16));
    ASSERT_EQ(bytes.size(), text.size() + 1);
    EXPECT_TRUE(std::equal(text.begin(), text.end(), bytes.begin()));
    EXPECT_EQ(bytes.back(), 0);
    EXPECT_EQ(memory->served_spaces(), (std::vector<std::uint8_t>{0xFB, 0xFC, 0xFD, 0xFF}));
}

TEST(NodeMemoryTest, CdiHooksChangeTheServedBytes) {
    const auto plain = open_memory()->read(0xFF, 0, 1 << 16);
    const auto unterminated = open_memory({"cdi-unterminated"})->read(0xFF, 0, 1 << 16);
    ASSERT_EQ(unterminated.size() + 1, plain.size());
    EXPECT_NE(unterminated.back(), 0);
    const auto padded = open_memory({"cdi-padding", "cdi-unterminated"})->read(0xFF, 0, 1 << 16);
    ASSERT_EQ(padded.size(), unterminated.size() + 16) << "the trailer follows the text at once";
    EXPECT_TRUE(std::equal(unterminated.begin(), unterminated.end(), padded.begin()));
}

TEST(NodeMemoryTest, AcdiVersionBytesFollowTheHooks) {
    const auto plain = open_memory();
    const auto bumped = open_memory({"acdi-version"});
    EXPECT_EQ(bumped->read(0xFC, 0, 1).at(0), plain->read(0xFC, 0, 1).at(0) + 1);
    EXPECT_EQ(bumped->read(0xFB, 0, 1).at(0), plain->read(0xFB, 0, 1).at(0) + 1);
    EXPECT_EQ(bumped->factory_image(0xFB).at(0), bumped->read(0xFB, 0, 1).at(0));
}

TEST(NodeMemoryTest, ConstantSpacesAreWritableOnlyThroughAFaultLayerThatARebootForgets) {
    const std::vector<std::uint8_t> x{'X'};
    const auto plain = open_memory();
    EXPECT_EQ(plain->space(0xFF)->write(0, x), memory::WriteStatus::kReadOnly);

    const auto faulty = open_memory({"readonly-writable"});
    const auto before = faulty->read(0xFF, 0, 1);
    EXPECT_EQ(faulty->space(0xFF)->write(0, x), memory::WriteStatus::kOk);
    EXPECT_EQ(faulty->read(0xFF, 0, 1), x);
    EXPECT_TRUE(faulty->base_space(0xFF)->read_only()) << "the space as built stays read-only";
    faulty->reboot();
    EXPECT_EQ(faulty->read(0xFF, 0, 1), before);
}

TEST(NodeMemoryTest, AcknowledgingLayersSitAboveTheEncoding) {
    // write-dropped over int-byte-order: nothing reaches storage, reversed or not.
    const auto memory = open_memory({"int-byte-order", "write-dropped"});
    const auto before = memory->read(0xFD, test::kDelay, 4);
    EXPECT_EQ(memory->space(0xFD)->write(test::kDelay, std::vector<std::uint8_t>{0, 0, 1, 2}),
              memory::WriteStatus::kOk);
    EXPECT_EQ(memory->read(0xFD, test::kDelay, 4), before);
}

TEST(NodeMemoryTest, StoreHooksApplyToWritesAndDefaults) {
    const auto plain = open_memory();
    const auto reversed = open_memory({"int-byte-order"});
    auto delay = plain->read(0xFD, test::kDelay, 4);
    std::reverse(delay.begin(), delay.end());
    EXPECT_EQ(reversed->read(0xFD, test::kDelay, 4), delay) << "the default, stored reversed";
    ASSERT_EQ(reversed->space(0xFD)->write(test::kDelay, std::vector<std::uint8_t>{0, 0, 1, 2}),
              memory::WriteStatus::kOk);
    EXPECT_EQ(reversed->read(0xFD, test::kDelay, 4), (std::vector<std::uint8_t>{2, 1, 0, 0}));
}

TEST(NodeMemoryTest, TheEventPolicyHidesSlots) {
    const auto plain = open_memory();
    const auto hiding = open_memory({"events-missing"});
    ASSERT_GE(plain->events().size(), 2u);
    EXPECT_EQ(hiding->events().size(), (plain->events().size() + 1) / 2);
    EXPECT_EQ(hiding->events().front(), plain->events().front()) << "slot 0 stays";
    EXPECT_FALSE(plain->event_policy().frozen_at_start);
    EXPECT_TRUE(open_memory({"events-stale-after-write"})->event_policy().frozen_at_start);
}

}  // namespace
}  // namespace olcb::simnode
