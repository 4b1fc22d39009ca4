#include "cdi/simple_xml_reader.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

namespace olcb::cdi {
namespace {

// Character classes, one table lookup each. pugixml's name characters also include every byte
// from 0x80 up; those are kForeign here, and a name holding one makes the reader decline.
enum : std::uint8_t {
    kSpace = 1,          // the four XML white-space characters
    kNameStart = 2,      // ASCII letters, '_' and ':'
    kNameChar = 4,       // kNameStart plus digits, '-' and '.'
    kForeign = 8,        // bytes from 0x80 up
    kTextSpecial = 16,   // '&' and '\r': text needs decoding
    kValueSpecial = 32,  // '&', '\r', '\n', '\t': an attribute value needs decoding
};

constexpr std::array<std::uint8_t, 256> kClass = [] {
    std::array<std::uint8_t, 256> t{};
    for (unsigned char c : {' ', '\t', '\r', '\n'}) t[c] |= kSpace;
    for (int c = 'a'; c <= 'z'; ++c) t[c] |= kNameStart | kNameChar;
    for (int c = 'A'; c <= 'Z'; ++c) t[c] |= kNameStart | kNameChar;
    for (unsigned char c : {'_', ':'}) t[c] |= kNameStart | kNameChar;
    for (int c = '0'; c <= '9'; ++c) t[c] |= kNameChar;
    for (unsigned char c : {'-', '.'}) t[c] |= kNameChar;
    for (int c = 0x80; c <= 0xFF; ++c) t[c] |= kForeign;
    for (unsigned char c : {'&', '\r'}) t[c] |= kTextSpecial;
    for (unsigned char c : {'&', '\r', '\n', '\t'}) t[c] |= kValueSpecial;
    return t;
}();

bool has(char c, std::uint8_t cls) {
    return (kClass[static_cast<unsigned char>(c)] & cls) != 0;
}

const char* find(const char* p, const char* end, char c) {
    const void* hit = std::memchr(p, c, static_cast<std::size_t>(end - p));
    return hit == nullptr ? end : static_cast<const char*>(hit);
}

const char* search(const char* p, const char* end, std::string_view what) {
    const std::string_view rest(p, static_cast<std::size_t>(end - p));
    const std::size_t at = rest.find(what);
    return at == std::string_view::npos ? nullptr : p + at;
}

const char* skip_space(const char* p, const char* end) {
    while (p < end && has(*p, kSpace)) ++p;
    return p;
}

const char* skip_name(const char* p, const char* end) {
    while (p < end && has(*p, kNameChar)) ++p;
    return p;
}

// The character one of the five predefined entities at p ('&') stands for, advancing p past
// it; nullopt for anything else (character references, unknown names, a bare '&').
std::optional<char> predefined_entity(const char*& p, const char* end) {
    static constexpr std::pair<std::string_view, char> kEntities[] = {
        {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
    const std::string_view rest(p, static_cast<std::size_t>(end - p));
    for (const auto& [name, c] : kEntities) {
        if (rest.substr(0, name.size()) == name) {
            p += name.size();
            return c;
        }
    }
    return std::nullopt;
}

// Where a character next occurs, found with memchr and remembered: text is read forwards, so
// the whole source is searched once, and text without the character is never scanned.
class NextOccurrence {
public:
    NextOccurrence(char c, const char* begin, const char* end)
        : c_(c), end_(end), at_(find(begin, end, c)) {}

    // True when the character occurs in [from, to); from must not decrease between calls.
    bool within(const char* from, const char* to) {
        if (at_ < from) at_ = find(from, end_, c_);
        return at_ < to;
    }

private:
    char c_;
    const char* end_;
    const char* at_;
};

// How pugixml stores decoded characters: element text (parse_eol) turns CR LF and a lone CR
// into LF; an attribute value (parse_wconv_attribute) turns tab, LF, CR and CR LF into a space.
enum class Decoding { kText, kAttribute };

// Decodes entities and line ends of [p, end) as pugixml stores them; nullopt for an entity
// other than the five predefined ones. Undecoded text is returned as a view of the source.
std::optional<std::string_view> decode(const char* p, const char* end, Decoding how,
                                       XmlTree& tree) {
    const bool attribute = how == Decoding::kAttribute;
    const std::uint8_t special = attribute ? kValueSpecial : kTextSpecial;
    const char line_end = attribute ? ' ' : '\n';
    const char* q = p;
    while (q < end && !has(*q, special)) ++q;
    if (q == end) return std::string_view(p, static_cast<std::size_t>(end - p));
    std::string out(p, q);
    while (q < end) {
        if (*q == '&') {
            const std::optional<char> c = predefined_entity(q, end);
            if (!c) return std::nullopt;
            out += *c;
        } else if (*q == '\r') {
            out += line_end;
            ++q;
            if (q < end && *q == '\n') ++q;
        } else if (attribute && (*q == '\n' || *q == '\t')) {
            out += ' ';
            ++q;
        } else {
            out += *q++;
        }
    }
    return tree.keep(std::move(out));
}

}  // namespace

bool read_simple_xml(std::string_view text, std::size_t max_depth, XmlTree& tree) {
    const char* const begin = text.data();
    const char* const end = begin + text.size();
    // pugixml ends text at a NUL byte; whatever follows one is left to it.
    if (std::memchr(begin, 0, text.size()) != nullptr) return false;
    // A CDI spends about 25 bytes per element and far more per attribute. A hint only, capped
    // so that a huge input reserves nothing before it is known to be plain XML.
    constexpr std::size_t kMaxHint = std::size_t{1} << 16;
    tree.reserve(std::min(text.size() / 24 + 16, kMaxHint),
                 std::min(text.size() / 128 + 16, kMaxHint / 4));
    std::vector<std::uint32_t> open;  // the open elements, innermost last
    bool seen_root = false;
    NextOccurrence ampersand('&', begin, end);
    NextOccurrence carriage_return('\r', begin, end);
    const char* p = begin;
    while (p < end) {
        if (*p != '<') {
            // Text up to the next tag. White space alone is not kept (as without
            // parse_ws_pcdata); an element keeps its first other text.
            const char* const stop = find(p, end, '<');
            if (skip_space(p, stop) != stop) {
                if (open.empty()) return false;  // text outside the root element
                const std::uint32_t index = open.back();
                if (!tree.has_text(index)) {
                    if (ampersand.within(p, stop) || carriage_return.within(p, stop)) {
                        const std::optional<std::string_view> decoded =
                            decode(p, stop, Decoding::kText, tree);
                        if (!decoded) return false;
                        tree.set_text(index, *decoded);
                    } else {
                        tree.set_text(index,
                                      std::string_view(p, static_cast<std::size_t>(stop - p)));
                    }
                }
            }
            p = stop;
            continue;
        }
        if (end - p < 2) return false;
        const char next = p[1];
        if (next == '/') {
            // End tag: the open element's exact name, optional white space, '>'.
            if (open.empty()) return false;
            const std::uint32_t index = open.back();
            const std::string_view name = tree.name(index);
            const char* q = p + 2;
            if (static_cast<std::size_t>(end - q) < name.size() ||
                std::string_view(q, name.size()) != name) {
                return false;
            }
            q += name.size();
            if (q < end && has(*q, kNameChar | kForeign)) return false;
            q = skip_space(q, end);
            if (q == end || *q != '>') return false;
            tree.close(index);
            open.pop_back();
            p = q + 1;
        } else if (next == '?') {
            // A processing instruction or the XML declaration: skipped, as pugixml does
            // without parse_pi and parse_declaration.
            if (end - p < 3 || !has(p[2], kNameStart)) return false;
            const char* close = search(p + 2, end, "?>");
            if (close == nullptr) return false;
            p = close + 2;
        } else if (next == '!') {
            // Only a comment; CDATA and DOCTYPE are left to pugixml.
            if (end - p < 4 || p[2] != '-' || p[3] != '-') return false;
            const char* close = search(p + 4, end, "-->");
            if (close == nullptr) return false;
            p = close + 3;
        } else {
            // Start tag.
            if (!has(next, kNameStart)) return false;
            if (open.empty() && seen_root) return false;  // a second root element
            if (open.size() >= max_depth) return false;
            const char* const name_begin = p + 1;
            const char* q = skip_name(name_begin, end);
            if (q < end && has(*q, kForeign)) return false;
            const std::uint32_t index = tree.open(static_cast<std::size_t>(name_begin - begin),
                                                  static_cast<std::size_t>(q - name_begin));
            bool self_closing = false;
            for (;;) {
                // As pugixml: white space before each attribute, none needed before > or />.
                if (q == end) return false;
                if (*q == '>') {
                    ++q;
                    break;
                }
                if (*q == '/') {
                    if (end - q < 2 || q[1] != '>') return false;
                    q += 2;
                    self_closing = true;
                    break;
                }
                if (!has(*q, kSpace)) return false;
                q = skip_space(q, end);
                if (q == end || *q == '>' || *q == '/') continue;
                if (!has(*q, kNameStart)) return false;
                const char* const attribute_begin = q;
                q = skip_name(q, end);
                if (q < end && has(*q, kForeign)) return false;
                const std::string_view attribute(attribute_begin,
                                                 static_cast<std::size_t>(q - attribute_begin));
                q = skip_space(q, end);
                if (q == end || *q != '=') return false;
                q = skip_space(q + 1, end);
                if (q == end || (*q != '"' && *q != '\'')) return false;
                const char* const value_end = find(q + 1, end, *q);
                if (value_end == end) return false;
                const std::optional<std::string_view> value =
                    decode(q + 1, value_end, Decoding::kAttribute, tree);
                if (!value) return false;
                tree.add_attribute(attribute, *value);
                q = value_end + 1;
            }
            seen_root = true;
            if (self_closing) {
                tree.close(index);
            } else {
                open.push_back(index);
            }
            p = q;
        }
    }
    return open.empty() && seen_root;
}

}  // namespace olcb::cdi
