// The cdi-* faults: the CDI as served in space 0xFF is unterminated, padded or schema-invalid,
// and a good node serves a parseable CDI as written.
#include <gtest/gtest.h>

#include "cdi/validator.hpp"
#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(FaultTest, CdiUnterminated) {
    start_with({"cdi-unterminated"});
    const auto cdi = served_cdi();
    EXPECT_EQ(cdi.size(), default_cdi().size());
    EXPECT_EQ(std::find(cdi.begin(), cdi.end(), 0), cdi.end());
    EXPECT_EQ(highest(0xFF), default_cdi().size() - 1);
}

TEST_F(FaultTest, CdiPadding) {
    start_with({"cdi-padding"});
    EXPECT_GT(highest(0xFF), default_cdi().size());
    const auto tail = read(0xFF, static_cast<std::uint32_t>(default_cdi().size()), 64);
    ASSERT_GT(tail.size(), 8u);
    EXPECT_EQ(tail[0], 0);
    EXPECT_NE(std::string(tail.begin(), tail.end()).find("PADDING"), std::string::npos);
}

TEST_F(FaultTest, CdiInvalidServesASchemaViolation) {
    start_with({"cdi-invalid"});
    auto cdi = served_cdi();
    ASSERT_FALSE(cdi.empty());
    const std::string text(cdi.begin(), cdi.end() - 1);
    EXPECT_NE(text.rfind("<?xml", 0), 0u);
    EXPECT_FALSE(cdi::validate(text).ok());
    EXPECT_TRUE(cdi::validate(default_cdi()).ok());
}

TEST_F(FaultTest, InvalidButParseableCdiIsServedWithItsProblem) {
    NodeConfig c = default_config();
    // Schema-invalid (unknown element) but parseable: served as real firmware would.
    c.cdi.insert(c.cdi.find("<acdi/>"), "<bogus/>");
    std::string error;
    auto node = SimNode::create(c, error);
    ASSERT_NE(node, nullptr) << error;
    EXPECT_NE(node->cdi_problem().find("bogus"), std::string::npos) << node->cdi_problem();
    c.cdi = "<cdi><segment space='253'><int size='3'/></segment";  // not well-formed
    EXPECT_EQ(SimNode::create(c, error), nullptr);
    EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace olcb::simnode::test
