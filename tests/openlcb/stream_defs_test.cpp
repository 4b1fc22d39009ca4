// Stream transport wire constants and payload codecs (openlcb/stream_defs.cpp): the bytes after
// the CAN `fddd` of Initiate Request/Reply, Data Proceed and Data Complete.
#include "openlcb/stream_defs.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace olcb {
namespace {

TEST(StreamDefsTest, CodecsRoundTripAndRejectShortPayloads) {
    stream::InitiateRequest req{0x0100, 0, 0, 0x05, 0xFF, std::nullopt};
    EXPECT_EQ(stream::encode(req), (std::vector<std::uint8_t>{0x01, 0x00, 0, 0, 0x05, 0xFF}));
    EXPECT_EQ(stream::decode_initiate_request(stream::encode(req)), req);
    req.content_uid = std::array<std::uint8_t, 6>{1, 2, 3, 4, 5, 6};
    EXPECT_EQ(stream::encode(req).size(), 12u);
    EXPECT_EQ(stream::encode(req)[2], stream::kFlagCarriesContentUid);
    EXPECT_FALSE(stream::decode_initiate_request(std::vector<std::uint8_t>{0, 1, 1, 0, 5, 0xFF}));
    EXPECT_FALSE(stream::decode_initiate_request(std::vector<std::uint8_t>{0, 1, 0, 0}));
    // Five bytes: no suggested DID, read as "none".
    EXPECT_EQ(stream::decode_initiate_request(std::vector<std::uint8_t>{0, 1, 0, 0, 5})
                  ->suggested_dest_id,
              stream::kInvalidStreamId);
    const stream::InitiateReply rep{0x40, stream::kAccept, 5, 9};
    EXPECT_EQ(stream::decode_initiate_reply(stream::encode(rep)), rep);
    EXPECT_FALSE(stream::decode_initiate_reply(std::vector<std::uint8_t>{0, 1, 0, 0, 5}));
    const stream::DataComplete with{1, 2, 0x01020304};
    EXPECT_EQ(stream::encode(with), (std::vector<std::uint8_t>{1, 2, 1, 2, 3, 4}));
    EXPECT_EQ(stream::decode_data_complete(stream::encode(with)), with);
    EXPECT_EQ(stream::decode_data_complete(std::vector<std::uint8_t>{1, 2})->total_bytes,
              std::nullopt);
    EXPECT_EQ(stream::negotiate_buffer(1024, 256), 256);
    EXPECT_EQ(stream::negotiate_buffer(64, 256), 64);
    EXPECT_EQ(stream::data_frames(16, 16), 3u);  // 7 + 7 + 2
    EXPECT_EQ(stream::data_frames(20, 16), 4u);
    EXPECT_EQ(stream::data_frames(14, 0xFFFF), 2u);
}

TEST(StreamDefsTest, InitiateRequestFlagFollowsTheContentUid) {
    // The UID flag is set from the UID's presence, whatever flags says.
    stream::InitiateRequest req{0x0040,      stream::kFlagCarriesContentUid | 0x02, 0, 7, 3,
                                std::nullopt};
    EXPECT_EQ(stream::encode(req), (std::vector<std::uint8_t>{0x00, 0x40, 0x02, 0, 7, 3}));
    req.flags = 0;
    req.content_uid = std::array<std::uint8_t, 6>{0xA, 0xB, 0xC, 0xD, 0xE, 0xF};
    const std::vector<std::uint8_t> bytes = stream::encode(req);
    EXPECT_EQ(bytes,
              (std::vector<std::uint8_t>{0x00, 0x40, 0x01, 0, 7, 3, 0xA, 0xB, 0xC, 0xD, 0xE, 0xF}));
    const auto back = stream::decode_initiate_request(bytes);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->content_uid, req.content_uid);
    EXPECT_EQ(back->flags, stream::kFlagCarriesContentUid);
    EXPECT_EQ(back->max_buffer, 0x40);
    EXPECT_EQ(back->source_id, 7);
    EXPECT_EQ(back->suggested_dest_id, 3);
}

TEST(StreamDefsTest, ReplyProceedAndCompleteWireBytes) {
    const stream::InitiateReply rejected{0, stream::kRejectBufferFull, 4, 0xFF};
    EXPECT_EQ(stream::encode(rejected), (std::vector<std::uint8_t>{0, 0, 0x20, 0x20, 4, 0xFF}));
    EXPECT_FALSE(stream::is_accept(rejected.code));
    EXPECT_TRUE(stream::is_accept(stream::kAccept));
    EXPECT_TRUE(stream::is_accept(0x8123));  // only bit 15 counts
    EXPECT_FALSE(stream::is_accept(stream::kRejectInvalid));
    EXPECT_FALSE(stream::is_accept(stream::kRejectNotAccepted));
    const stream::DataProceed proceed{4, 9};
    EXPECT_EQ(stream::encode(proceed), (std::vector<std::uint8_t>{4, 9}));
    EXPECT_EQ(stream::decode_data_proceed(stream::encode(proceed)), proceed);
    EXPECT_FALSE(stream::decode_data_proceed(std::vector<std::uint8_t>{4}));
    const stream::DataComplete without{4, 9, std::nullopt};
    EXPECT_EQ(stream::encode(without), (std::vector<std::uint8_t>{4, 9}));
    EXPECT_FALSE(stream::decode_data_complete(std::vector<std::uint8_t>{4}));
    // Three to five bytes: too short for a count, read as none.
    EXPECT_EQ(stream::decode_data_complete(std::vector<std::uint8_t>{4, 9, 0, 0, 1})->total_bytes,
              std::nullopt);
}

TEST(StreamDefsTest, BufferNegotiationAndFrameCounts) {
    EXPECT_EQ(stream::negotiate_buffer(0, 256), 0);
    EXPECT_EQ(stream::negotiate_buffer(256, 0), 0);
    EXPECT_EQ(stream::negotiate_buffer(stream::kMaxBufferSize, stream::kMaxBufferSize),
              stream::kMaxBufferSize);
    EXPECT_EQ(stream::data_frames(0, 64), 0u);
    EXPECT_EQ(stream::data_frames(100, 0), 0u);
    EXPECT_EQ(stream::data_frames(7, 64), 1u);
    EXPECT_EQ(stream::data_frames(8, 64), 2u);
    EXPECT_EQ(stream::data_frames(128, 64), 20u);  // 10 frames per 64-byte buffer
    EXPECT_EQ(stream::data_frames(1, 1), 1u);
    EXPECT_EQ(stream::data_frames(5, 1), 5u);
}

}  // namespace
}  // namespace olcb
