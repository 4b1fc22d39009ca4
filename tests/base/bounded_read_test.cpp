#include "base/bounded_read.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <optional>
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

// As simnode reads: streams refused.
std::optional<std::string> read_regular(const fs::path& path, std::size_t max_bytes,
                                        std::string& error) {
    return read_bounded_file(path, max_bytes, Streams::kRefuse, error);
}

TEST(BoundedRead, ARegularFileUpToTheLimitIsReadWhole) {
    const test_support::TempDir dir("olcb-bounded-read");
    std::string error;
    EXPECT_EQ(read_regular(write(dir.path() / "a", "12345"), 5, error), "12345") << error;
    EXPECT_EQ(read_regular(write(dir.path() / "e", ""), 0, error), "") << error;
    const std::string big(200'000, 'x');  // several reads
    EXPECT_EQ(read_regular(write(dir.path() / "b", big), big.size(), error), big) << error;
}

TEST(BoundedRead, AFileOverTheLimitIsRefusedBeforeReading) {
    const test_support::TempDir dir("olcb-bounded-read");
    const fs::path big = write(dir.path() / "big", "<cdi>");
    fs::resize_file(big, 100'000'000'000);  // sparse: reading it would take minutes
    std::string error;
    EXPECT_FALSE(read_regular(big, 16, error));
    EXPECT_EQ(error,
              "cannot read " + big.string() + ": 100000000000 bytes, over the limit of 16 bytes");
    EXPECT_FALSE(read_regular(write(dir.path() / "six", "123456"), 5, error));
    EXPECT_EQ(error, "cannot read " + (dir.path() / "six").string() +
                         ": 6 bytes, over the limit of 5 bytes");
}

TEST(BoundedRead, TheLimitHoldsWhileReadingAFileWhoseSizeSaysNothing) {
    // /proc files are regular and 0 bytes by their size, yet hold text.
    std::string error;
    const auto whole = read_regular("/proc/self/status", 1 << 20, error);
    ASSERT_TRUE(whole) << error;
    ASSERT_GT(whole->size(), 100u);
    EXPECT_FALSE(read_regular("/proc/self/status", 100, error));
    EXPECT_EQ(error,
              "cannot read /proc/self/status: more than 100 bytes, over the limit of 100 bytes");
}

TEST(BoundedRead, DevicesAndDirectoriesAreRefusedUnread) {
    const test_support::TempDir dir("olcb-bounded-read");
    std::string error;
    EXPECT_FALSE(read_regular("/dev/zero", 1 << 20, error));
    EXPECT_EQ(error, "cannot read /dev/zero: not a regular file");
    EXPECT_FALSE(read_regular(dir.path(), 1 << 20, error));
    EXPECT_EQ(error, "cannot read " + dir.str() + ": not a regular file");
    EXPECT_FALSE(read_regular(dir.path() / "none", 1 << 20, error));
    EXPECT_EQ(error,
              "cannot read " + (dir.path() / "none").string() + ": No such file or directory");
}

TEST(BoundedRead, AFifoWithoutAWriterIsRefusedAtOnce) {
    const test_support::TempDir dir("olcb-bounded-read");
    const fs::path fifo = dir.path() / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    auto read = std::async(std::launch::async, [&fifo] {
        std::string error;
        const auto bytes = read_regular(fifo, 1 << 20, error);
        return bytes ? std::string("read ") + std::to_string(bytes->size()) : error;
    });
    if (read.wait_for(1s) != std::future_status::ready) {
        // Blocked in open(): a writer that comes and goes lets it return, so the test ends.
        std::ofstream(fifo) << "";
        FAIL() << "the read blocked on a FIFO without a writer: " << read.get();
    }
    EXPECT_EQ(read.get(), "cannot read " + fifo.string() + ": not a regular file");
}

// Streams read within the bound (as lcc-cdi reads, tests/cdi/cdi_file_test.cpp for FIFOs).
TEST(BoundedRead, AStreamReadWithinTheBoundStopsOneBytePastIt) {
    std::string error;
    EXPECT_FALSE(read_bounded_file("/dev/zero", 1000, Streams::kReadBounded, error));
    EXPECT_EQ(error, "cannot read /dev/zero: more than 1000 bytes, over the limit of 1000 bytes");
    EXPECT_FALSE(read_bounded_file("/dev/zero", 10, Streams::kReadBounded, error, "CDI limit"));
    EXPECT_EQ(error, "cannot read /dev/zero: more than 10 bytes, over the CDI limit of 10 bytes");
    const auto empty = read_bounded_file("/dev/null", 10, Streams::kReadBounded, error);
    EXPECT_EQ(empty, "") << error;
}

TEST(BoundedRead, ADirectoryIsRefusedEvenWhenStreamsAreRead) {
    const test_support::TempDir dir("olcb-bounded-read");
    std::string error;
    EXPECT_FALSE(read_bounded_file(dir.path(), 1 << 20, Streams::kReadBounded, error));
    EXPECT_EQ(error, "cannot read " + dir.str() + ": Is a directory");
}

}  // namespace
}  // namespace olcb::base
