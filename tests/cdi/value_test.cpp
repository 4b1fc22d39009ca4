// A typed value of a CDI variable (cdi/value.cpp): one alternative per kind, named factories,
// typed accessors and equality.
#include "cdi/value.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace olcb::cdi {
namespace {

TEST(Value, FactoriesAndAccessors) {
    const Value i = Value::integer(-3);
    EXPECT_EQ(i.kind(), ValueKind::kInt);
    ASSERT_NE(i.as_int(), nullptr);
    EXPECT_EQ(*i.as_int(), -3);
    EXPECT_EQ(i.as_float(), nullptr);
    EXPECT_EQ(Value::real(1.5).kind(), ValueKind::kFloat);
    EXPECT_EQ(*Value::text("a").as_string(), "a");
    EXPECT_EQ(*Value::event_id(7).as_event_id(), 7u);
    EXPECT_EQ(Value::integer(7), Value::integer(7));
    EXPECT_NE(Value::integer(7), Value::event_id(7));
    EXPECT_STREQ(value_kind_name(ValueKind::kEventId), "eventid");
}

TEST(Value, EveryKindHasItsName) {
    EXPECT_STREQ(value_kind_name(ValueKind::kInt), "int");
    EXPECT_STREQ(value_kind_name(ValueKind::kFloat), "float");
    EXPECT_STREQ(value_kind_name(ValueKind::kString), "string");
    EXPECT_STREQ(value_kind_name(ValueKind::kEventId), "eventid");
}

TEST(Value, AccessorsAnswerOnlyForTheKindHeld) {
    const Value e = Value::event_id(0x0501010122000001ull);
    EXPECT_EQ(e.kind(), ValueKind::kEventId);
    EXPECT_EQ(e.as_int(), nullptr);
    EXPECT_EQ(e.as_float(), nullptr);
    EXPECT_EQ(e.as_string(), nullptr);
    ASSERT_NE(e.as_event_id(), nullptr);
    EXPECT_EQ(*e.as_event_id(), 0x0501010122000001ull);
    const Value s = Value::text("");
    EXPECT_EQ(s.kind(), ValueKind::kString);
    EXPECT_EQ(s.as_event_id(), nullptr);
    const WideInt big = WideInt{1} << 100;
    EXPECT_EQ(*Value::integer(big).as_int(), big);
}

TEST(Value, EqualityIsByKindAndContent) {
    EXPECT_EQ(Value::text("a"), Value::text("a"));
    EXPECT_NE(Value::text("a"), Value::text("b"));
    EXPECT_NE(Value::integer(1), Value::real(1.0));
    EXPECT_EQ(Value::real(-0.0), Value::real(0.0));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(Value::real(nan), Value::real(nan));
}

}  // namespace
}  // namespace olcb::cdi
