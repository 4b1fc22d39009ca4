#include "cdi/value_codec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace olcb::cdi {
namespace {

using Bytes = std::vector<std::uint8_t>;

Element variable(ElementKind kind, std::uint64_t size, std::string name = "X") {
    Element e;
    e.kind = kind;
    e.size = size;
    e.name = std::move(name);
    return e;
}

Element int_element(std::uint64_t size, std::optional<WideInt> min = std::nullopt,
                    std::optional<WideInt> max = std::nullopt, std::string name = "X") {
    Element e = variable(ElementKind::kInt, size, std::move(name));
    e.int_min = min;
    e.int_max = max;
    return e;
}

Map map_of(std::initializer_list<const char*> properties) {
    Map m;
    for (const char* p : properties) m.entries.push_back({p, std::string("label ") + p});
    return m;
}

std::string error_of(const CodecStatus& status) {
    EXPECT_FALSE(status.ok());
    return status.error().message;
}

bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

Bytes encoded(const Element& e, const Value& v, CodecMode mode = CodecMode::kStrict) {
    auto r = encode(e, v, mode);
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? r.value() : Bytes{};
}

Value decoded(const Element& e, const Bytes& bytes, CodecMode mode = CodecMode::kStrict) {
    auto r = decode(e, bytes, mode);
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? r.value() : Value::text("<error>");
}

// ---- Value -----------------------------------------------------------------------------------

// ---- sizes and kinds -------------------------------------------------------------------------

TEST(ValueCodec, ValueSizePerKind) {
    EXPECT_EQ(value_size(int_element(4)).value(), 4u);
    EXPECT_EQ(value_size(variable(ElementKind::kEventId, 0)).value(), 8u);
    EXPECT_EQ(value_size(variable(ElementKind::kEventId, 8)).value(), 8u);
    EXPECT_FALSE(value_size(variable(ElementKind::kEventId, 4)).ok());
    EXPECT_EQ(value_size(variable(ElementKind::kBit, 0)).value(), 1u);
    EXPECT_FALSE(value_size(int_element(3)).ok());
    EXPECT_FALSE(value_size(variable(ElementKind::kFloat, 1)).ok());
    EXPECT_FALSE(value_size(variable(ElementKind::kString, 0)).ok());
    EXPECT_EQ(value_size(variable(ElementKind::kString, 64)).value(), 64u);
}

TEST(ValueCodec, ElementsWithoutValueAreErrors) {
    for (ElementKind kind : {ElementKind::kGroup, ElementKind::kBlob, ElementKind::kUnknown}) {
        const Element e = variable(kind, 10, "Thing");
        EXPECT_FALSE(value_kind_of(e).has_value());
        const auto enc = encode(e, Value::integer(1));
        ASSERT_FALSE(enc.ok());
        EXPECT_TRUE(contains(enc.error().message, "has no value")) << enc.error().message;
        EXPECT_FALSE(decode(e, Bytes(10, 0)).ok());
        EXPECT_FALSE(check_value(e, Value::integer(1)).ok());
        EXPECT_FALSE(parse_value_text(e, "1").ok());
    }
}

TEST(ValueCodec, WrongValueKindIsAnError) {
    const auto r = encode(int_element(1, std::nullopt, std::nullopt, "Mode"), Value::text("1"));
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "expected int value for <int> 'Mode', got string");
    EXPECT_FALSE(check_value(variable(ElementKind::kFloat, 4), Value::integer(1)).ok());
    EXPECT_FALSE(encode(variable(ElementKind::kEventId, 8), Value::integer(1)).ok());
}

TEST(ValueCodec, UnnamedElementsAreNamedByTagAndLine) {
    Element e = int_element(1, std::nullopt, std::nullopt, "");
    e.pos.line = 12;
    EXPECT_EQ(error_of(check_value(e, Value::integer(256))),
              "value 256 above max 255 of unnamed <int> at line 12");
}

// ---- int -------------------------------------------------------------------------------------

TEST(ValueCodec, IntSignednessFollowsMin) {
    const Element unsigned_int = int_element(2);
    const Element signed_int = int_element(2, -100);
    EXPECT_EQ(encoded(signed_int, Value::integer(-1)), (Bytes{0xFF, 0xFF}));
    EXPECT_EQ(decoded(signed_int, {0xFF, 0xFF}), Value::integer(-1));
    EXPECT_EQ(decoded(unsigned_int, {0xFF, 0xFF}), Value::integer(65535));
    EXPECT_FALSE(encode(unsigned_int, Value::integer(-1)).ok());
    EXPECT_FALSE(encode(unsigned_int, Value::integer(65536)).ok());
    // encode checks only what fits; min/max is check_value's job.
    EXPECT_EQ(encoded(int_element(1, 0, 10), Value::integer(200)), (Bytes{200}));
}

TEST(ValueCodec, IntDefaultMinMax) {
    const Element e = int_element(1, std::nullopt, std::nullopt, "Brightness");
    EXPECT_TRUE(check_value(e, Value::integer(0)).ok());
    EXPECT_TRUE(check_value(e, Value::integer(255)).ok());
    EXPECT_EQ(error_of(check_value(e, Value::integer(300))),
              "value 300 above max 255 of 'Brightness'");
    EXPECT_EQ(error_of(check_value(e, Value::integer(-1))), "value -1 below min 0 of 'Brightness'");
    const Element wide = int_element(8);
    const WideInt two64 = static_cast<WideInt>(1) << 64;
    EXPECT_TRUE(check_value(wide, Value::integer(two64 - 1)).ok());
    EXPECT_FALSE(check_value(wide, Value::integer(two64)).ok());
}

TEST(ValueCodec, IntDeclaredMinMax) {
    const Element e = int_element(2, -10, 10, "Trim");
    EXPECT_TRUE(check_value(e, Value::integer(-10)).ok());
    EXPECT_TRUE(check_value(e, Value::integer(10)).ok());
    EXPECT_EQ(error_of(check_value(e, Value::integer(-11))), "value -11 below min -10 of 'Trim'");
    EXPECT_EQ(error_of(check_value(e, Value::integer(11))), "value 11 above max 10 of 'Trim'");
    // A declared max beyond the size is capped by what the bytes can hold.
    const Element capped = int_element(1, 1, 1000, "Rate");
    EXPECT_EQ(error_of(check_value(capped, Value::integer(300))),
              "value 300 above max 255 of 'Rate'");
    EXPECT_EQ(error_of(check_value(capped, Value::integer(0))), "value 0 below min 1 of 'Rate'");
    const Element signed_capped = int_element(1, -1000, std::nullopt, "S");
    EXPECT_EQ(error_of(check_value(signed_capped, Value::integer(-129))),
              "value -129 below min -128 of 'S'");
    EXPECT_EQ(error_of(check_value(signed_capped, Value::integer(128))),
              "value 128 above max 127 of 'S'");
}

TEST(ValueCodec, IntMapMembershipIsNumeric) {
    Element e = int_element(1, std::nullopt, std::nullopt, "Mode");
    e.map = map_of({"0", " 2 ", "007", "not a number"});
    EXPECT_TRUE(check_value(e, Value::integer(0)).ok());
    EXPECT_TRUE(check_value(e, Value::integer(2)).ok());
    EXPECT_TRUE(check_value(e, Value::integer(7)).ok());
    EXPECT_EQ(error_of(check_value(e, Value::integer(1))),
              "value 1 is not one of the map properties (0,  2 , 007, not a number) of 'Mode'");
    // min/max apply on top of the map.
    e.int_max = 5;
    EXPECT_TRUE(contains(error_of(check_value(e, Value::integer(7))), "above max 5"));
}

TEST(ValueCodec, LongMapsAreAbbreviatedInMessages) {
    Element e = int_element(1);
    e.map = map_of({"0", "1", "2", "3", "4", "5", "6", "7", "8", "9"});
    EXPECT_TRUE(
        contains(error_of(check_value(e, Value::integer(10))), "(0, 1, 2, 3, 4, 5, 6, 7, ...)"));
}

TEST(ValueCodec, EmptyMapAllowsNothing) {
    Element e = int_element(1);
    e.map = Map{};
    EXPECT_FALSE(check_value(e, Value::integer(0)).ok());
}

TEST(ValueCodec, BitIsAnUnsignedByte) {
    const Element bit = variable(ElementKind::kBit, 0);
    EXPECT_EQ(encoded(bit, Value::integer(1)), (Bytes{1}));
    EXPECT_EQ(decoded(bit, {0xFF}), Value::integer(255));
    EXPECT_TRUE(check_value(bit, Value::integer(1)).ok());
}

// ---- action ----------------------------------------------------------------------------------

TEST(ValueCodec, ActionWritesItsValue) {
    Element e = variable(ElementKind::kAction, 1, "Reboot");
    e.action_value = 1;
    EXPECT_EQ(encode_action(e).value(), (Bytes{0x01}));
    EXPECT_TRUE(check_value(e, Value::integer(1)).ok());
    EXPECT_EQ(error_of(check_value(e, Value::integer(2))),
              "value 2 is not the action value 1 of 'Reboot'");
    e.size = 4;
    e.action_value = 0x01020304;
    EXPECT_EQ(encode_action(e).value(), (Bytes{1, 2, 3, 4}));
}

TEST(ValueCodec, NegativeActionValueIsTwosComplement) {
    Element e = variable(ElementKind::kAction, 2, "Reset");
    e.action_value = -1;
    EXPECT_EQ(encode_action(e).value(), (Bytes{0xFF, 0xFF}));
    EXPECT_EQ(decoded(e, {0xFF, 0xFF}), Value::integer(-1));
}

TEST(ValueCodec, ActionErrors) {
    Element e = variable(ElementKind::kAction, 1, "Go");
    EXPECT_EQ(error_of(check_value(e, Value::integer(1))), "action 'Go' has no <value>");
    EXPECT_FALSE(encode_action(e).ok());
    e.action_value = 300;
    EXPECT_FALSE(encode_action(e).ok());
    EXPECT_TRUE(contains(error_of(check_value(e, Value::integer(300))), "does not fit"));
    EXPECT_FALSE(encode_action(int_element(1)).ok());
}

// ---- float -----------------------------------------------------------------------------------

TEST(ValueCodec, FloatEncodesPerSize) {
    EXPECT_EQ(encoded(variable(ElementKind::kFloat, 2), Value::real(1.0)), (Bytes{0x3C, 0x00}));
    EXPECT_EQ(encoded(variable(ElementKind::kFloat, 4), Value::real(1.0)),
              (Bytes{0x3F, 0x80, 0, 0}));
    EXPECT_EQ(decoded(variable(ElementKind::kFloat, 8), {0x3F, 0xF0, 0, 0, 0, 0, 0, 0}),
              Value::real(1.0));
}

TEST(ValueCodec, FloatOverflowStrictAndLenient) {
    const Element e = variable(ElementKind::kFloat, 4, "Gain");
    const auto r = encode(e, Value::real(1e39));
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.error().message, "'Gain': value 1e+39 overflows a 4-byte float"))
        << r.error().message;
    EXPECT_EQ(encoded(e, Value::real(1e39), CodecMode::kLenient), (Bytes{0x7F, 0x80, 0, 0}));
}

TEST(ValueCodec, FloatDefaultMinZeroAndMaxOfSize) {
    const Element half = variable(ElementKind::kFloat, 2, "Timeout");
    EXPECT_TRUE(check_value(half, Value::real(0.0)).ok());
    EXPECT_TRUE(check_value(half, Value::real(65504.0)).ok());
    EXPECT_TRUE(check_value(half, Value::real(65519.0)).ok());  // stored as 65504
    EXPECT_EQ(error_of(check_value(half, Value::real(-1.0))), "value -1 below min 0 of 'Timeout'");
    EXPECT_EQ(error_of(check_value(half, Value::real(70000.0))),
              "value 70000 above max 65504 of 'Timeout'");
    EXPECT_EQ(error_of(check_value(half, Value::real(std::nan("")))),
              "value nan (not a number) is invalid for 'Timeout'");
    EXPECT_FALSE(check_value(half, Value::real(std::numeric_limits<double>::infinity())).ok());
    const Element single = variable(ElementKind::kFloat, 4, "Gain");
    EXPECT_EQ(error_of(check_value(single, parse_value_text(single, "-0.1").value())),
              "value -0.1 below min 0 of 'Gain'");
    EXPECT_TRUE(check_value(single, Value::real(3.0e38)).ok());
    EXPECT_FALSE(check_value(single, Value::real(1e39)).ok());
}

TEST(ValueCodec, FloatLimitsCompareInTheStoredPrecision) {
    Element e = variable(ElementKind::kFloat, 2, "Speed");
    e.float_min = 0.1;
    e.float_max = 0.3;
    EXPECT_TRUE(check_value(e, Value::real(0.1)).ok());  // both round to the same half
    EXPECT_TRUE(check_value(e, Value::real(0.3)).ok());
    EXPECT_FALSE(check_value(e, Value::real(0.09)).ok());
    EXPECT_FALSE(check_value(e, Value::real(0.31)).ok());
    e.float_min = -5.0;
    EXPECT_TRUE(check_value(e, Value::real(-5.0)).ok());
    EXPECT_TRUE(contains(error_of(check_value(e, Value::real(-5.5))), "below min -5"));
}

TEST(ValueCodec, FloatMapMembershipIsNumeric) {
    Element e = variable(ElementKind::kFloat, 4, "Scale");
    e.map = map_of({"1.0", "1.50", " 2e0 ", "0.1"});
    EXPECT_TRUE(check_value(e, Value::real(1.0)).ok());
    EXPECT_TRUE(check_value(e, Value::real(1.5)).ok());
    EXPECT_TRUE(check_value(e, Value::real(2.0)).ok());
    EXPECT_TRUE(check_value(e, Value::real(0.1)).ok());
    EXPECT_TRUE(contains(error_of(check_value(e, Value::real(3.0))),
                         "value 3 is not one of the map properties"));
}

// ---- string ----------------------------------------------------------------------------------

TEST(ValueCodec, StringEncodeDecode) {
    const Element e = variable(ElementKind::kString, 8, "Name");
    EXPECT_EQ(encoded(e, Value::text("abc")), (Bytes{'a', 'b', 'c', 0, 0, 0, 0, 0}));
    EXPECT_EQ(decoded(e, {'a', 'b', 0, 'x', 0, 0, 0, 0}), Value::text("ab"));
    const auto long_text = encode(e, Value::text("abcdefgh"));
    ASSERT_FALSE(long_text.ok());
    EXPECT_TRUE(contains(long_text.error().message, "'Name': text of 8 bytes is longer"));
    EXPECT_EQ(encoded(e, Value::text("abcdefgh"), CodecMode::kLenient),
              (Bytes{'a', 'b', 'c', 'd', 'e', 'f', 'g', 0}));
}

TEST(ValueCodec, StringDecodeStrictAndLenient) {
    const Element e = variable(ElementKind::kString, 4, "Name");
    const auto unterminated = decode(e, Bytes{'a', 'b', 'c', 'd'});
    ASSERT_FALSE(unterminated.ok());
    EXPECT_EQ(unterminated.error().message,
              "'Name': string has no NUL terminator within its 4 bytes");
    EXPECT_EQ(decoded(e, {'a', 'b', 'c', 'd'}, CodecMode::kLenient), Value::text("abcd"));
    const auto invalid = decode(e, Bytes{'a', 0xFF, 0, 0});
    ASSERT_FALSE(invalid.ok());
    EXPECT_EQ(invalid.error().message, "'Name': string is not valid UTF-8 (byte 1)");
    EXPECT_EQ(decoded(e, {'a', 0xFF, 0, 0}, CodecMode::kLenient), Value::text("a\xFF"));
}

TEST(ValueCodec, StringChecks) {
    Element e = variable(ElementKind::kString, 4, "Code");
    EXPECT_TRUE(check_value(e, Value::text("abc")).ok());
    EXPECT_TRUE(check_value(e, Value::text("")).ok());
    EXPECT_EQ(error_of(check_value(e, Value::text("abcd"))),
              "text of 4 bytes is longer than max 3 bytes of 'Code'");
    EXPECT_TRUE(contains(error_of(check_value(e, Value::text("\xC3"))), "not valid UTF-8"));
    EXPECT_TRUE(contains(error_of(check_value(e, Value::text(std::string("a\0", 2)))), "NUL"));
    e.map = map_of({"ab", "cd"});
    EXPECT_TRUE(check_value(e, Value::text("ab")).ok());
    EXPECT_EQ(error_of(check_value(e, Value::text("AB"))),
              "value 'AB' is not one of the map properties (ab, cd) of 'Code'");
    EXPECT_FALSE(check_value(e, Value::text("ab ")).ok());  // strings compare exactly
}

// ---- eventid ---------------------------------------------------------------------------------

TEST(ValueCodec, EventIdEncodeDecode) {
    const Element e = variable(ElementKind::kEventId, 8, "Event");
    EXPECT_EQ(encoded(e, Value::event_id(0x0501010122000001)),
              (Bytes{0x05, 0x01, 0x01, 0x01, 0x22, 0x00, 0x00, 0x01}));
    EXPECT_EQ(decoded(e, {0x05, 0x01, 0x01, 0x01, 0x22, 0x00, 0x00, 0x01}),
              Value::event_id(0x0501010122000001));
    const auto short_read = decode(e, Bytes(7, 0));
    ASSERT_FALSE(short_read.ok());
    EXPECT_EQ(short_read.error().message, "'Event': got 7 bytes, expected 8");
}

TEST(ValueCodec, EventIdMapComparesAsEventIds) {
    Element e = variable(ElementKind::kEventId, 8, "Event");
    e.map = map_of({"05.01.01.01.22.00.00.01", " 0501010122000002 ", "junk"});
    EXPECT_TRUE(check_value(e, Value::event_id(0x0501010122000001)).ok());
    EXPECT_TRUE(check_value(e, Value::event_id(0x0501010122000002)).ok());
    EXPECT_TRUE(contains(error_of(check_value(e, Value::event_id(0x0501010122000003))),
                         "value 05.01.01.01.22.00.00.03 is not one of the map properties"));
    e.map.reset();
    EXPECT_TRUE(check_value(e, Value::event_id(0)).ok());
}

// ---- text ------------------------------------------------------------------------------------

TEST(ValueCodec, ParseValueText) {
    EXPECT_EQ(parse_value_text(int_element(1), " 42 ").value(), Value::integer(42));
    EXPECT_EQ(parse_value_text(int_element(1, -5), "-5").value(), Value::integer(-5));
    EXPECT_EQ(parse_value_text(variable(ElementKind::kFloat, 8), "2.5").value(), Value::real(2.5));
    EXPECT_EQ(parse_value_text(variable(ElementKind::kFloat, 4), "0.1").value(),
              Value::real(static_cast<double>(0.1f)));
    EXPECT_EQ(parse_value_text(variable(ElementKind::kString, 8), "  a b ").value(),
              Value::text("  a b "));
    EXPECT_EQ(
        parse_value_text(variable(ElementKind::kEventId, 8), "05.01.01.01.22.00.00.ff\n").value(),
        Value::event_id(0x05010101220000FF));
    Element action = variable(ElementKind::kAction, 1);
    EXPECT_EQ(parse_value_text(action, "1").value(), Value::integer(1));
}

TEST(ValueCodec, ParseValueTextErrorsNameTheElement) {
    const auto r = parse_value_text(int_element(1, std::nullopt, std::nullopt, "Count"), "12x");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "'Count': '12x' is not a decimal integer");
    const auto f = parse_value_text(variable(ElementKind::kFloat, 4, "Gain"), "fast");
    ASSERT_FALSE(f.ok());
    EXPECT_EQ(f.error().message, "'Gain': 'fast' is not a decimal number");
    const auto id = parse_value_text(variable(ElementKind::kEventId, 8, "Ev"), "01.02");
    ASSERT_FALSE(id.ok());
    EXPECT_TRUE(contains(id.error().message, "'Ev': event ID '01.02' has 2 groups"));
}

TEST(ValueCodec, FormatValue) {
    EXPECT_EQ(format_value(int_element(8), Value::integer(-42)), "-42");
    EXPECT_EQ(format_value(variable(ElementKind::kFloat, 2), Value::real(0.0999755859375)), "0.1");
    EXPECT_EQ(format_value(variable(ElementKind::kFloat, 4), Value::real(1.0 / 3)), "0.33333334");
    EXPECT_EQ(format_value(variable(ElementKind::kFloat, 8), Value::real(1.0 / 3)),
              "0.3333333333333333");
    EXPECT_EQ(format_value(variable(ElementKind::kString, 8), Value::text(" x ")), " x ");
    EXPECT_EQ(format_value(variable(ElementKind::kEventId, 8), Value::event_id(0x0501010122000001)),
              "05.01.01.01.22.00.00.01");
}

TEST(ValueCodec, BytesToTextToBytesRoundTrip) {
    struct Case {
        Element element;
        Bytes bytes;
    };
    Element signed_int = int_element(4, -1);
    const std::vector<Case> cases = {
        {int_element(1), {0xAB}},
        {signed_int, {0xFF, 0xFF, 0xFF, 0xF6}},
        {int_element(8), Bytes(8, 0xFF)},
        {variable(ElementKind::kFloat, 2), {0x2E, 0x66}},
        {variable(ElementKind::kFloat, 4), {0x3D, 0xCC, 0xCC, 0xCD}},
        {variable(ElementKind::kFloat, 8), {0x40, 0x09, 0x21, 0xFB, 0x54, 0x44, 0x2D, 0x18}},
        {variable(ElementKind::kString, 6), {'h', 'i', 0, 0, 0, 0}},
        {variable(ElementKind::kEventId, 8), {1, 2, 3, 4, 5, 6, 7, 8}},
    };
    for (const Case& c : cases) {
        const Value v = decoded(c.element, c.bytes);
        const std::string text = format_value(c.element, v);
        const auto back = parse_value_text(c.element, text);
        ASSERT_TRUE(back.ok()) << text;
        EXPECT_EQ(encoded(c.element, back.value()), c.bytes) << text;
    }
}

}  // namespace
}  // namespace olcb::cdi
