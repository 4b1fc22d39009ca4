// The node run's gate on the write ledger (conformance/run/write_cover.hpp): a write goes out only
// once the bytes it may change are in the backup file; the restore writes back only what differs.
#include "conformance/run/write_cover.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

namespace fs = std::filesystem;
using testing::SimBench;

class WriteCoverTest : public ::testing::Test {
protected:
    void SetUp() override {
        path_ =
            fs::temp_directory_path() / ("write_cover_test_" + std::to_string(::getpid()) + ".txt");
        fs::remove(path_);
        auto node = b_.start();
        ASSERT_TRUE(node);
        node_ = *node;
    }
    void TearDown() override { fs::remove(path_); }

    std::vector<std::uint8_t> node_bytes(std::uint8_t space, std::uint32_t address,
                                         std::uint32_t n) {
        return b_.dut->memory().read(space, address, n);
    }
    MemResult write(std::uint8_t space, std::uint32_t address, std::vector<std::uint8_t> data) {
        return b_.session->write(node_, static_cast<memory::Space>(space), address, data);
    }

    SimBench b_;
    NodeInfo node_;
    fs::path path_;
};

TEST_F(WriteCoverTest, AWriteIsSavedToTheFileBeforeItGoesOut) {
    WriteCover cover(*b_.session, node_, path_.string(), false);
    const auto before = node_bytes(0xFD, 0, 4);
    EXPECT_FALSE(cover.armed());
    ASSERT_TRUE(write(0xFD, 0, {1, 2, 3, 4}).ok);
    EXPECT_TRUE(cover.armed());
    std::string error;
    const auto saved = SafetyBackup::load(path_.string(), error);
    ASSERT_TRUE(saved) << error;
    ASSERT_EQ(saved->ranges().size(), 1u);
    EXPECT_EQ(saved->ranges()[0].bytes, before) << "the bytes before the write";
    // A second write over the same bytes keeps their first value.
    ASSERT_TRUE(write(0xFD, 0, {5, 6, 7, 8}).ok);
    EXPECT_TRUE(cover.backup()->uncovered(0xFD, 0, 4).empty());
    EXPECT_EQ(cover.backup()->ranges().size(), 1u);
    const RestoreOutcome out = cover.finish();
    EXPECT_TRUE(out.identical) << out.summary();
    EXPECT_EQ(out.rewritten, 4u);
    EXPECT_EQ(node_bytes(0xFD, 0, 4), before);
}

TEST_F(WriteCoverTest, ARestoreWritesOnlyWhatDiffers) {
    WriteCover cover(*b_.session, node_, path_.string(), false);
    const auto before = node_bytes(0xFD, 0, 8);
    ASSERT_TRUE(write(0xFD, 0, before).ok);  // the same bytes: nothing to put back
    const std::size_t writes = b_.session->ledger().entries().size();
    const RestoreOutcome out = cover.finish();
    EXPECT_TRUE(out.identical);
    EXPECT_EQ(out.bytes, 8u);
    EXPECT_EQ(out.rewritten, 0u);
    EXPECT_EQ(b_.session->ledger().entries().size(), writes) << "no write at all";
}

TEST_F(WriteCoverTest, ReadOnlyOtherNodesAndStreamsAreKeptBack) {
    WriteCover cover(*b_.session, node_, path_.string(), true);
    const auto before = node_bytes(0xFD, 0, 2);
    const MemResult r = write(0xFD, 0, {9, 9});
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.not_sent, "--read-only");
    EXPECT_EQ(node_bytes(0xFD, 0, 2), before);
    EXPECT_FALSE(fs::exists(path_));
    WriteCover open(*b_.session, node_, path_.string(), false);
    const NodeInfo other{NodeId{0x0501010122EEull}, 0x123};
    EXPECT_EQ(
        b_.session->write(other, memory::Space::kConfig, 0, std::vector<std::uint8_t>{1}).not_sent,
        "not the node under test");
}

TEST_F(WriteCoverTest, ACrossingWriteNeedsThePermitAndCountsItsBytePastTheEnd) {
    WriteCover cover(*b_.session, node_, path_.string(), false);
    const std::uint32_t last = 127;  // space 251 holds 0..127
    const auto before = node_bytes(0xFB, last, 1);
    const MemResult kept = write(0xFB, last, {0x41, 0x41});
    EXPECT_FALSE(kept.ok);
    EXPECT_NE(kept.not_sent.find("past the end of the space"), std::string::npos) << kept.not_sent;
    {
        WriteLedger::PastEndPermit permit(b_.session->ledger(), 0xFB);
        const MemResult sent = write(0xFB, last, {0x41, 0x41});
        EXPECT_TRUE(sent.not_sent.empty()) << sent.not_sent;
        EXPECT_FALSE(sent.ok) << "simnode refuses it (0x1082)";
    }
    EXPECT_EQ(b_.session->ledger().entries().back().past_end, 1u);
    EXPECT_TRUE(b_.session->ledger().unrestorable(node_.id).empty()) << "refused: nothing kept";
    EXPECT_EQ(node_bytes(0xFB, last, 1), before);
}

TEST_F(WriteCoverTest, TheCoverRestoresOnTheWayOut) {
    const auto before = node_bytes(0xFD, 0, 4);
    {
        WriteCover cover(*b_.session, node_, path_.string(), false);
        ASSERT_TRUE(write(0xFD, 0, {1, 2, 3, 4}).ok);
    }  // e.g. an exception left the run
    EXPECT_EQ(node_bytes(0xFD, 0, 4), before);
}

// Each save costs two fsyncs (the file, then its directory after the rename): a write over bytes
// the file already holds does not write it again; one with new bytes does, before it goes out.
TEST_F(WriteCoverTest, TheFileIsWrittenAgainOnlyWhenItGainsBytes) {
    WriteCover cover(*b_.session, node_, path_.string(), false);
    ASSERT_TRUE(write(0xFD, 0, {1, 2, 3, 4}).ok);
    // A second name for the file as it is now: a save renames a new file over path_, and the
    // link keeps the old one (and its inode number, so no new file can reuse it).
    const fs::path witness = path_.string() + ".witness";
    fs::remove(witness);
    fs::create_hard_link(path_, witness);
    ASSERT_TRUE(write(0xFD, 0, {5, 6, 7, 8}).ok);
    ASSERT_TRUE(write(0xFD, 1, {9}).ok);
    EXPECT_TRUE(fs::equivalent(path_, witness)) << "written again without new bytes";
    ASSERT_TRUE(write(0xFD, 8, {1}).ok);
    EXPECT_FALSE(fs::equivalent(path_, witness));
    std::string error;
    const auto saved = SafetyBackup::load(path_.string(), error);
    ASSERT_TRUE(saved) << error;
    EXPECT_EQ(saved->ranges().size(), 2u);
    EXPECT_TRUE(cover.finish().identical);
    fs::remove(witness);
}

// A backup file that cannot be written keeps the write back, and the cover remembers why, so the
// run can call itself incomplete instead of a clean run of SKIPs.
TEST_F(WriteCoverTest, AnUnwritableBackupKeepsTheWriteBackAndSaysWhy) {
    WriteCover cover(*b_.session, node_, "/dev/null/backup.txt", false);
    EXPECT_EQ(cover.save_error(), "");
    const auto before = node_bytes(0xFD, 0, 4);
    const MemResult r = write(0xFD, 0, {1, 2, 3, 4});
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.not_sent,
              "the safety backup cannot be saved: cannot open /dev/null/backup.txt for writing: "
              "Not a directory");
    EXPECT_EQ(cover.save_error(), "cannot open /dev/null/backup.txt for writing: Not a directory");
    std::vector<std::pair<RangeRequest, std::string>> missing;
    std::string error;
    EXPECT_FALSE(cover.capture({{0xFD, 8, 4}}, missing, error));
    EXPECT_EQ(cover.save_error(), error) << "the first reason is kept";
    EXPECT_FALSE(cover.armed());
    EXPECT_EQ(b_.session->ledger().sent(node_.id), 0u);
    EXPECT_EQ(node_bytes(0xFD, 0, 4), before);
}

}  // namespace
}  // namespace olcb::conform
