// Source lines of byte offsets (cdi/line_counter.cpp): newlines counted sixteen bytes at a time,
// and a counter that moves forward incrementally and recounts after a step back.
#include "cdi/line_counter.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

namespace olcb::cdi {
namespace {

// The plain count, byte by byte, for comparison.
std::size_t slow_count(const std::string& text, std::size_t begin, std::size_t end) {
    std::size_t n = 0;
    for (std::size_t i = begin; i < end; ++i) n += text[i] == '\n' ? 1 : 0;
    return n;
}

TEST(LineCounter, CountNewlinesAgreesWithAByteByByteCountAtEveryAlignment) {
    std::string text;
    for (std::size_t i = 0; i < 300; ++i)
        text += (i * 7 % 5 == 0) ? '\n' : static_cast<char>('a' + i % 26);
    for (std::size_t begin = 0; begin < 20; ++begin) {
        for (std::size_t end = begin; end <= text.size(); end += 13) {
            EXPECT_EQ(count_newlines(text.data() + begin, text.data() + end),
                      slow_count(text, begin, end))
                << begin << ".." << end;
        }
    }
    EXPECT_EQ(count_newlines(text.data(), text.data()), 0u);
}

TEST(LineCounter, CountNewlinesOfTextBeyondALanesCapacity) {
    // More than 255 blocks of 16 bytes, all newlines: a lane's byte counter would overflow.
    const std::string lines(std::size_t{16} * 300 + 5, '\n');
    EXPECT_EQ(count_newlines(lines.data(), lines.data() + lines.size()), lines.size());
    const std::string none(std::size_t{16} * 1000, 'x');
    EXPECT_EQ(count_newlines(none.data(), none.data() + none.size()), 0u);
}

TEST(LineCounter, LinesOfOffsetsForwardBackwardAndPastTheEnd) {
    const std::string text = "<cdi>\n<segment>\n\n<int/>\n</segment>";
    LineCounter lines(text);
    EXPECT_EQ(lines.line_of(0), 1u);
    EXPECT_EQ(lines.line_of(5), 1u);  // the '\n' itself is on line 1
    EXPECT_EQ(lines.line_of(6), 2u);
    EXPECT_EQ(lines.line_of(text.find("<int")), 4u);
    EXPECT_EQ(lines.line_of(text.find("</segment")), 5u);
    EXPECT_EQ(lines.line_of(text.find("<segment")), 2u);  // a step back recounts
    EXPECT_EQ(lines.line_of(text.find("<int")), 4u);
    EXPECT_EQ(lines.line_of(text.size() + 100), 5u);  // past the end: the last line
    LineCounter empty("");
    EXPECT_EQ(empty.line_of(0), 1u);
    EXPECT_EQ(empty.line_of(3), 1u);
}

}  // namespace
}  // namespace olcb::cdi
