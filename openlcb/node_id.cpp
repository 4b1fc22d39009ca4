#include "openlcb/node_id.hpp"

namespace olcb {
namespace {

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// Appending (rather than operator+ chains) keeps g++ 12's -Wrestrict false positive away.
template <class... Parts>
std::string concat(const Parts&... parts) {
    std::string out;
    (out.append(parts), ...);
    return out;
}

// Records "node ID '05.01': <detail>" when the caller asked for a reason.
template <class... Parts>
void fail(std::string* error, const char* what, std::string_view text, const Parts&... detail) {
    if (error) *error = concat(std::string_view(what), " '", text.substr(0, 40), "': ", detail...);
}

// The value of a run of hex digits of the id `text`; nullopt and the reason on a non-digit.
std::optional<std::uint64_t> hex_run(std::string_view digits, std::string_view text,
                                     const char* what, std::string* error) {
    std::uint64_t value = 0;
    for (char c : digits) {
        const int v = hex_value(c);
        if (v < 0) {
            fail(error, what, text, "'", std::string(1, c), "' is not a hex digit");
            return std::nullopt;
        }
        value = value << 4 | static_cast<std::uint64_t>(v);
    }
    return value;
}

// Shared by NodeId and EventId: they differ only in byte count.
std::optional<std::uint64_t> parse_id(std::string_view text, std::size_t bytes, const char* what,
                                      std::string* error) {
    if (text.empty()) {
        if (error) *error = concat(std::string_view("empty "), std::string_view(what));
        return std::nullopt;
    }
    const std::string n = std::to_string(bytes);
    std::uint64_t value = 0;
    if (text.find('.') == std::string_view::npos) {
        if (text.size() != 2 * bytes) {
            fail(error, what, text, "expected ", n, " dot-separated bytes or ",
                 std::to_string(2 * bytes), " hex digits");
            return std::nullopt;
        }
        return hex_run(text, text, what, error);
    }
    std::size_t count = 0;
    std::size_t pos = 0;
    while (true) {
        const std::size_t dot = text.find('.', pos);
        const std::string_view part =
            text.substr(pos, dot == std::string_view::npos ? std::string_view::npos : dot - pos);
        ++count;
        if (count > bytes) {
            fail(error, what, text, "more than ", n, " bytes");
            return std::nullopt;
        }
        if (part.empty() || part.size() > 2) {
            fail(error, what, text, "byte ", std::to_string(count), " must be 1 or 2 hex digits");
            return std::nullopt;
        }
        const auto byte = hex_run(part, text, what, error);
        if (!byte) return std::nullopt;
        value = value << 8 | *byte;
        if (dot == std::string_view::npos) break;
        pos = dot + 1;
    }
    if (count != bytes) {
        fail(error, what, text, "expected ", n, " bytes, got ", std::to_string(count));
        return std::nullopt;
    }
    return value;
}

std::string format_id(std::uint64_t value, std::size_t bytes) {
    static constexpr char kDigits[] = "0123456789ABCDEF";
    std::string out;
    out.reserve(bytes * 3);
    for (std::size_t i = bytes; i-- > 0;) {
        const auto b = static_cast<unsigned>(value >> (8 * i)) & 0xFF;
        out.push_back(kDigits[b >> 4]);
        out.push_back(kDigits[b & 0xF]);
        if (i != 0) out.push_back('.');
    }
    return out;
}

template <std::size_t N>
std::array<std::uint8_t, N> to_big_endian(std::uint64_t value) {
    std::array<std::uint8_t, N> out{};
    for (std::size_t i = 0; i < N; ++i) {
        out[i] = static_cast<std::uint8_t>(value >> (8 * (N - 1 - i)));
    }
    return out;
}

std::optional<std::uint64_t> from_big_endian(std::span<const std::uint8_t> bytes, std::size_t n) {
    if (bytes.size() < n) return std::nullopt;
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < n; ++i) value = value << 8 | bytes[i];
    return value;
}

}  // namespace

std::array<std::uint8_t, NodeId::kSize> NodeId::to_bytes() const {
    return to_big_endian<kSize>(value_);
}

std::optional<NodeId> NodeId::from_bytes(std::span<const std::uint8_t> bytes) {
    if (auto v = from_big_endian(bytes, kSize)) return NodeId(*v);
    return std::nullopt;
}

std::string NodeId::to_string() const {
    return format_id(value_, kSize);
}

std::optional<NodeId> NodeId::parse(std::string_view text, std::string* error) {
    if (auto v = parse_id(text, kSize, "node ID", error)) return NodeId(*v);
    return std::nullopt;
}

std::array<std::uint8_t, EventId::kSize> EventId::to_bytes() const {
    return to_big_endian<kSize>(value_);
}

std::optional<EventId> EventId::from_bytes(std::span<const std::uint8_t> bytes) {
    if (auto v = from_big_endian(bytes, kSize)) return EventId(*v);
    return std::nullopt;
}

std::string EventId::to_string() const {
    return format_id(value_, kSize);
}

std::optional<EventId> EventId::parse(std::string_view text, std::string* error) {
    if (auto v = parse_id(text, kSize, "event ID", error)) return EventId(*v);
    return std::nullopt;
}

}  // namespace olcb
