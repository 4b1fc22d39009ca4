#include "openlcb/monitor.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "openlcb/gridconnect.hpp"

namespace olcb {
namespace {

// Feeds GridConnect frames; returns the lines produced.
std::vector<std::string> run(Monitor& monitor, const std::vector<std::string>& frames) {
    std::vector<std::string> lines;
    for (const auto& text : frames) {
        const auto frame = gridconnect::parse_frame(text);
        EXPECT_TRUE(frame) << text;
        if (!frame) continue;
        if (auto line = monitor.decode(*frame)) lines.push_back(*line);
    }
    return lines;
}

// The 64-byte CDI read reply of the fact sheet's worked example (70 datagram bytes).
const std::vector<std::string> kReadReply = {
    ":X1B12C343N2053000000003C3F;", ":X1C12C343N786D6C2076657273;", ":X1C12C343N696F6E3D22312E30;",
    ":X1C12C343N223F3E0A3C636469;", ":X1C12C343N20786D6C6E733A78;", ":X1C12C343N73693D2268747470;",
    ":X1C12C343N3A2F2F7777772E77;", ":X1C12C343N332E6F72672F3230;", ":X1D12C343N30312F584D4C;",
};

TEST(Monitor, PerFrameGoldenLines) {
    Monitor monitor;
    const auto lines = run(monitor, {
                                        ":X17050343N;",
                                        ":X10701343N050101012200;",
                                        ":X19490343N;",
                                        ":X19170343N050101012200;",
                                        ":X1982812CN0343;",
                                        ":X19A28343N012C80;",
                                        ":X194C7343N0501010122000001;",
                                        ":X19068343N012C104304F9;",
                                    });
    const std::vector<std::string> expected = {
        ":X17050343N;                 343 CID7 050",
        ":X10701343N050101012200;     343 AMD 05.01.01.01.22.00",
        ":X19490343N;                 343 Verify Node ID Global",
        ":X19170343N050101012200;     343 Verified Node ID 05.01.01.01.22.00",
        ":X1982812CN0343;             12C -> 343 Protocol Support Inquiry",
        ":X19A28343N012C80;           343 -> 12C Datagram Received OK flags 80",
        ":X194C7343N0501010122000001; 343 Consumer Identified Unknown 05.01.01.01.22.00.00.01",
        // One line, split only to fit: the parentheses say the concatenation is meant.
        (":X19068343N012C104304F9;     343 -> 12C Optional Interaction Rejected error 0x1043 "
         "MTI 0x04F9"),
    };
    EXPECT_EQ(lines, expected);
}

TEST(Monitor, PerFrameDatagramShowsEachFrameAndTheReassembledBytes) {
    Monitor monitor;
    const auto only = run(monitor, {":X1A34312CN20430000000040;"});
    EXPECT_EQ(only, std::vector<std::string>{":X1A34312CN20430000000040;   12C -> 343 Datagram 7 "
                                             "bytes: 20 43 00 00 00 00 40"});
    const auto lines = run(monitor, kReadReply);
    ASSERT_EQ(lines.size(), 9u);
    EXPECT_EQ(lines[0],
              ":X1B12C343N2053000000003C3F; 343 -> 12C Datagram first frame "
              "[20 53 00 00 00 00 3C 3F]");
    EXPECT_EQ(lines[1],
              ":X1C12C343N786D6C2076657273; 343 -> 12C Datagram middle frame "
              "[78 6D 6C 20 76 65 72 73]");
    EXPECT_EQ(lines[8].rfind(":X1D12C343N30312F584D4C;     343 -> 12C Datagram last frame "
                             "[30 31 2F 58 4D 4C] => Datagram 70 bytes: 20 53 00 00 00 00 3C 3F 78",
                             0),
              0u)
        << lines[8];
}

TEST(Monitor, PerMessageDatagramUsesTheRegisteredDecoder) {
    Monitor monitor({Monitor::Mode::kPerMessage, false});
    monitor.register_datagram_decoder(0x20, [](std::span<const std::uint8_t> bytes) {
        return "memory config command " + std::to_string(bytes[1]) + ", " +
               std::to_string(bytes.size()) + " bytes";
    });
    const auto lines = run(monitor, kReadReply);
    ASSERT_EQ(lines.size(), 1u);
    const std::string& line = lines[0];
    EXPECT_EQ(line.rfind("343 -> 12C Datagram 70 bytes: 20 53 00 00 00 00 3C 3F 78 6D 6C", 0), 0u)
        << line;
    EXPECT_NE(line.find("2F 58 4D 4C | memory config command 83, 70 bytes"), std::string::npos)
        << line;
}

TEST(Monitor, PerMessageReassemblesMultiFrameAddressedMessages) {
    Monitor monitor({Monitor::Mode::kPerMessage, true});
    const auto lines = run(monitor, {
                                        ":X10701343N050101012200;",
                                        ":X19A08343N112C0441434D4520;",
                                        ":X19A08343N312C53696D004344;",
                                        ":X19A08343N212C6E636800;",
                                    });
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[1],
              "343(05.01.01.01.22.00) -> 12C Simple Node Ident Info Reply "
              "[04 41 43 4D 45 20 53 69 6D 00 43 44 6E 63 68 00]");
}

TEST(Monitor, ReportsBrokenSequencesAndIgnoresForeignFrames) {
    Monitor monitor({Monitor::Mode::kPerMessage, false});
    EXPECT_EQ(run(monitor, {":X1D12C343N3031;"}),
              std::vector<std::string>{"343 -> 12C Datagram last frame without first [30 31]"});
    std::vector<std::string> too_long = {":X1B12C343N0001020304050607;"};
    for (int i = 0; i < 9; ++i) too_long.push_back(":X1C12C343N0001020304050607;");
    EXPECT_EQ(run(monitor, too_long),
              std::vector<std::string>{"343 -> 12C Datagram longer than 72 bytes, dropped"});
    EXPECT_EQ(
        run(monitor, {":S123N01;", ":X19490343R;"}),
        (std::vector<std::string>{"standard frame (not OpenLCB)", "remote frame (not OpenLCB)"}));
}

TEST(Monitor, PartialMessagesStayBounded) {
    Monitor monitor({Monitor::Mode::kPerMessage, false});
    // First frames from many (src, dst) pairs: the oldest partials are forgotten.
    for (std::uint32_t i = 0; i < 4 * Monitor::kMaxPartials; ++i) {
        CanFrame f;
        f.id = 0x1B000000u | (i & 0xFFF) << 12 | 0x343;
        f.len = 8;
        EXPECT_FALSE(monitor.decode(f));
    }
    // The newest one is still there, the first one is gone.
    CanFrame last;
    last.id = 0x1D000000u | ((4 * Monitor::kMaxPartials - 1) & 0xFFF) << 12 | 0x343;
    last.len = 1;
    EXPECT_NE(monitor.decode(last)->find("Datagram 9 bytes"), std::string::npos);
    CanFrame first = last;
    first.id = 0x1D000343u;
    EXPECT_NE(monitor.decode(first)->find("without first"), std::string::npos);
}

}  // namespace
}  // namespace olcb
