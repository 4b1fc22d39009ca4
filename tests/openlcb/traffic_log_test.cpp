#include "openlcb/traffic_log.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "openlcb/candump_log.hpp"
#include "openlcb/gridconnect.hpp"

namespace olcb {
namespace {

CanFrame verified_node_id() {
    CanFrame f;
    f.id = 0x19170343;
    f.len = 6;
    f.data = {0x05, 0x01, 0x01, 0x01, 0x22, 0x00};
    return f;
}

TEST(TrafficLog, WritesGridConnectAndCandumpLinesToStreams) {
    std::int64_t now = 1700000000000000;
    TrafficLog log([&] { return std::chrono::microseconds(now); });
    std::ostringstream gc, cd;
    log.add_gridconnect_stream(gc);
    log.add_candump_stream(cd, "can0");
    CanFrame verify;
    verify.id = 0x19490343;
    log.record(verify);
    now += 1500;
    log.record(verified_node_id());
    EXPECT_EQ(gc.str(), ":X19490343N;\n:X19170343N050101012200;\n");
    EXPECT_EQ(cd.str(),
              "(1700000000.000000) can0 19490343#\n"
              "(1700000000.001500) can0 19170343#050101012200\n");
    EXPECT_TRUE(log.ok());
    EXPECT_EQ(log.frames_recorded(), 2u);
}

TEST(TrafficLog, FilesCanBeReadBackByTheParsers) {
    const auto dir = std::filesystem::temp_directory_path();
    const auto gc_path = dir / ("olcb_traffic_gc_" + std::to_string(::getpid()) + ".log");
    const auto cd_path = dir / ("olcb_traffic_cd_" + std::to_string(::getpid()) + ".log");
    std::filesystem::remove(gc_path);
    std::filesystem::remove(cd_path);
    {
        TrafficLog log;
        ASSERT_TRUE(log.add_gridconnect_file(gc_path.string()));
        ASSERT_TRUE(log.add_candump_file(cd_path.string()));
        log.record(verified_node_id(), std::chrono::microseconds(42));
    }
    std::ifstream gc(gc_path), cd(cd_path);
    std::string gc_line, cd_line;
    ASSERT_TRUE(std::getline(gc, gc_line));
    ASSERT_TRUE(std::getline(cd, cd_line));
    EXPECT_EQ(gridconnect::parse_frame(gc_line), verified_node_id());
    const auto entry = candump::parse(cd_line);
    ASSERT_TRUE(entry);
    EXPECT_EQ(entry->frame, verified_node_id());
    EXPECT_EQ(entry->timestamp, std::chrono::microseconds(42));
    EXPECT_EQ(entry->interface, "vcan0");
    std::filesystem::remove(gc_path);
    std::filesystem::remove(cd_path);
}

TEST(TrafficLog, ReportsAnUnopenableFile) {
    TrafficLog log;
    EXPECT_FALSE(log.add_gridconnect_file("/nonexistent-dir/x.log"));
    EXPECT_FALSE(log.add_candump_file("/nonexistent-dir/x.log"));
    log.record(verified_node_id());  // no outputs: nothing happens
    EXPECT_TRUE(log.ok());
}

namespace fs = std::filesystem;

// A fresh path in the temp directory, with no FILE or FILE.1 left from an earlier run.
fs::path fresh_log(const std::string& name) {
    auto path = fs::temp_directory_path() /
                ("olcb_rotate_" + name + "_" + std::to_string(::getpid()) + ".log");
    fs::remove(path);
    fs::remove(path.string() + ".1");
    return path;
}

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Line i, 10 bytes with its newline.
std::string line(int i) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "line %04d\n", i);
    return buf;
}

std::string lines(int first, int last) {
    std::string out;
    for (int i = first; i <= last; ++i) out += line(i);
    return out;
}

TEST(RotatingFile, RotatesToDotOneEachTimeTheBoundWouldBePassed) {
    const auto path = fresh_log("twice");
    const std::string old_path = path.string() + ".1";
    RotatingFile file;
    ASSERT_TRUE(file.open(path.string(), 30));
    for (int i = 0; i < 3; ++i) file.write(line(i));
    EXPECT_EQ(file.rotations(), 0u) << "exactly at the bound is still within it";
    EXPECT_FALSE(fs::exists(old_path));
    file.write(line(3));
    EXPECT_EQ(file.rotations(), 1u);
    EXPECT_EQ(slurp(old_path), lines(0, 2));
    EXPECT_EQ(slurp(path), lines(3, 3));
    for (int i = 4; i < 7; ++i) file.write(line(i));
    EXPECT_EQ(file.rotations(), 2u);
    EXPECT_EQ(fs::file_size(old_path), 30u);
    EXPECT_EQ(fs::file_size(path), 10u);
    EXPECT_EQ(slurp(old_path), lines(3, 5)) << "the older FILE.1 was replaced";
    EXPECT_EQ(slurp(path), lines(6, 6));
    EXPECT_EQ(file.size(), 10u);
    EXPECT_TRUE(file.ok());
    fs::remove(path);
    fs::remove(old_path);
}

// simnode's default bound (64 MiB) must not make it rename a FIFO or device given as the file.
TEST(RotatingFile, AFifoIsNeverRotated) {
    const auto path = fresh_log("fifo");
    ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
    const int reader = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);  // lets the writer open
    ASSERT_GE(reader, 0);
    {
        RotatingFile file;
        ASSERT_TRUE(file.open(path.string(), 30));
        for (int i = 0; i < 7; ++i) file.write(line(i));
        EXPECT_EQ(file.rotations(), 0u);
        EXPECT_TRUE(file.ok());
    }
    EXPECT_TRUE(fs::is_fifo(path));
    EXPECT_FALSE(fs::exists(path.string() + ".1"));
    std::array<char, 128> got{};
    EXPECT_EQ(::read(reader, got.data(), got.size()), 70) << "every line reached the reader";
    ::close(reader);
    fs::remove(path);
}

TEST(RotatingFile, ZeroNeverRotates) {
    const auto path = fresh_log("zero");
    {
        RotatingFile file;
        ASSERT_TRUE(file.open(path.string()));
        for (int i = 0; i < 100; ++i) file.write(line(i));
        EXPECT_EQ(file.rotations(), 0u);
    }
    EXPECT_EQ(slurp(path), lines(0, 99));
    EXPECT_FALSE(fs::exists(path.string() + ".1"));
    fs::remove(path);
}

TEST(RotatingFile, AnExistingFileCountsAndALongLineStaysWhole) {
    const auto path = fresh_log("existing");
    std::ofstream(path) << lines(0, 1);
    RotatingFile file;
    ASSERT_TRUE(file.open(path.string(), 25));
    EXPECT_EQ(file.size(), 20u);
    file.write(line(2));
    EXPECT_EQ(file.rotations(), 1u);
    EXPECT_EQ(slurp(path.string() + ".1"), lines(0, 1));
    const std::string long_line(40, 'x');
    file.write(long_line);
    EXPECT_EQ(file.rotations(), 2u);
    EXPECT_EQ(slurp(path), long_line) << "longer than the bound: alone in its file, not split";
    fs::remove(path);
    fs::remove(path.string() + ".1");
}

TEST(RotatingFile, OpenFailsForAMissingDirectory) {
    RotatingFile file;
    EXPECT_FALSE(file.open("/nonexistent-dir/x.log", 10));
    EXPECT_FALSE(file.is_open());
    file.write("ignored\n");  // harmless
}

TEST(TrafficLog, CandumpFileRotatesAndKeepsTheOrder) {
    const auto path = fresh_log("candump");
    const std::string old_path = path.string() + ".1";
    // One line is "(0000000000.000001) vcan0 19170343#050101012200\n", 48 bytes.
    const std::uint64_t max = 100;
    TrafficLog log;
    ASSERT_TRUE(log.add_candump_file(path.string(), "vcan0", max));
    for (int i = 1; i <= 7; ++i) log.record(verified_node_id(), std::chrono::microseconds(i));
    EXPECT_EQ(log.rotations(), 3u);  // 2 lines per file: 1-2, 3-4, 5-6, then 7
    EXPECT_TRUE(log.ok());
    EXPECT_LE(fs::file_size(path), max);
    EXPECT_LE(fs::file_size(old_path), max);
    std::vector<std::int64_t> stamps;
    for (const auto& p : {fs::path(old_path), path}) {
        std::ifstream in(p);
        for (std::string text; std::getline(in, text);) {
            const auto entry = candump::parse(text);
            ASSERT_TRUE(entry) << text;
            stamps.push_back(entry->timestamp.count());
        }
    }
    EXPECT_EQ(stamps, (std::vector<std::int64_t>{5, 6, 7}));
    fs::remove(path);
    fs::remove(old_path);
}

}  // namespace
}  // namespace olcb
