#include "conformance/backup/backup_values.hpp"

#include <charconv>
#include <utility>

#include "cdi/decimal.hpp"
#include "cdi/value_codec.hpp"

namespace olcb::conform {

namespace {

void append_utf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) {
        out += static_cast<char>(cp);
    } else if (cp < 0x800) {
        out += static_cast<char>(0xC0 | (cp >> 6));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

constexpr bool valid_int_size(std::uint64_t size) {
    return size >= 1 && size <= 8;
}

// OpenLCB_Java reads an int's bytes into a Java long: unsigned below 8 bytes, signed at 8.
std::string format_int(std::span<const std::uint8_t> bytes) {
    std::uint64_t v = 0;
    for (std::uint8_t b : bytes) v = (v << 8) | b;
    if (bytes.size() == 8) return std::to_string(static_cast<std::int64_t>(v));
    return std::to_string(v);
}

std::optional<std::vector<std::uint8_t>> int_bytes(std::uint64_t size, std::string_view text,
                                                   std::string& error) {
    const std::optional<cdi::WideInt> v = cdi::parse_decimal_int(text);
    if (!v) {
        error = "'" + std::string(text) + "' is not a decimal integer";
        return std::nullopt;
    }
    // Both readings of the bytes are accepted: signed from -2^(8n-1), unsigned up to 2^(8n)-1.
    const cdi::WideInt lowest = -(cdi::WideInt{1} << (8 * size - 1));
    const cdi::WideInt highest = (cdi::WideInt{1} << (8 * size)) - 1;
    if (*v < lowest || *v > highest) {
        error = "value " + std::string(text) + " out of range for a " + std::to_string(size) +
                "-byte int (" + cdi::to_string(lowest) + ".." + cdi::to_string(highest) + ")";
        return std::nullopt;
    }
    const auto u = static_cast<unsigned __int128>(*v);
    std::vector<std::uint8_t> bytes(size);
    for (std::size_t k = 0; k < size; ++k) bytes[size - 1 - k] = (u >> (8 * k)) & 0xFF;
    return bytes;
}

std::optional<std::vector<std::uint8_t>> string_bytes(std::uint64_t size, std::string_view text,
                                                      std::string& error) {
    if (text.find('\0') != std::string_view::npos || text.size() > size) {
        error = "string of " + std::to_string(text.size()) + " bytes out of range for a " +
                std::to_string(size) + "-byte string";
        return std::nullopt;
    }
    // A full-length string without its NUL is written back as it was read.
    std::vector<std::uint8_t> bytes(size, 0);
    std::copy(text.begin(), text.end(), bytes.begin());
    return bytes;
}

}  // namespace

std::string unescape_backup_text(std::string_view text) {
    if (text.find('\\') == std::string_view::npos) return std::string(text);
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\\' && i + 5 < text.size() && text[i + 1] == 'x') {
            std::uint32_t cp = 0;
            auto [end, ec] = std::from_chars(text.data() + i + 2, text.data() + i + 6, cp, 16);
            if (ec == std::errc() && end == text.data() + i + 6) {
                append_utf8(out, cp);
                i += 5;
                continue;
            }
        }
        out += text[i];
    }
    return out;
}

std::optional<std::string> format_backup_value(const cdi::Element& e,
                                               std::span<const std::uint8_t> bytes,
                                               std::string& error) {
    if (e.kind == cdi::ElementKind::kInt) {
        if (!valid_int_size(bytes.size()) || bytes.size() != e.size) {
            error = "an int of " + std::to_string(e.size) + " bytes has no backup form";
            return std::nullopt;
        }
        return format_int(bytes);
    }
    if (e.kind == cdi::ElementKind::kString) {
        std::size_t len = 0;
        while (len < bytes.size() && bytes[len] != 0) ++len;
        return std::string(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(len));
    }
    auto value = cdi::decode(e, bytes, cdi::CodecMode::kLenient);
    if (!value) {
        error = value.error().message;
        return std::nullopt;
    }
    return cdi::format_value(e, *value);
}

std::optional<std::vector<std::uint8_t>> parse_backup_value(const cdi::Element& e,
                                                            std::string_view text,
                                                            std::string& error) {
    if (e.kind == cdi::ElementKind::kInt) {
        if (!valid_int_size(e.size)) {
            error = "an int of " + std::to_string(e.size) + " bytes has no backup form";
            return std::nullopt;
        }
        return int_bytes(e.size, cdi::trim_xml_space(text), error);
    }
    if (e.kind == cdi::ElementKind::kString) return string_bytes(e.size, text, error);
    auto value = cdi::parse_value_text(e, text);
    if (!value) {
        error = value.error().message;
        return std::nullopt;
    }
    auto bytes = cdi::encode(e, *value);
    if (!bytes) {
        error = bytes.error().message;
        return std::nullopt;
    }
    return std::move(bytes).value();
}

std::optional<std::string> canonical_backup_value(const cdi::Element& e, std::string_view text,
                                                  std::string& error) {
    auto bytes = parse_backup_value(e, text, error);
    if (!bytes) return std::nullopt;
    return format_backup_value(e, *bytes, error);
}

const char* backup_type_name(const cdi::Element& e) {
    switch (e.kind) {
        case cdi::ElementKind::kInt:
            return "int";
        case cdi::ElementKind::kString:
            return "string";
        case cdi::ElementKind::kEventId:
            return "eventid";
        case cdi::ElementKind::kFloat:
            return "float";
        default:
            return cdi::kind_name(e.kind);
    }
}

}  // namespace olcb::conform
