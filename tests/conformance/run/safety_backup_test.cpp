#include "conformance/run/safety_backup.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "conformance/fake_memory.hpp"

namespace olcb::conform {
namespace {

std::string temp_path(const std::string& name) {
    return (std::filesystem::temp_directory_path() /
            ("j2-" + std::to_string(::getpid()) + "-" + name))
        .string();
}

TEST(MergeRanges, MergesOverlappingAndAdjacentOfOneSpaceOnly) {
    auto out = merge_ranges({{253, 10, 4}, {253, 0, 10}, {251, 0, 4}, {253, 20, 2}, {253, 12, 4}});
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out[0].space, 251);
    EXPECT_EQ(out[1].address, 0u);
    EXPECT_EQ(out[1].length, 16u);
    EXPECT_EQ(out[2].address, 20u);
}

TEST(SafetyBackup, CaptureSavesFileThatLoadsBackIdentically) {
    testing::FakeMemory mem;
    mem.spaces[253] = {1, 2, 3, 4, 5, 6, 7, 8};
    std::string path = temp_path("cap.txt");
    SafetyBackup b(path, "05.01.01.01.22.00");
    std::string error;
    ASSERT_TRUE(b.capture(mem, {{253, 2, 3}}, error)) << error;
    std::string load_error;
    auto loaded = SafetyBackup::load(path, load_error);
    ASSERT_TRUE(loaded) << load_error;
    EXPECT_EQ(loaded->node_id(), "05.01.01.01.22.00");
    ASSERT_EQ(loaded->ranges().size(), 1u);
    EXPECT_EQ(loaded->ranges()[0], (BackupRange{253, 2, {3, 4, 5}}));
    std::filesystem::remove(path);
}

TEST(SafetyBackup, CaptureFailsWithoutWritingWhenReadFails) {
    testing::FakeMemory mem;
    SafetyBackup b(temp_path("fail.txt"), "05.01.01.01.22.00");
    std::string error;
    EXPECT_FALSE(b.capture(mem, {{253, 0, 4}}, error));
    EXPECT_NE(error.find("0x1081"), std::string::npos) << error;
    EXPECT_FALSE(std::filesystem::exists(b.path()));
}

// The attack measured on an older commit: a link planted at PATH.tmp, the fixed temporary name,
// had its target overwritten with the backup text (as root, any file of the system).
TEST(SafetyBackup, SaveNeverFollowsALinkPlantedAtTheTemporaryName) {
    namespace fs = std::filesystem;
    const fs::path outside = temp_path("outside.txt");
    const std::string path = temp_path("planted.txt");
    {
        std::ofstream f(outside, std::ios::binary);
        f << "precious\n";
    }
    fs::remove(path + ".tmp");
    fs::create_symlink(outside, path + ".tmp");
    testing::FakeMemory mem;
    mem.spaces[253] = {1, 2, 3, 4};
    SafetyBackup b(path, "05.01.01.01.22.00");
    std::string error;
    EXPECT_TRUE(b.capture(mem, {{253, 0, 4}}, error)) << error;
    std::ifstream in(outside, std::ios::binary);
    const std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(kept, "precious\n");
    EXPECT_TRUE(fs::is_symlink(path + ".tmp")) << "left as it was";
    EXPECT_FALSE(fs::is_symlink(path));
    std::string load_error;
    const auto loaded = SafetyBackup::load(path, load_error);
    ASSERT_TRUE(loaded) << load_error;
    EXPECT_EQ(loaded->ranges(), b.ranges());
    fs::remove(path);
    fs::remove(path + ".tmp");
    fs::remove(outside);
}

// A directory nobody can create a file in, root included: the error names the backup's own path,
// and the caller writes nothing to the node.
TEST(SafetyBackup, SaveFailsWithThePathAndWhy) {
    testing::FakeMemory mem;
    mem.spaces[253] = {1, 2, 3, 4};
    SafetyBackup b("/dev/null/backup.txt", "05.01.01.01.22.00");
    std::string error;
    EXPECT_FALSE(b.capture(mem, {{253, 0, 4}}, error));
    EXPECT_EQ(error, "cannot open /dev/null/backup.txt for writing: Not a directory");
}

TEST(SafetyBackup, LoadRejectsTruncatedAndMalformedFiles) {
    std::string path = temp_path("bad.txt");
    std::string error;
    {
        std::ofstream f(path);
        f << "# lcc-conform safety backup v1\nnode 05.01.01.01.22.00\nrange 253 0x10 2 0A0B\n";
    }
    EXPECT_FALSE(SafetyBackup::load(path, error));
    EXPECT_NE(error.find("incomplete"), std::string::npos);
    {
        std::ofstream f(path);
        f << "# lcc-conform safety backup v1\nnode 1\nrange 253 0x10 3 0A0B\nend\n";
    }
    EXPECT_FALSE(SafetyBackup::load(path, error));
    {
        std::ofstream f(path);
        f << "# lcc-conform safety backup v1\nnode 1\nrange 253 0x10 99999999999 00\nend\n";
    }
    EXPECT_FALSE(SafetyBackup::load(path, error));
    // A space past 32 bits must not wrap to a valid one (2^32 + 253 is not space 253), nor an
    // address past 32 bits to a valid address; an address is written in 0x-hex, never bare.
    for (const char* range :
         {"range 4294967549 0x10 2 0A0B", "range 253 0x100000010 2 0A0B", "range 253 0x10 -2 0A0B",
          "range 253 0x10 2x 0A0B", "range 253 10 2 0A0B"}) {
        {
            std::ofstream f(path);
            f << "# lcc-conform safety backup v1\nnode 1\n" << range << "\nend\n";
        }
        EXPECT_FALSE(SafetyBackup::load(path, error)) << range;
        EXPECT_NE(error.find("malformed range line"), std::string::npos) << range << ": " << error;
    }
    {
        std::ofstream f(path);
        f << "hello\n";
    }
    EXPECT_FALSE(SafetyBackup::load(path, error));
    EXPECT_FALSE(SafetyBackup::load(temp_path("missing.txt"), error));
    std::filesystem::remove(path);
}

TEST(Restore, PutsBytesBackAndReportsIdentical) {
    testing::FakeMemory mem;
    mem.spaces[253] = {1, 2, 3, 4};
    SafetyBackup b("unused", "n");
    b.add({253, 1, {2, 3}});
    mem.spaces[253] = {1, 9, 9, 4};
    RestoreOutcome r = restore(b, mem);
    EXPECT_TRUE(r.identical);
    EXPECT_EQ(mem.spaces[253], (std::vector<std::uint8_t>{1, 2, 3, 4}));
    EXPECT_NE(r.summary().find("byte-identical"), std::string::npos);
}

TEST(Restore, ReportsWhatDiffersWhenTheNodeDropsWrites) {
    testing::FakeMemory mem;
    mem.spaces[253] = {1, 9, 9, 4};
    mem.drop_writes = true;
    SafetyBackup b("unused", "n");
    b.add({253, 1, {2, 3}});
    RestoreOutcome r = restore(b, mem);
    EXPECT_FALSE(r.identical);
    ASSERT_EQ(r.differences.size(), 1u);
    EXPECT_NE(r.differences[0].find("2 bytes differ"), std::string::npos) << r.differences[0];
    EXPECT_NE(r.summary().find("NOT identical"), std::string::npos);
}

TEST(Restore, LeavesARangeOutsideItsScopeAsAnotherToolLeftIt) {
    // Two concurrent runs: the one without the lock saved bytes it never wrote; the lock holder
    // changed them meanwhile. Writing them back would undo the holder's test value.
    testing::FakeMemory mem;
    mem.spaces[251] = {1, 'A', 'B', 0};
    SafetyBackup b("unused", "n");
    b.add({251, 1, {'A', 'B'}});
    b.add({251, 3, {0}});
    mem.spaces[251] = {1, 'x', 'x', 7};
    const RestoreScope ours = [](const BackupRange& r) { return r.address == 3; };
    RestoreOutcome r = restore(b, mem, ours);
    EXPECT_TRUE(r.identical) << r.summary();
    EXPECT_EQ(mem.spaces[251], (std::vector<std::uint8_t>{1, 'x', 'x', 0}));
    EXPECT_EQ(r.rewritten, 1u);
    ASSERT_EQ(r.left_as_found.size(), 1u);
    const auto& left = r.left_as_found[0];
    EXPECT_NE(left.difference.find("2 bytes differ"), std::string::npos) << left.difference;
    EXPECT_EQ(left.range.space, 251);
    EXPECT_EQ(left.range.address, 1u);
    EXPECT_EQ(left.range.length, 2u);
    // Without a scope (a user's `lcc-conform restore FILE`) every saved byte goes back.
    r = restore(b, mem);
    EXPECT_TRUE(r.left_as_found.empty());
    EXPECT_EQ(mem.spaces[251], (std::vector<std::uint8_t>{1, 'A', 'B', 0}));
}

TEST(DefaultBackupPath, NamesTheNode) {
    EXPECT_EQ(default_backup_path("05.01.01.01.22.00"), "./lcc-conform-backup-050101012200.txt");
}

}  // namespace
}  // namespace olcb::conform
