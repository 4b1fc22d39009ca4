// The snip faults: a SNIP reply that differs from the ACDI spaces or is not UTF-8.
#include <gtest/gtest.h>

#include "base/utf8.hpp"
#include "memory/acdi.hpp"
#include "memory/snip.hpp"
#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(FaultTest, SnipMismatch) {
    start_with({"snip-mismatch"});
    const memory::Snip snip = memory::decode_snip(request_snip());
    const auto fixed = memory::decode_acdi_manufacturer(node_->memory().read(0xFC, 0, 125));
    EXPECT_NE(snip.model, fixed.model);
    EXPECT_EQ(fixed.model, "simnode default");
    EXPECT_EQ(snip.manufacturer, fixed.manufacturer);
}

TEST_F(FaultTest, SnipInvalidUtf8) {
    start_with({"snip-invalid-utf8"});
    const memory::Snip snip = memory::decode_snip(request_snip());
    const auto user = memory::decode_acdi_user(node_->memory().read(0xFB, 0, 128));
    EXPECT_EQ(user.name, "Test node");  // space 251 keeps the valid name
    EXPECT_EQ(snip.user_name, user.name + "\xFF\xFE");
    EXPECT_FALSE(base::is_valid_utf8(snip.user_name));
    EXPECT_EQ(snip.model, "simnode default");  // only the user name is touched
}

}  // namespace
}  // namespace olcb::simnode::test
