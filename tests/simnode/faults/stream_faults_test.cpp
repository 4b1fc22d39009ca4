// The stream-* faults: a stream read whose count, end or window is wrong, read by a second
// NodeStack as lcc-conform reads (the good node: sim_node_stream_test.cpp).
#include <gtest/gtest.h>

#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(StreamReadTest, WrongCountFaultMisstatesTheTotal) {
    NodeConfig c = default_config();
    c.faults = test::faults_of({"stream-wrong-count"});
    boot(std::move(c));
    read_cdi(256);
    ASSERT_TRUE(completed_);
    EXPECT_EQ(data_, cdi_bytes());
    EXPECT_EQ(completed_->count, data_.size() + 1);
}

TEST_F(StreamReadTest, NoCompleteFaultNeverEnds) {
    NodeConfig c = default_config();
    c.faults = test::faults_of({"stream-no-complete"});
    boot(std::move(c));
    read_cdi(256, 2s);
    EXPECT_FALSE(completed_);
    EXPECT_EQ(data_, cdi_bytes());
}

TEST_F(StreamReadTest, IgnoreProceedAndExceedBufferOverrunTheWindow) {
    NodeConfig c = default_config();
    c.faults = test::faults_of({"stream-ignore-proceed"});
    boot(std::move(c));
    read_cdi(64);
    ASSERT_TRUE(completed_);
    EXPECT_GT(info()->max_in_window, 64u);
}

TEST_F(StreamReadTest, ExceedBufferSendsTwiceTheGrant) {
    NodeConfig c = default_config();
    c.faults = test::faults_of({"stream-exceed-buffer"});
    boot(std::move(c));
    read_cdi(64);
    ASSERT_TRUE(completed_);
    EXPECT_GT(info()->max_in_window, 64u);  // our auto Proceed at 64 hides part of the 128
    EXPECT_EQ(data_, cdi_bytes());
}

}  // namespace
}  // namespace olcb::simnode::test
