// Strict decimal numbers (cdi/decimal.cpp): the CDI standard's attributes and element texts hold
// decimal numbers only, with XML whitespace around them.
#include "cdi/decimal.hpp"

#include <gtest/gtest.h>

#include <string>

namespace olcb::cdi {
namespace {

TEST(Decimal, IntegersAreStrictDecimal) {
    EXPECT_EQ(parse_decimal_int("42"), WideInt{42});
    EXPECT_EQ(parse_decimal_int(" \t-17\r\n"), WideInt{-17});
    EXPECT_EQ(parse_decimal_int("+8"), WideInt{8});
    EXPECT_EQ(parse_decimal_int("007"), WideInt{7});
    EXPECT_EQ(parse_decimal_int("18446744073709551615"),
              static_cast<WideInt>(18446744073709551615ULL));
    EXPECT_EQ(parse_decimal_int("-9223372036854775808"), -(WideInt{1} << 63));
    for (const char* bad : {"", " ", "-", "+", "0x10", "1e3", "1.0", "12a", "--1", "1 2", "٣",
                            "123456789012345678901234567890123456789"}) {
        EXPECT_FALSE(parse_decimal_int(bad).has_value()) << bad;
    }
}

TEST(Decimal, FloatsAreDecimal) {
    EXPECT_EQ(parse_decimal_float("1.5"), 1.5);
    EXPECT_EQ(parse_decimal_float(" -0.25 "), -0.25);
    EXPECT_EQ(parse_decimal_float("+3"), 3.0);
    EXPECT_EQ(parse_decimal_float("1e3"), 1000.0);
    EXPECT_EQ(parse_decimal_float(".5"), 0.5);
    for (const char* bad : {"", "0x1p3", "inf", "nan", "1e", "1.2.3", "e5", "1e400", "--1"}) {
        EXPECT_FALSE(parse_decimal_float(bad).has_value()) << bad;
    }
}

TEST(Decimal, ThirtyEightSignificantDigitsFitLeadingZerosDoNotCount) {
    const std::string max38(38, '9');
    ASSERT_TRUE(parse_decimal_int(max38).has_value());
    EXPECT_EQ(to_string(*parse_decimal_int(max38)), max38);
    EXPECT_EQ(to_string(*parse_decimal_int("-" + max38)), "-" + max38);
    EXPECT_EQ(parse_decimal_int(std::string(50, '0') + "12"), WideInt{12});
    EXPECT_EQ(parse_decimal_int("-0"), WideInt{0});
    EXPECT_FALSE(parse_decimal_int("1" + std::string(38, '0')).has_value());
}

TEST(Decimal, FloatExponentsAndSigns) {
    EXPECT_EQ(parse_decimal_float("2.5E-1"), 0.25);
    EXPECT_EQ(parse_decimal_float("-1e+2"), -100.0);
    EXPECT_EQ(parse_decimal_float("+.5"), 0.5);
    EXPECT_EQ(parse_decimal_float("7."), 7.0);
    EXPECT_EQ(parse_decimal_float("\n\t1\r "), 1.0);
    for (const char* bad : {".", "+", "-.", "1e+", "e", "1 e3", "1,5", "0x10", "Infinity"}) {
        EXPECT_FALSE(parse_decimal_float(bad).has_value()) << bad;
    }
}

TEST(Decimal, TrimsXmlSpaceOnly) {
    EXPECT_EQ(trim_xml_space(" \t\r\nab c\n "), "ab c");
    EXPECT_EQ(trim_xml_space("   "), "");
    EXPECT_EQ(trim_xml_space(""), "");
    EXPECT_EQ(trim_xml_space("\v1\f"), "\v1\f");  // not XML whitespace
    EXPECT_TRUE(is_xml_space(' '));
    EXPECT_TRUE(is_xml_space('\t'));
    EXPECT_TRUE(is_xml_space('\r'));
    EXPECT_TRUE(is_xml_space('\n'));
    EXPECT_FALSE(is_xml_space('\v'));
    EXPECT_FALSE(is_xml_space('\0'));
    EXPECT_FALSE(parse_decimal_int("\v1").has_value());
}

}  // namespace
}  // namespace olcb::cdi
