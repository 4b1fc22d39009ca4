// `lcc-conform decode`: a candump -L or GridConnect log read back one decoded line per frame, with
// the lines that are not classic CAN frames skipped, counted and said on stderr.
#include "conformance/app/log_decode.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "memory/memory_config_codec.hpp"
#include "support/temp_files.hpp"

namespace olcb::conform {
namespace {

// The lines of a text, without their newlines.
std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

struct Decoded {
    DecodeCounts counts;
    std::vector<std::string> out;
    std::string err;
};

Decoded decode(const std::string& log) {
    std::istringstream in(log);
    std::ostringstream out;
    std::ostringstream err;
    Decoded d;
    d.counts = decode_log(in, out, err);
    d.out = lines_of(out.str());
    d.err = err.str();
    return d;
}

// What candump -L writes on a bus with OpenLCB traffic, a non-OpenLCB device and a CAN FD node.
constexpr const char* kCandumpLog =
    "(1700000000.000100) vcan0 10701343#050101012200\n"      // AMD: alias 343 is 05.01.01.01.22.00
    "(1700000000.000200) vcan0 123#DEADBEEF\n"               // standard frame
    "(1700000000.000300) vcan0 123#R\n"                      // standard remote (RTR) frame
    "(1700000000.000400) vcan0 123##1112233\n"               // CAN FD
    "(1700000000.000500) vcan0 20000080#0000000000000000\n"  // error frame (CAN_ERR_FLAG)
    "this is not a frame\n"
    "(1700000000.000600) can1 19490343#\n"    // Verify Node ID Global
    "(1700000000.000700) can1 19490343#R\n";  // extended remote frame

TEST(LogDecode, ACandumpLogGivesOneLinePerClassicFrameAndSkipsTheRest) {
    const Decoded d = decode(kCandumpLog);
    EXPECT_EQ(d.counts.frames, 5u);
    EXPECT_EQ(d.counts.skipped, 3u);
    ASSERT_EQ(d.out.size(), 5u) << d.err;
    // The timestamp and interface as the log has them, then the monitor's line.
    EXPECT_TRUE(d.out[0].starts_with("1700000000.000100 vcan0 :X10701343N050101012200; "))
        << d.out[0];
    EXPECT_TRUE(contains(d.out[0], "05.01.01.01.22.00")) << d.out[0];
    EXPECT_TRUE(d.out[1].starts_with("1700000000.000200 vcan0 :S123NDEADBEEF;")) << d.out[1];
    EXPECT_TRUE(contains(d.out[1], "standard frame")) << d.out[1];
    EXPECT_TRUE(d.out[2].starts_with("1700000000.000300 vcan0 :S123R;")) << d.out[2];
    EXPECT_TRUE(contains(d.out[2], "standard frame")) << d.out[2];
    EXPECT_TRUE(d.out[3].starts_with("1700000000.000600 can1 :X19490343N;")) << d.out[3];
    EXPECT_TRUE(contains(d.out[3], "Verify Node ID Global")) << d.out[3];
    EXPECT_TRUE(d.out[4].starts_with("1700000000.000700 can1 :X19490343R;")) << d.out[4];
    EXPECT_TRUE(contains(d.out[4], "remote frame")) << d.out[4];
}

TEST(LogDecode, EverySkippedLineIsNamedWithItsNumberAndReasonThenTheSummary) {
    const std::vector<std::string> err = lines_of(decode(kCandumpLog).err);
    ASSERT_EQ(err.size(), 4u) << decode(kCandumpLog).err;
    EXPECT_TRUE(err[0].starts_with("decode: line 4: CAN FD frame")) << err[0];
    EXPECT_EQ(err[1], "decode: line 5: CAN error frame");
    EXPECT_EQ(err[2], "decode: line 6: neither a candump -L nor a GridConnect frame");
    EXPECT_EQ(err[3], "decode: 5 frames, 3 lines skipped");
}

TEST(LogDecode, AGridConnectLogIsDecodedToTheMonitorsLines) {
    const Decoded d = decode(
        ":X10701343N050101012200;\n"
        "  :x19490343n;  \n"  // any case, surrounding blanks
        ":X1949;\n"           // no N or R
        ":X19170343N050101012200;\n");
    EXPECT_EQ(d.counts.frames, 3u);
    EXPECT_EQ(d.counts.skipped, 1u);
    ASSERT_EQ(d.out.size(), 3u);
    EXPECT_TRUE(d.out[0].starts_with(":X10701343N050101012200; ")) << d.out[0];
    EXPECT_TRUE(contains(d.out[0], "05.01.01.01.22.00")) << d.out[0];
    EXPECT_TRUE(d.out[1].starts_with(":X19490343N; ")) << d.out[1];
    EXPECT_TRUE(contains(d.out[2], "Verified Node ID")) << d.out[2];
    EXPECT_TRUE(contains(d.err, "decode: line 3: not a valid GridConnect frame\n")) << d.err;
    EXPECT_TRUE(contains(d.err, "decode: 3 frames, 1 lines skipped\n")) << d.err;
}

TEST(LogDecode, FormatsAreFoundPerLineAndBlankLinesAndCrlfAreIgnored) {
    const Decoded d = decode(
        "(0000000012.000001) vcan0 19490343#\r\n"
        "\r\n"
        "\n"
        ":X19490343N;\r\n"
        "(0000000012.000002) vcan0 19490343#");  // no final newline
    EXPECT_EQ(d.counts.frames, 3u);
    EXPECT_EQ(d.counts.skipped, 0u);
    ASSERT_EQ(d.out.size(), 3u);
    EXPECT_TRUE(d.out[0].starts_with("0000000012.000001 vcan0 :X19490343N;")) << d.out[0];
    EXPECT_TRUE(d.out[1].starts_with(":X19490343N;")) << d.out[1];
    EXPECT_TRUE(d.out[2].starts_with("0000000012.000002 vcan0 ")) << d.out[2];
    for (const std::string& line : d.out) EXPECT_FALSE(contains(line, "\r")) << line;
    EXPECT_EQ(d.err, "decode: 3 frames, 0 lines skipped\n");
}

TEST(LogDecode, ALineLongerThanTheLimitIsSkippedAndTheNextOneRead) {
    std::string log(kMaxLogLine + 1, 'x');
    log.push_back('\n');
    log.append(kMaxLogLine, 'x');  // garbage, but not too long
    log.append("\n:X19490343N;\n");
    const Decoded d = decode(log);
    EXPECT_EQ(d.counts.frames, 1u);
    EXPECT_EQ(d.counts.skipped, 2u);
    EXPECT_TRUE(contains(d.err, "decode: line 1: longer than 4096 characters")) << d.err;
    EXPECT_TRUE(contains(d.err, "decode: line 2: neither")) << d.err;
    ASSERT_EQ(d.out.size(), 1u);
    EXPECT_TRUE(d.out[0].starts_with(":X19490343N;"));
}

TEST(LogDecode, AtMostTwentySkippedLinesAreShownThenHowManyMore) {
    std::string log;
    for (int i = 0; i < 25; ++i) log += "garbage\n";
    const std::vector<std::string> err = lines_of(decode(log).err);
    ASSERT_EQ(err.size(), kMaxSkipReports + 2);
    EXPECT_EQ(err[0], "decode: line 1: neither a candump -L nor a GridConnect frame");
    EXPECT_TRUE(err[kMaxSkipReports - 1].starts_with("decode: line 20: ")) << err[19];
    EXPECT_EQ(err[kMaxSkipReports], "decode: ... 5 more skipped lines");
    EXPECT_EQ(err[kMaxSkipReports + 1], "decode: 0 frames, 25 lines skipped");
}

TEST(LogDecode, AMemoryConfigurationDatagramIsDescribed) {
    // Read 64 bytes at 0 of space FF (the CDI), one datagram frame from alias 343 to 22A.
    const std::array<std::uint8_t, 7> read = {0x20, 0x43, 0x00, 0x00, 0x00, 0x00, 0x40};
    const Decoded d = decode("(1700000000.000100) vcan0 1A22A343#20430000000040\n");
    ASSERT_EQ(d.out.size(), 1u) << d.err;
    EXPECT_TRUE(contains(d.out[0], memory::describe(read))) << d.out[0];
}

TEST(LogDecode, ControlBytesOfTheInterfaceNameNeverReachTheOutput) {
    const Decoded d = decode("(1700000000.000100) vc\x1b[2Jan0 19490343#\n");
    ASSERT_EQ(d.out.size(), 1u) << d.err;
    EXPECT_TRUE(d.out[0].starts_with("1700000000.000100 vc?[2Jan0 :X19490343N;")) << d.out[0];
}

TEST(LogDecode, TheCommandReadsAFileOrStandardInputAndSaysWhyAFileCannotBeRead) {
    const test_support::TempDir dir("log-decode");
    const std::string file = (dir.path() / "bus.log").string();
    std::ofstream(file) << kCandumpLog;
    std::istringstream no_input;
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(run_decode(file, no_input, out, err), 0);
    EXPECT_EQ(lines_of(out.str()).size(), 5u);
    EXPECT_TRUE(contains(err.str(), "decode: 5 frames, 3 lines skipped\n")) << err.str();

    std::istringstream input(":X19490343N;\n");
    std::ostringstream stdin_out;
    std::ostringstream stdin_err;
    EXPECT_EQ(run_decode("-", input, stdin_out, stdin_err), 0);
    EXPECT_TRUE(stdin_out.str().starts_with(":X19490343N;")) << stdin_out.str();

    for (const std::string& bad : {(dir.path() / "missing.log").string(), dir.str()}) {
        std::ostringstream bad_out;
        std::ostringstream bad_err;
        EXPECT_EQ(run_decode(bad, no_input, bad_out, bad_err), 2) << bad;
        EXPECT_TRUE(bad_err.str().starts_with("lcc-conform: cannot read " + bad + ": "))
            << bad_err.str();
        EXPECT_EQ(bad_out.str(), "");
    }
}

}  // namespace
}  // namespace olcb::conform
