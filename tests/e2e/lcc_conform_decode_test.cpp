// `lcc-conform decode FILE` as a user runs it on a candump -L log of their bus: decoded lines on
// standard output, the skipped lines and the summary on standard error, exit 0 once the file was
// read and 2 when it cannot be; and every frame of a log simnode wrote is decoded.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "e2e/conform_util.hpp"

#if defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

std::size_t count_lines(const std::string& text) {
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// lcc-conform decode with its input on `shell_redirects` ("$1" is `in`, "$2" the stderr file);
// exit status, stdout and stderr.
struct DecodeRun {
    int code = 0;
    std::string out;
    std::string err;
};
DecodeRun decode(const std::string& what, const std::string& shell_redirects,
                 const std::string& in) {
    const TempDir dir("lcc-conform-decode-e2e");
    const std::string err = (dir.path() / "stderr").string();
    const auto [code, out] = run_program(
        "/bin/sh",
        {"-c", "exec \"$0\" decode " + what + " " + shell_redirects, LCC_CONFORM_PATH, in, err});
    return {code, out, read_text(err)};
}

constexpr const char* kLog =
    "(1700000000.000100) vcan0 10701343#050101012200\n"
    "(1700000000.000200) vcan0 123##1112233\n"
    "(1700000000.000300) vcan0 19490343#\n";

TEST(LccConformDecodeE2e, ACandumpLogIsDecodedOnStdoutAndSummedUpOnStderr) {
    const TempDir dir("lcc-conform-decode-log");
    const std::string log = (dir.path() / "bus.log").string();
    std::ofstream(log) << kLog;
    const DecodeRun r = decode("\"$1\"", "2>\"$2\"", log);
    EXPECT_EQ(r.code, 0) << r.out << r.err;
    EXPECT_EQ(count_lines(r.out), 2u) << r.out;
    EXPECT_NE(r.out.find("1700000000.000100 vcan0 :X10701343N050101012200; "), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("05.01.01.01.22.00"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("decode: line 2: CAN FD frame"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("decode: 2 frames, 1 lines skipped\n"), std::string::npos) << r.err;

    const DecodeRun piped = decode("-", "<\"$1\" 2>\"$2\"", log);  // "-": standard input
    EXPECT_EQ(piped.code, 0) << piped.err;
    EXPECT_EQ(piped.out, r.out);
    EXPECT_EQ(piped.err, r.err);
}

TEST(LccConformDecodeE2e, AFileThatCannotBeOpenedIsAUsageErrorWithTheSystemsReason) {
    const TempDir dir("lcc-conform-decode-missing");
    const std::string missing = (dir.path() / "missing.log").string();
    const DecodeRun r = decode("\"$1\"", "2>\"$2\"", missing);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "lcc-conform: cannot read " + missing + ": No such file or directory\n");

    const DecodeRun no_file = decode("", "2>\"$2\"", missing);
    EXPECT_EQ(no_file.code, 2) << no_file.err;
    EXPECT_NE(no_file.err.find("decode wants exactly one FILE"), std::string::npos) << no_file.err;
}

#if defined(SIMNODE_PATH)
// What simnode --candump writes is what decode reads: every line one frame, none skipped.
TEST(LccConformDecodeE2e, EveryFrameOfASimnodeCandumpLogIsDecoded) {
    const TempDir dir("lcc-conform-decode-simnode");
    const std::string log = (dir.path() / "x.log").string();
    const auto [sim_code, sim_out] = run_program(
        SIMNODE_PATH,
        {"--scenario", source_path("scenarios/default.ini").string(), "--listen", "127.0.0.1:0",
         "--image-dir", (dir.path() / "img").string(), "--candump", log, "--run-for", "1"});
    ASSERT_EQ(sim_code, 0) << sim_out;
    const std::size_t frames = count_lines(read_text(log));
    ASSERT_GT(frames, 0u) << "simnode logged no frame";
    const DecodeRun r = decode("\"$1\"", "2>\"$2\"", log);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(count_lines(r.out), frames) << r.out;
    EXPECT_EQ(r.err, "decode: " + std::to_string(frames) + " frames, 0 lines skipped\n");
    EXPECT_NE(r.out.find(" Initialization Complete"), std::string::npos) << r.out;
}
#endif

TEST(LccConformDecodeE2e, TheUsageDocumentsDecodeAndItsOutput) {
    const auto [code, text] = conform({"--help"});
    EXPECT_EQ(code, 0);
    for (const char* s : {"decode FILE", "SECONDS.MICROS IFACE", "lines skipped"})
        EXPECT_NE(text.find(s), std::string::npos) << s << "\n" << text;
}

}  // namespace
}  // namespace olcb::e2e

#endif
