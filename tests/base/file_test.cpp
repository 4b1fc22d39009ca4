#include "base/file.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace olcb::base {
namespace {

namespace fs = std::filesystem;

class FileTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ =
            fs::temp_directory_path() /
            ("olcb_base_file_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
             "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const std::string& name, const std::string& bytes) {
        fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary) << bytes;
        return p;
    }
    static std::string text(const fs::path& p) {
        std::ifstream in(p, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        return s.str();
    }
    // Every name in the directory, sorted: no temporary file may be left behind.
    std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const auto& e : fs::directory_iterator(dir_)) out.push_back(e.path().filename());
        std::sort(out.begin(), out.end());
        return out;
    }

    fs::path dir_;
};

TEST_F(FileTest, ReadsEveryByteAsItIs) {
    std::string bytes("a\0b\r\n\xFF", 6);
    bytes += std::string(200000, 'x');  // several read() calls
    std::string error;
    const auto got = read_file(write("bin", bytes), error);
    ASSERT_TRUE(got.has_value()) << error;
    EXPECT_EQ(*got, bytes);
    EXPECT_TRUE(error.empty());
}

TEST_F(FileTest, ReadsAnEmptyFile) {
    std::string error;
    const auto got = read_file(write("empty", ""), error);
    ASSERT_TRUE(got.has_value()) << error;
    EXPECT_TRUE(got->empty());
}

TEST_F(FileTest, AMissingFileSaysPathAndReason) {
    const fs::path missing = dir_ / "missing.xml";
    std::string error;
    EXPECT_FALSE(read_file(missing, error).has_value());
    EXPECT_EQ(error, "cannot read " + missing.string() + ": No such file or directory");
}

TEST_F(FileTest, ADirectoryIsRefusedNotReadAsEmpty) {
    std::string error;
    EXPECT_FALSE(read_file(dir_, error).has_value());
    EXPECT_EQ(error, "cannot read " + dir_.string() + ": Is a directory");
}

TEST_F(FileTest, WriteCreatesTheFileWithEveryByte) {
    std::string bytes("a\0b\r\n\xFF", 6);
    bytes += std::string(200000, 'x');
    const fs::path path = dir_ / "new.txt";
    std::string error;
    ASSERT_TRUE(write_file(path, bytes, error)) << error;
    EXPECT_EQ(text(path), bytes);
    EXPECT_EQ(names(), std::vector<std::string>{"new.txt"});
    const mode_t mask = ::umask(0);
    ::umask(mask);
    EXPECT_EQ(fs::status(path).permissions(), static_cast<fs::perms>(0644 & ~mask));
}

TEST_F(FileTest, WriteReplacesAnExistingFileWhole) {
    const fs::path path = write("old.txt", std::string(1000, 'o'));
    std::string error;
    ASSERT_TRUE(write_file(path, "new", error)) << error;
    EXPECT_EQ(text(path), "new");
    EXPECT_EQ(names(), std::vector<std::string>{"old.txt"});
}

// The attack: a link planted at PATH.tmp (the fixed temporary name lcc-conform used) had its
// target truncated and overwritten, then the link renamed into place.
TEST_F(FileTest, WriteNeverFollowsALinkPlantedAtATemporaryName) {
    const fs::path outside = write("outside", "precious");
    const fs::path path = dir_ / "backup.txt";
    fs::create_symlink(outside, dir_ / "backup.txt.tmp");
    std::string error;
    ASSERT_TRUE(write_file(path, "saved", error)) << error;
    EXPECT_EQ(text(outside), "precious");
    EXPECT_EQ(text(path), "saved");
    EXPECT_FALSE(fs::is_symlink(path));
    EXPECT_EQ(fs::read_symlink(dir_ / "backup.txt.tmp"), outside) << "left as it was";
    EXPECT_EQ(names(), (std::vector<std::string>{"backup.txt", "backup.txt.tmp", "outside"}));
}

TEST_F(FileTest, AStaleTemporaryFileOfACrashedRunBlocksNothing) {
    const fs::path stale = write("backup.txt.tmp", "half a backup");
    std::string error;
    ASSERT_TRUE(write_file(dir_ / "backup.txt", "saved", error)) << error;
    EXPECT_EQ(text(dir_ / "backup.txt"), "saved");
    EXPECT_EQ(text(stale), "half a backup");
}

// rename() replaces the link itself: the file it pointed to is never written.
TEST_F(FileTest, ALinkAtThePathIsReplacedAndItsTargetLeftAlone) {
    const fs::path outside = write("outside", "precious");
    const fs::path path = dir_ / "report.json";
    fs::create_symlink(outside, path);
    std::string error;
    ASSERT_TRUE(write_file(path, "{}", error)) << error;
    EXPECT_EQ(text(outside), "precious");
    EXPECT_FALSE(fs::is_symlink(path));
    EXPECT_EQ(text(path), "{}");
}

TEST_F(FileTest, WriteFailuresSayPathAndReasonAndLeaveNothing) {
    std::string error;
    const fs::path missing = dir_ / "missing" / "x.txt";
    EXPECT_FALSE(write_file(missing, "x", error));
    EXPECT_EQ(error, "cannot open " + missing.string() + " for writing: No such file or directory");
    // Even root cannot create a file under a path whose parent is not a directory.
    EXPECT_FALSE(write_file("/dev/null/x", "x", error));
    EXPECT_EQ(error, "cannot open /dev/null/x for writing: Not a directory");
    fs::create_directory(dir_ / "a-directory");
    EXPECT_FALSE(write_file(dir_ / "a-directory", "x", error));
    EXPECT_EQ(error, "cannot write " + (dir_ / "a-directory").string() + ": Is a directory");
    EXPECT_EQ(names(), std::vector<std::string>{"a-directory"}) << "the temporary file removed";
}

TEST_F(FileTest, AStreamIsWrittenInPlace) {
    std::string error;
    // Renaming over /dev/null would take it from every other process (root may write /dev).
    ASSERT_TRUE(write_file("/dev/null", "x", error)) << error;
    EXPECT_TRUE(fs::is_character_file("/dev/null"));
    const fs::path fifo = dir_ / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    ASSERT_GE(reader, 0);
    ASSERT_TRUE(write_file(fifo, "through", error)) << error;
    char got[16] = {};
    EXPECT_EQ(::read(reader, got, sizeof got), 7);
    EXPECT_EQ(std::string(got), "through");
    ::close(reader);
    EXPECT_TRUE(fs::is_fifo(fifo));
    EXPECT_EQ(names(), std::vector<std::string>{"fifo"});
}

// /dev/stdout and /dev/fd/N reach an open file through /proc: the file is written, and no link
// is replaced (a temporary file cannot even be made in /proc/self/fd).
TEST_F(FileTest, ANameThroughProcIsWrittenInPlace) {
    const fs::path out = write("stdout.txt", "earlier");
    const int fd = ::open(out.c_str(), O_WRONLY | O_CLOEXEC);
    ASSERT_GE(fd, 0);
    const fs::path through = "/proc/self/fd/" + std::to_string(fd);
    std::string error;
    ASSERT_TRUE(write_file(through, "report", error)) << error;
    EXPECT_EQ(text(out), "report");
    const fs::path like_dev_stdout = dir_ / "stdout-link";
    fs::create_symlink(through, like_dev_stdout);
    ASSERT_TRUE(write_file(like_dev_stdout, "again", error)) << error;
    EXPECT_EQ(text(out), "again");
    EXPECT_TRUE(fs::is_symlink(like_dev_stdout));
    ::close(fd);
}

}  // namespace
}  // namespace olcb::base
