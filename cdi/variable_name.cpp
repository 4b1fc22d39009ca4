#include "cdi/variable_name.hpp"

#include <utility>

#include "base/hex.hpp"

namespace olcb::cdi {

namespace {

// Decodes the UTF-8 sequence at text[i]; its code point and length, or length 0 when invalid.
std::pair<std::uint32_t, std::size_t> decode_utf8(std::string_view text, std::size_t i) {
    const auto b0 = static_cast<unsigned char>(text[i]);
    std::size_t len = b0 < 0x80         ? 1
                      : (b0 >> 5) == 6  ? 2
                      : (b0 >> 4) == 14 ? 3
                      : (b0 >> 3) == 30 ? 4
                                        : 0;
    if (len == 0 || i + len > text.size()) return {0, 0};
    std::uint32_t cp = b0;
    if (len > 1) cp &= 0x7Fu >> len;
    for (std::size_t k = 1; k < len; ++k) {
        const std::uint32_t b = static_cast<unsigned char>(text[i + k]);
        if ((b & 0xC0u) != 0x80u) return {0, 0};
        cp = (cp << 6) | (b & 0x3Fu);
    }
    return {cp, len};
}

bool needs_escape(std::uint32_t cp) {
    return cp == '=' || cp == '\\' || cp < 0x20 || (cp >= 0x7F && cp <= 0x9F) ||
           (cp >= 0xD800 && cp <= 0xDFFF) || cp == 0xFFFE || cp == 0xFFFF;
}

// Lower-case hex, as OpenLCB_Java writes it (keys must match its files exactly).
std::string hex4(std::uint32_t v) {
    return "\\x" + base::hex_digits(v & 0xFFFF, 4, base::HexCase::kLower);
}

}  // namespace

std::string escape_backup_text(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        auto [cp, len] = decode_utf8(text, i);
        // Not UTF-8: the byte is kept visible as its code point; the format has no way to say
        // "raw byte", so it comes back as that character (a restore then finds it too long).
        if (len == 0) {
            out += hex4(static_cast<unsigned char>(text[i]));
            ++i;
            continue;
        }
        if (needs_escape(cp)) {
            out += hex4(cp);
        } else {
            out.append(text.substr(i, len));
        }
        i += len;
    }
    return out;
}

std::string variable_name_part(const Element& e) {
    return e.name.empty() ? "child" + std::to_string(e.content_index) : escape_backup_text(e.name);
}

std::string variable_name(const Layout& layout, const Cursor& c) {
    const Segment& seg = layout.document().segments[c.segment_index()];
    std::string key =
        seg.name.empty() ? "seg" + std::to_string(seg.content_index) : escape_backup_text(seg.name);
    for (std::size_t level = 0; level < c.group_depth(); ++level) {
        const Element& g = c.group(level);
        key += '.';
        key += variable_name_part(g);
        if (g.replication > 1) key += "(" + std::to_string(c.replica(level)) + ")";
    }
    key += '.';
    key += variable_name_part(c.element());
    return key;
}

std::string replica_names(const Cursor& c) {
    std::string out;
    for (std::size_t level = 0; level < c.group_depth(); ++level) {
        const Element& g = c.group(level);
        if (g.replication <= 1) continue;
        const std::string name = replica_name(g, c.replica(level));
        if (name.empty()) continue;
        if (!out.empty()) out += " / ";
        out += name;
    }
    return out;
}

bool names_variable(const Layout& layout, const Cursor& c, std::string_view text) {
    return variable_name(layout, c) == text || c.path() == text;
}

}  // namespace olcb::cdi
