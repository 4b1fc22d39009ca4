// Errors-as-values for the CDI value codecs: a result that holds either a value or a message.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <variant>

namespace olcb::cdi {

/// Why a value could not be encoded, decoded, parsed or accepted; message is user-readable.
struct CodecError {
    std::string message;  ///< a complete sentence fragment, e.g. "value 300 above max 255 of 'X'"
};

/// How forgiving a codec is: strict follows the standard; lenient keeps data usable.
enum class CodecMode : std::uint8_t {
    kStrict,   ///< reject anything the standard forbids
    kLenient,  ///< truncate long strings, accept unterminated or non-UTF-8 strings, float overflow
               ///< becomes infinity
};

/// Either a T or a CodecError (C++20 has no std::expected).
template <typename T>
class [[nodiscard]] CodecResult {
public:
    /// A successful result.
    CodecResult(T value) : state_(std::in_place_index<0>, std::move(value)) {}
    /// A failed result.
    CodecResult(CodecError error) : state_(std::in_place_index<1>, std::move(error)) {}

    /// True when a value is held.
    bool ok() const { return state_.index() == 0; }
    /// Same as ok().
    explicit operator bool() const { return ok(); }

    /// The value; throws std::bad_variant_access when !ok().
    const T& value() const& { return std::get<0>(state_); }
    /// The value; throws std::bad_variant_access when !ok().
    T& value() & { return std::get<0>(state_); }
    /// The value, moved out; throws std::bad_variant_access when !ok().
    T&& value() && { return std::get<0>(std::move(state_)); }
    /// The value; throws std::bad_variant_access when !ok().
    const T& operator*() const& { return value(); }
    /// Member access to the value; throws std::bad_variant_access when !ok().
    const T* operator->() const { return &value(); }

    /// The error; throws std::bad_variant_access when ok().
    const CodecError& error() const { return std::get<1>(state_); }

private:
    std::variant<T, CodecError> state_;
};

/// Success or a CodecError, for checks that produce no value.
template <>
class [[nodiscard]] CodecResult<void> {
public:
    /// Success.
    CodecResult() = default;
    /// Failure.
    CodecResult(CodecError error) : error_(std::move(error)), ok_(false) {}

    /// True on success.
    bool ok() const { return ok_; }
    /// Same as ok().
    explicit operator bool() const { return ok_; }
    /// The error (empty message on success).
    const CodecError& error() const { return error_; }

private:
    CodecError error_;
    bool ok_ = true;
};

/// Result of a check: success or a CodecError.
using CodecStatus = CodecResult<void>;

}  // namespace olcb::cdi
