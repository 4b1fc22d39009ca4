#include "openlcb/traffic_log.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

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

}  // namespace
}  // namespace olcb
