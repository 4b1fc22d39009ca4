#include "openlcb/can_defs.hpp"

#include <gtest/gtest.h>

#include "openlcb/gc_test_util.hpp"

namespace olcb::can {
namespace {

using namespace test;

TEST(CanDefs, MessageHeaderFields) {
    const std::uint32_t id = 0x19490343;
    EXPECT_TRUE(is_message(id));
    EXPECT_FALSE(is_control(id));
    EXPECT_EQ(frame_format(id), FrameFormat::kGlobalAddressed);
    EXPECT_EQ(can_mti(id), 0x490);
    EXPECT_EQ(source_alias(id), 0x343);
    EXPECT_EQ(message_header(0x490, 0x343), id);
}

TEST(CanDefs, DatagramAndStreamHeaders) {
    EXPECT_EQ(addressed_header(FrameFormat::kDatagramOnly, 0x343, 0x12C), 0x1A34312Cu);
    EXPECT_EQ(addressed_header(FrameFormat::kDatagramFirst, 0x12C, 0x343), 0x1B12C343u);
    EXPECT_EQ(addressed_header(FrameFormat::kDatagramMiddle, 0x12C, 0x343), 0x1C12C343u);
    EXPECT_EQ(addressed_header(FrameFormat::kDatagramLast, 0x12C, 0x343), 0x1D12C343u);
    EXPECT_EQ(addressed_header(FrameFormat::kStreamData, 0x12C, 0x343), 0x1F12C343u);
    EXPECT_EQ(frame_format(0x1D12C343), FrameFormat::kDatagramLast);
    EXPECT_EQ(dest_alias(0x1D12C343), 0x12C);
    EXPECT_TRUE(is_datagram_format(FrameFormat::kDatagramOnly));
    EXPECT_TRUE(is_datagram_format(FrameFormat::kDatagramLast));
    EXPECT_FALSE(is_datagram_format(FrameFormat::kStreamData));
    EXPECT_FALSE(is_datagram_format(FrameFormat::kGlobalAddressed));
}

TEST(CanDefs, ControlFramesClassified) {
    EXPECT_EQ(classify_control(0x17050343), ControlFrame::kCid7);
    EXPECT_EQ(classify_control(0x16101343), ControlFrame::kCid6);
    EXPECT_EQ(classify_control(0x15012343), ControlFrame::kCid5);
    EXPECT_EQ(classify_control(0x14200343), ControlFrame::kCid4);
    EXPECT_EQ(classify_control(0x10700343), ControlFrame::kRid);
    EXPECT_EQ(classify_control(0x10701343), ControlFrame::kAmd);
    EXPECT_EQ(classify_control(0x10702343), ControlFrame::kAme);
    EXPECT_EQ(classify_control(0x10703343), ControlFrame::kAmr);
    EXPECT_EQ(classify_control(0x10710343), ControlFrame::kErrorInfo0);
    EXPECT_EQ(classify_control(0x10713343), ControlFrame::kErrorInfo3);
    EXPECT_EQ(classify_control(0x10714343), ControlFrame::kOther);
    EXPECT_EQ(classify_control(0x13000343), ControlFrame::kOther);  // CID3: not OpenLCB
    EXPECT_EQ(classify_control(0x10704343), ControlFrame::kOther);
    EXPECT_TRUE(is_cid(0x17050343));
    EXPECT_TRUE(is_cid(0x14200343));
    EXPECT_FALSE(is_cid(0x13000343));
    EXPECT_FALSE(is_cid(0x10700343));
    EXPECT_FALSE(is_cid(0x19490343));
    EXPECT_EQ(cid_node_id_bits(0x16101343), 0x101);
    EXPECT_STREQ(control_name(ControlFrame::kAmd), "AMD");
}

TEST(CanDefs, ControlBuildersMatchFactSheet) {
    const NodeId node(0x050101012200);
    EXPECT_EQ(make_cid(7, node, 0x343), gc(":X17050343N;"));
    EXPECT_EQ(make_cid(6, node, 0x343), gc(":X16101343N;"));
    EXPECT_EQ(make_cid(5, node, 0x343), gc(":X15012343N;"));
    EXPECT_EQ(make_cid(4, node, 0x343), gc(":X14200343N;"));
    EXPECT_EQ(make_rid(0x343), gc(":X10700343N;"));
    EXPECT_EQ(make_amd(0x343, node), gc(":X10701343N050101012200;"));
    EXPECT_EQ(make_ame(0x12C), gc(":X1070212CN;"));
    EXPECT_EQ(make_ame(0x12C, node), gc(":X1070212CN050101012200;"));
    EXPECT_EQ(make_amr(0x343, node), gc(":X10703343N050101012200;"));
}

TEST(CanDefs, AddressedFramingNibble) {
    EXPECT_EQ(addressed_framing(0x03), AddressedFraming::kOnly);
    EXPECT_EQ(addressed_framing(0x11), AddressedFraming::kFirst);
    EXPECT_EQ(addressed_framing(0x31), AddressedFraming::kMiddle);
    EXPECT_EQ(addressed_framing(0x21), AddressedFraming::kLast);
    EXPECT_EQ(addressed_framing(0xC1), AddressedFraming::kOnly);  // reserved bits ignored
    EXPECT_EQ(addressed_dest(0x31, 0x2C), 0x12C);
}

TEST(CanDefs, OpenLcbFrameFilter) {
    CanFrame f = gc(":X19490343N;");
    EXPECT_TRUE(is_openlcb_frame(f));
    EXPECT_FALSE(is_openlcb_frame(gc(":X19490343R;")));
    EXPECT_FALSE(is_openlcb_frame(gc(":S123N;")));
}

TEST(CanDefs, MakeFrameTruncatesToEight) {
    const std::uint8_t nine[9] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    EXPECT_EQ(make_frame(0x19490343, nine).len, 8);
}

}  // namespace
}  // namespace olcb::can
