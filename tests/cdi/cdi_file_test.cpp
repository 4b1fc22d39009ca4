// Reading a CDI file under the size limit (cdi/cdi_file.hpp): regular files refused by their size,
// FIFOs and devices refused once they give one byte past it, never read to their end.
#include "cdi/cdi_file.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "support/endless_fifo.hpp"
#include "support/temp_files.hpp"

namespace olcb::cdi {
namespace {

namespace fs = std::filesystem;
using test_support::TempDir;

void write(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

TEST(CdiFile, ReadsAFileOfExactlyTheLimit) {
    const TempDir dir("cdi-file");
    const std::string text = "<cdi/>\n";
    write(dir.path() / "a.xml", text);
    std::string error;
    const auto bytes = read_cdi_file(dir.path() / "a.xml", text.size(), error);
    ASSERT_TRUE(bytes) << error;
    EXPECT_EQ(*bytes, text);
    EXPECT_EQ(error, "");
}

TEST(CdiFile, RefusesARegularFileOneBytePastTheLimit) {
    const TempDir dir("cdi-file");
    write(dir.path() / "a.xml", "<cdi/>\n");
    std::string error;
    EXPECT_FALSE(read_cdi_file(dir.path() / "a.xml", 6, error));
    EXPECT_EQ(error, "cannot read " + (dir.path() / "a.xml").string() +
                         ": 7 bytes, over the CDI limit of 6 bytes");
}

TEST(CdiFile, RefusesA100MegabyteFileByItsSizeWithoutReadingIt) {
    const TempDir dir("cdi-file");
    const fs::path path = dir.path() / "huge.xml";
    write(path, "");
    fs::resize_file(path, 100'000'000);  // sparse: nothing to read costs nothing to make
    const auto start = std::chrono::steady_clock::now();
    std::string error;
    EXPECT_FALSE(read_cdi_file(path, error));
    // Reading 100 MB takes far longer; refusing by fstat is immediate.
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(50));
    EXPECT_NE(error.find(": 100000000 bytes, over the CDI limit of 16777216 bytes"),
              std::string::npos)
        << error;
}

TEST(CdiFile, TheDefaultLimitIsKMaxCdiBytes) {
    const TempDir dir("cdi-file");
    const fs::path path = dir.path() / "limit.xml";
    write(path, "");
    fs::resize_file(path, kMaxCdiBytes);
    std::string error;
    const auto bytes = read_cdi_file(path, error);
    ASSERT_TRUE(bytes) << error;
    EXPECT_EQ(bytes->size(), kMaxCdiBytes);
    fs::resize_file(path, kMaxCdiBytes + 1);
    EXPECT_FALSE(read_cdi_file(path, error));
}

TEST(CdiFile, ADeviceThatNeverEndsIsReadOnlyToOneBytePastTheLimit) {
    std::string error;
    EXPECT_FALSE(read_cdi_file("/dev/zero", 1000, error));
    EXPECT_EQ(error,
              "cannot read /dev/zero: more than 1000 bytes, over the CDI limit of 1000 bytes");
}

// A FIFO fed by a writer that stops only when the reader has gone: the reader must give up.
TEST(CdiFile, AFifoFedWithoutEndIsRefused) {
    const TempDir dir("cdi-file");
    std::optional<std::string> bytes;
    std::string error;
    {
        const olcb::test_support::EndlessFifo fifo(dir.path() / "fifo");
        ASSERT_TRUE(fifo.made());
        bytes = read_cdi_file(fifo.path(), 100'000, error);
    }
    EXPECT_FALSE(bytes);
    EXPECT_NE(error.find(": more than 100000 bytes, over the CDI limit"), std::string::npos)
        << error;
}

TEST(CdiFile, AFifoUnderTheLimitIsReadToItsEnd) {
    const TempDir dir("cdi-file");
    const fs::path fifo = dir.path() / "fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string text(200'000, 'y');  // several pipe buffers
    std::thread writer([&fifo, &text] { write(fifo, text); });
    std::string error;
    const auto bytes = read_cdi_file(fifo, text.size(), error);
    writer.join();
    ASSERT_TRUE(bytes) << error;
    EXPECT_EQ(*bytes, text);
}

TEST(CdiFile, MissingFilesAndDirectoriesSayWhy) {
    const TempDir dir("cdi-file");
    std::string error;
    EXPECT_FALSE(read_cdi_file(dir.path() / "none.xml", error));
    EXPECT_EQ(error,
              "cannot read " + (dir.path() / "none.xml").string() + ": No such file or directory");
    EXPECT_FALSE(read_cdi_file(dir.path(), error));
    EXPECT_EQ(error, "cannot read " + dir.str() + ": Is a directory");
}

}  // namespace
}  // namespace olcb::cdi
