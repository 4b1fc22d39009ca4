#include "base/bounded_read.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>

#include "support/temp_files.hpp"

namespace olcb::base {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

fs::path write(const fs::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
}

TEST(BoundedRead, ARegularFileUpToTheLimitIsReadWhole) {
    const test_support::TempDir dir("olcb-bounded-read");
    std::string error;
    EXPECT_EQ(read_regular_file(write(dir.path() / "a", "12345"), 5, error), "12345") << error;
    EXPECT_EQ(read_regular_file(write(dir.path() / "e", ""), 0, error), "") << error;
    const std::string big(200'000, 'x');  // several reads
    EXPECT_EQ(read_regular_file(write(dir.path() / "b", big), big.size(), error), big) << error;
}

TEST(BoundedRead, AFileOverTheLimitIsRefusedBeforeReading) {
    const test_support::TempDir dir("olcb-bounded-read");
    const fs::path big = write(dir.path() / "big", "<cdi>");
    fs::resize_file(big, 100'000'000'000);  // sparse: reading it would take minutes
    std::string error;
    EXPECT_FALSE(read_regular_file(big, 16, error));
    EXPECT_EQ(error, big.string() + " is 100000000000 bytes, over the limit of 16 bytes");
    EXPECT_FALSE(read_regular_file(write(dir.path() / "six", "123456"), 5, error));
    EXPECT_EQ(error, (dir.path() / "six").string() + " is 6 bytes, over the limit of 5 bytes");
}

TEST(BoundedRead, TheLimitHoldsWhileReadingAFileWhoseSizeSaysNothing) {
    // /proc files are regular and 0 bytes by their size, yet hold text.
    std::string error;
    const auto whole = read_regular_file("/proc/self/status", 1 << 20, error);
    ASSERT_TRUE(whole) << error;
    ASSERT_GT(whole->size(), 100u);
    EXPECT_FALSE(read_regular_file("/proc/self/status", 100, error));
    EXPECT_EQ(error, "/proc/self/status is over the limit of 100 bytes");
}

TEST(BoundedRead, DevicesAndDirectoriesAreRefusedUnread) {
    const test_support::TempDir dir("olcb-bounded-read");
    std::string error;
    EXPECT_FALSE(read_regular_file("/dev/zero", 1 << 20, error));
    EXPECT_EQ(error, "cannot read /dev/zero: not a regular file");
    EXPECT_FALSE(read_regular_file(dir.path(), 1 << 20, error));
    EXPECT_EQ(error, "cannot read " + dir.str() + ": not a regular file");
    EXPECT_FALSE(read_regular_file(dir.path() / "none", 1 << 20, error));
    EXPECT_EQ(error,
              "cannot read " + (dir.path() / "none").string() + ": No such file or directory");
}

TEST(BoundedRead, AFifoWithoutAWriterIsRefusedAtOnce) {
    const test_support::TempDir dir("olcb-bounded-read");
    const fs::path fifo = dir.path() / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    auto read = std::async(std::launch::async, [&fifo] {
        std::string error;
        const auto bytes = read_regular_file(fifo, 1 << 20, error);
        return bytes ? std::string("read ") + std::to_string(bytes->size()) : error;
    });
    if (read.wait_for(1s) != std::future_status::ready) {
        // Blocked in open(): a writer that comes and goes lets it return, so the test ends.
        std::ofstream(fifo) << "";
        FAIL() << "the read blocked on a FIFO without a writer: " << read.get();
    }
    EXPECT_EQ(read.get(), "cannot read " + fifo.string() + ": not a regular file");
}

}  // namespace
}  // namespace olcb::base
