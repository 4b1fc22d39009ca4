// lcc-cdi and the 16 MiB CDI limit (issue 31): a larger file is refused before it is read, with
// one line and exit status 1, and a FIFO or device is read no further than the limit.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "cdi/schema_validator.hpp"
#include "support/endless_fifo.hpp"
#include "support/run_shell.hpp"
#include "support/temp_files.hpp"

namespace {

namespace fs = std::filesystem;
using olcb::test_support::TempDir;

using RunResult = olcb::test_support::ShellResult;

// Runs a shell command line with stderr merged; `timeout` turns a hang into exit status 124.
RunResult shell(const std::string& line) {
    return olcb::test_support::run_shell(line + " 2>&1");
}

const std::string kLccCdi = std::string("timeout 30 ") + LCC_CDI_PATH;

RunResult lcc_cdi(const std::string& args) {
    return shell(kLccCdi + " " + args);
}

// A sparse file of `size` bytes whose first bytes are a valid CDI: only its size is wrong.
fs::path sized_cdi(const TempDir& dir, std::uintmax_t size) {
    const fs::path path = dir.path() / "big.xml";
    std::ofstream(path, std::ios::binary)
        << "<?xml version=\"1.0\"?>\n<cdi><segment space=\"253\"><int size=\"1\"/></segment></cdi>";
    fs::resize_file(path, size);
    return path;
}

TEST(LccCdiLimit, EveryCommandRefusesAFileOverTheLimitInOneLine) {
    const TempDir dir("lcc-cdi-limit");
    const fs::path path = sized_cdi(dir, 100'000'000);
    const std::string line = "cannot read " + path.string() +
                             ": 100000000 bytes, over the CDI limit of 16777216 bytes\n";
    for (const char* command : {"validate", "layout", "render", "render --html"}) {
        const auto start = std::chrono::steady_clock::now();
        const RunResult r = lcc_cdi(std::string(command) + " " + path.string());
        // Reading and parsing 100 MB took seconds; a refusal by size is a process start.
        EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2)) << command;
        EXPECT_EQ(r.status, 1) << command;
        EXPECT_EQ(r.out, "error: " + line) << command;
    }
}

TEST(LccCdiLimit, AFileOfExactlyTheLimitIsRead) {
    const TempDir dir("lcc-cdi-limit");
    const fs::path path = sized_cdi(dir, olcb::cdi::kMaxCdiBytes);
    // Read, not refused: what it reports is its content (the NUL padding), not its size.
    const RunResult r = lcc_cdi("layout " + path.string());
    EXPECT_EQ(r.out.find("over the CDI limit"), std::string::npos) << r.out;
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out, "seg0.child0\tint\tspace 253\taddress 0\tsize 1\n");
}

TEST(LccCdiLimit, ADeviceWithoutEndIsRefusedNotReadForever) {
    const RunResult r = lcc_cdi("validate /dev/zero");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out,
              "error: cannot read /dev/zero: more than 16777216 bytes, over the CDI limit "
              "of 16777216 bytes\n");
}

TEST(LccCdiLimit, AFifoIsReadUpToTheLimit) {
    const TempDir dir("lcc-cdi-limit");
    const fs::path fifo = dir.path() / "cdi.fifo";
    RunResult r;
    {
        const olcb::test_support::EndlessFifo endless(fifo, 65536);
        ASSERT_TRUE(endless.made());
        r = lcc_cdi("layout " + fifo.string());
    }
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(r.out, "error: cannot read " + fifo.string() +
                         ": more than 16777216 bytes, over the CDI limit of 16777216 bytes\n");
}

TEST(LccCdiLimit, ACdiThroughAPipeIsHandledLikeAFile) {
    const fs::path cdi = fs::path(OLCB_SOURCE_DIR) / "scenarios" / "default.xml";
    const RunResult from_file = lcc_cdi("layout " + cdi.string());
    std::string piped = "cat " + cdi.string();
    piped += " | " + kLccCdi + " layout /dev/stdin";  // its stdin a pipe, not the file
    const RunResult from_pipe = shell(piped);
    ASSERT_EQ(from_file.status, 0);
    EXPECT_EQ(from_pipe.status, 0);
    EXPECT_EQ(from_pipe.out, from_file.out);
}

TEST(LccCdiLimit, TheHelpNamesTheLimit) {
    const RunResult r = lcc_cdi("--help");
    EXPECT_EQ(r.status, 0);
    EXPECT_NE(r.out.find("A FILE over 16 MiB (the CDI limit) is refused unread"), std::string::npos)
        << r.out;
}

}  // namespace
