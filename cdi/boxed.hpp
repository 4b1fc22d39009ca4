// An optional value kept out of line, for members of the CDI model that are large or rarely
// present: an absent value costs one pointer instead of the whole value, which keeps Element
// small (a 1 MB CDI holds thousands of them).
#pragma once

#include <memory>
#include <optional>
#include <type_traits>
#include <utility>

namespace olcb::cdi {

/// std::optional<T>'s interface with the value on the heap; copies are deep, so it is a value.
template <class T>
class Boxed {
public:
    /// An empty box.
    Boxed() = default;
    /// An empty box, as std::optional's nullopt.
    Boxed(std::nullopt_t) {}
    /// A box holding value.
    Boxed(T value) : value_(std::make_unique<T>(std::move(value))) {}
    /// A deep copy.
    Boxed(const Boxed& other) : value_(other ? std::make_unique<T>(*other) : nullptr) {}
    /// Takes the other box's value, leaving it empty.
    Boxed(Boxed&& other) noexcept = default;

    /// A deep copy.
    Boxed& operator=(const Boxed& other) {
        if (this != &other) {
            if (other) {
                *this = *other;
            } else {
                reset();
            }
        }
        return *this;
    }
    /// Takes the other box's value, leaving it empty.
    Boxed& operator=(Boxed&& other) noexcept = default;
    /// Stores value (anything convertible to T), reusing the allocation when there is one.
    template <class U = T>
    requires(std::is_convertible_v<U&&, T> && !std::is_same_v<std::remove_cvref_t<U>, Boxed>) Boxed&
    operator=(U&& value) {
        if (value_) {
            *value_ = std::forward<U>(value);
        } else {
            value_ = std::make_unique<T>(std::forward<U>(value));
        }
        return *this;
    }
    /// Stores the optional's value, or empties the box when it has none.
    Boxed& operator=(std::optional<T> value) {
        if (value) {
            *this = std::move(*value);
        } else {
            reset();
        }
        return *this;
    }
    /// Empties the box.
    Boxed& operator=(std::nullopt_t) {
        reset();
        return *this;
    }

    /// True when a value is held.
    bool has_value() const { return value_ != nullptr; }
    /// True when a value is held.
    explicit operator bool() const { return has_value(); }
    /// The value; the box must not be empty.
    T& operator*() { return *value_; }
    /// The value; the box must not be empty.
    const T& operator*() const { return *value_; }
    /// The value's members; the box must not be empty.
    T* operator->() { return value_.get(); }
    /// The value's members; the box must not be empty.
    const T* operator->() const { return value_.get(); }
    /// The value, or fallback when the box is empty.
    template <class U>
    T value_or(U&& fallback) const {
        return value_ ? *value_ : static_cast<T>(std::forward<U>(fallback));
    }
    /// Replaces the value by one built from args.
    template <class... Args>
    T& emplace(Args&&... args) {
        value_ = std::make_unique<T>(std::forward<Args>(args)...);
        return *value_;
    }
    /// Empties the box.
    void reset() { value_.reset(); }

    /// Equal when both are empty or both hold equal values.
    friend bool operator==(const Boxed& a, const Boxed& b) {
        return a && b ? *a == *b : a.has_value() == b.has_value();
    }
    /// Equal when the box holds a value equal to value.
    template <class U>
    requires(!std::is_same_v<std::remove_cvref_t<U>, Boxed> &&
             !std::is_same_v<std::remove_cvref_t<U>, std::nullopt_t>) friend bool
    operator==(const Boxed& box, const U& value) {
        return box && *box == value;
    }
    /// Equal when the box is empty.
    friend bool operator==(const Boxed& box, std::nullopt_t) { return !box; }

private:
    std::unique_ptr<T> value_;
};

}  // namespace olcb::cdi
