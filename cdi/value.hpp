// A typed value of a CDI variable, independent of how it is stored in memory.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <variant>

#include "cdi/document.hpp"

namespace olcb::cdi {

/// An event ID as a number: the 8 bytes big-endian, most significant byte first.
using EventIdValue = std::uint64_t;

/// Which alternative a Value holds; the order matches Value::Data.
enum class ValueKind : std::uint8_t {
    kInt,      ///< <int>, <action>, <bit>
    kFloat,    ///< <float>
    kString,   ///< <string>
    kEventId,  ///< <eventid>
};

/// "int", "float", "string" or "eventid".
const char* value_kind_name(ValueKind kind);

/// The value of one variable. Built with the named factories because a plain integer literal
/// would convert equally well to three of the alternatives.
struct Value {
    /// The alternatives, in ValueKind order.
    using Data = std::variant<WideInt, double, std::string, EventIdValue>;
    Data data;

    /// An integer value.
    static Value integer(WideInt v) { return Value{Data(std::in_place_index<0>, v)}; }
    /// A floating point value.
    static Value real(double v) { return Value{Data(std::in_place_index<1>, v)}; }
    /// A string value.
    static Value text(std::string v) { return Value{Data(std::in_place_index<2>, std::move(v))}; }
    /// An event ID value.
    static Value event_id(EventIdValue v) { return Value{Data(std::in_place_index<3>, v)}; }

    /// The alternative held.
    ValueKind kind() const { return static_cast<ValueKind>(data.index()); }
    /// The integer, or nullptr when another kind is held.
    const WideInt* as_int() const { return std::get_if<0>(&data); }
    /// The float, or nullptr when another kind is held.
    const double* as_float() const { return std::get_if<1>(&data); }
    /// The string, or nullptr when another kind is held.
    const std::string* as_string() const { return std::get_if<2>(&data); }
    /// The event ID, or nullptr when another kind is held.
    const EventIdValue* as_event_id() const { return std::get_if<3>(&data); }

    /// Same kind and equal contents (floats compare numerically: NaN != NaN, -0 == +0).
    bool operator==(const Value& other) const = default;
};

}  // namespace olcb::cdi
