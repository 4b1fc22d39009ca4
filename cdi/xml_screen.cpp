#include "cdi/xml_screen.hpp"

#include <cstdint>
#include <cstring>
#include <string_view>

#include "base/utf8.hpp"
#include "cdi/content_index.hpp"
#include "cdi/decimal.hpp"

namespace olcb::cdi {
namespace {

// A run of non-ASCII bytes: valid UTF-8 without U+FFFE or U+FFFF (the only non-ASCII code points
// of valid UTF-8 that XML 1.0 forbids; surrogates are not valid UTF-8).
bool plain_non_ascii(std::string_view run) {
    if (!base::is_valid_utf8(run)) return false;
    for (std::size_t i = 0; i + 2 < run.size(); ++i) {
        if (run[i] == '\xEF' && run[i + 1] == '\xBF' &&
            (run[i + 2] == '\xBE' || run[i + 2] == '\xBF'))
            return false;
    }
    return true;
}

// Sixteen bytes at once through the compiler's generic vectors (SSE2 on x86-64, scalar code
// elsewhere): a byte loop over a 50 KB CDI costs more than pugixml's own parse.
using Bytes16 = std::uint8_t __attribute__((vector_size(16)));
using Words2 = std::uint64_t __attribute__((vector_size(16)));

// True when none of the 16 bytes at p is above 0x7F or a control other than tab, LF and CR.
bool plain_ascii16(const char* p) {
    Bytes16 v;
    std::memcpy(&v, p, sizeof v);
    const Bytes16 allowed_control = (v == 0x09) | (v == 0x0A) | (v == 0x0D);
    const Bytes16 flagged = ((v < 0x20) & ~allowed_control) | (v > 0x7F);
    Words2 words;
    std::memcpy(&words, &flagged, sizeof words);
    return (words[0] | words[1]) == 0;
}

// Every byte is part of a character XML allows: tab, newline, carriage return, printable ASCII,
// or valid UTF-8. *ascii tells whether every byte was ASCII.
bool plain_characters(std::string_view text, bool* ascii) {
    *ascii = true;
    const char* p = text.data();
    const char* const end = p + text.size();
    while (p < end) {
        if (end - p >= 16 && plain_ascii16(p)) {
            p += 16;
            continue;
        }
        const auto c = static_cast<unsigned char>(*p);
        if (c < 0x20) {
            if (c != '\t' && c != '\n' && c != '\r') return false;
            ++p;
        } else if (c < 0x80) {
            ++p;
        } else {
            *ascii = false;
            const char* q = p;
            while (q < end && static_cast<unsigned char>(*q) >= 0x80) ++q;
            if (!plain_non_ascii({p, static_cast<std::size_t>(q - p)})) return false;
            p = q;
        }
    }
    return true;
}

bool is_xml_char(std::uint32_t c) {
    return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) ||
           (c >= 0xE000 && c <= 0xFFFD) || (c >= 0x10000 && c <= 0x10FFFF);
}

// The character reference after "&#" (decimal, or hexadecimal after 'x') up to its ';'.
bool plain_char_reference(std::string_view rest) {
    const bool hex = !rest.empty() && rest[0] == 'x';
    if (hex) rest.remove_prefix(1);
    std::uint32_t value = 0;
    std::size_t digits = 0;
    for (; digits < rest.size() && rest[digits] != ';'; ++digits) {
        const char c = rest[digits];
        std::uint32_t d = 0;
        if (c >= '0' && c <= '9') {
            d = static_cast<std::uint32_t>(c - '0');
        } else if (hex && ((c | 0x20) >= 'a' && (c | 0x20) <= 'f')) {
            d = static_cast<std::uint32_t>((c | 0x20) - 'a' + 10);
        } else {
            return false;
        }
        value = value * (hex ? 16 : 10) + d;
        if (digits >= 7) return false;  // beyond any character
    }
    return digits > 0 && digits < rest.size() && is_xml_char(value);
}

// Every '&' starts a predefined entity or a character reference to a legal character.
bool plain_references(std::string_view text) {
    for (std::size_t at = text.find('&'); at != std::string_view::npos;
         at = text.find('&', at + 1)) {
        const std::string_view rest = text.substr(at + 1);
        if (rest.starts_with("amp;") || rest.starts_with("lt;") || rest.starts_with("gt;") ||
            rest.starts_with("quot;") || rest.starts_with("apos;"))
            continue;
        if (!rest.starts_with('#') || !plain_char_reference(rest.substr(1))) return false;
    }
    return true;
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if ((a[i] | 0x20) != (b[i] | 0x20)) return false;
    }
    return true;
}

bool is_name_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
}

// A processing instruction at `at` (its '<'): an ASCII target without a colon that libxml2
// neither refuses nor warns about (no "xml" prefix except the W3C's xml-stylesheet and
// xml-model), then whitespace or "?>", and an end.
bool plain_instruction(std::string_view text, std::size_t at) {
    std::size_t end = at + 2;
    if (end >= text.size() || !is_name_char(text[end]) || text[end] == '-' || text[end] == '.' ||
        (text[end] >= '0' && text[end] <= '9'))
        return false;
    while (end < text.size() && is_name_char(text[end])) ++end;
    const std::string_view target = text.substr(at + 2, end - at - 2);
    if (target.size() >= 3 && equals_ignoring_case(target.substr(0, 3), "xml") &&
        target != "xml-stylesheet" && target != "xml-model")
        return false;
    if (end >= text.size() || !(is_xml_space(text[end]) || text.substr(end, 2) == "?>"))
        return false;
    return text.find("?>", end) != std::string_view::npos;
}

// "<!" only opens comments, each free of "--" until its "-->"; "<?" opens a plain instruction
// (the declaration at 0 is after_declaration's to judge).
bool plain_markup(std::string_view text) {
    for (std::size_t at = text.find('!'); at != std::string_view::npos;
         at = text.find('!', at + 1)) {
        if (at == 0 || text[at - 1] != '<') continue;
        if (text.substr(at + 1, 2) != "--") return false;
        const std::size_t body = at + 3;
        const std::size_t dashes = text.find("--", body);
        if (dashes == std::string_view::npos || text.substr(dashes, 3) != "-->") return false;
        at = dashes + 2;
    }
    for (std::size_t at = text.find('?'); at != std::string_view::npos;
         at = text.find('?', at + 1)) {
        if (at > 1 && text[at - 1] == '<' && !plain_instruction(text, at - 1)) return false;
    }
    return text.find("]]>") == std::string_view::npos;
}

// pseudo-attribute="value" (either quote) after whitespace; value is left on what was read.
bool read_pseudo_attribute(std::string_view& rest, std::string_view name, std::string_view& value) {
    std::size_t i = 0;
    while (i < rest.size() && is_xml_space(rest[i])) ++i;
    if (i == 0 || rest.substr(i, name.size()) != name) return false;
    i += name.size();
    while (i < rest.size() && is_xml_space(rest[i])) ++i;
    if (i >= rest.size() || rest[i] != '=') return false;
    ++i;
    while (i < rest.size() && is_xml_space(rest[i])) ++i;
    if (i >= rest.size() || (rest[i] != '"' && rest[i] != '\'')) return false;
    const std::size_t close = rest.find(rest[i], i + 1);
    if (close == std::string_view::npos) return false;
    value = rest.substr(i + 1, close - i - 1);
    rest.remove_prefix(close + 1);
    return true;
}

// Where the content before the root starts: after `<?xml version="1.0" encoding="UTF-8"
// standalone="yes"?>` (encoding and standalone optional), or at 0 without one; npos for any
// other declaration.
std::size_t after_declaration(std::string_view text) {
    if (!text.starts_with("<?")) return 0;
    if (!text.starts_with("<?xml") || text.size() < 6 || !is_xml_space(text[5]))
        return std::string_view::npos;
    std::string_view rest = text.substr(5);
    std::string_view value;
    if (!read_pseudo_attribute(rest, "version", value) || value != "1.0")
        return std::string_view::npos;
    std::string_view probe = rest;
    if (read_pseudo_attribute(probe, "encoding", value)) {
        if (!equals_ignoring_case(value, "utf-8")) return std::string_view::npos;
        rest = probe;
    }
    probe = rest;
    if (read_pseudo_attribute(probe, "standalone", value)) {
        if (value != "yes" && value != "no") return std::string_view::npos;
        rest = probe;
    }
    std::size_t i = 0;
    while (i < rest.size() && is_xml_space(rest[i])) ++i;
    if (rest.substr(i, 2) != "?>") return std::string_view::npos;
    return text.size() - rest.size() + i + 2;
}

// Only whitespace, comments and instructions (checked already) in [from, to).
bool only_misc(std::string_view text, std::size_t from, std::size_t to) {
    while (from < to) {
        const bool comment = text.substr(from, 4) == "<!--";
        if (is_xml_space(text[from])) {
            ++from;
        } else if (comment || text.substr(from, 2) == "<?") {
            const std::size_t close = text.find(comment ? "-->" : "?>", from + 2);
            if (close == std::string_view::npos) return false;
            from = close + (comment ? 3 : 2);
            if (from > to) return false;
        } else {
            return false;
        }
    }
    return true;
}

// One root element, and nothing but whitespace and comments before and after it.
bool plain_outside_root(const LoadedXml& xml, std::size_t start) {
    const pugi::xml_node first = xml.document().first_child();
    if (!first || first.type() != pugi::node_element || first.next_sibling()) return false;
    const std::size_t root = source_offset(first);
    if (root == 0 || !only_misc(xml.text(), start, root - 1)) return false;
    const auto [last, depth] = last_element(first);
    const std::size_t end = end_of_element(xml.text(), source_offset(last), depth);
    return end != 0 && only_misc(xml.text(), end, xml.text().size());
}

}  // namespace

XmlScreen screen(const LoadedXml& xml) {
    XmlScreen out;
    if (!xml.result()) return out;
    const std::string_view text = xml.text();
    const std::size_t start = after_declaration(text);
    out.passes = start != std::string_view::npos && plain_characters(text, &out.ascii) &&
                 plain_references(text) && plain_markup(text) && plain_outside_root(xml, start);
    return out;
}

}  // namespace olcb::cdi
