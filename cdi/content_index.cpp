#include "cdi/content_index.hpp"

#include <cstring>

namespace olcb::cdi {
namespace {

const char* find_char(const char* p, const char* end, char c) {
    const void* hit = std::memchr(p, c, static_cast<std::size_t>(end - p));
    return static_cast<const char*>(hit);
}

// Past the first occurrence of what at or after p, or nullptr when it never occurs. memchr on
// its first character: string_view::find goes character by character.
const char* past(const char* p, const char* end, std::string_view what) {
    const std::size_t rest = what.size() - 1;
    while ((p = find_char(p, end, what[0])) != nullptr) {
        if (static_cast<std::size_t>(end - p) <= rest) return nullptr;
        if (std::memcmp(p + 1, what.data() + 1, rest) == 0) return p + 1 + rest;
        ++p;
    }
    return nullptr;
}

bool starts_with(const char* p, const char* end, std::string_view what) {
    return static_cast<std::size_t>(end - p) >= what.size() &&
           std::memcmp(p, what.data(), what.size()) == 0;
}

// Past the '>' ending the tag whose name starts at p, quoted attribute values skipped (they may
// hold '>'); nullptr when the tag never ends. self_closing tells "<x/>".
const char* tag_end(const char* p, const char* end, bool& self_closing) {
    char quote = 0;
    for (; p < end; ++p) {
        if (quote != 0) {
            if (*p == quote) quote = 0;
        } else if (*p == '"' || *p == '\'') {
            quote = *p;
        } else if (*p == '>') {
            self_closing = p[-1] == '/';
            return p + 1;
        }
    }
    return nullptr;
}

enum class Token : std::uint8_t {
    kNode,   // a text run, comment, CDATA section or PI: one content node
    kOpen,   // a start tag
    kEmpty,  // an empty-element tag <x/>
    kClose,  // an end tag
    kStop,   // the end of the text, or something no content node can be (a DOCTYPE, a bad tag)
};

// The token at p, advancing p past it.
Token next_token(const char*& p, const char* end) {
    if (p >= end) return Token::kStop;
    if (*p != '<') {
        const char* lt = find_char(p, end, '<');
        p = lt == nullptr ? end : lt;
        return Token::kNode;
    }
    const char* q = p + 1;
    if (q == end) return Token::kStop;
    if (*q == '/') {
        p = find_char(q, end, '>');
        if (p == nullptr) return Token::kStop;
        ++p;
        return Token::kClose;
    }
    if (*q == '?') {
        p = past(q + 1, end, "?>");
    } else if (starts_with(q, end, "!--")) {
        p = past(q + 3, end, "-->");
    } else if (starts_with(q, end, "![CDATA[")) {
        p = past(q + 8, end, "]]>");
    } else if (*q == '!') {
        return Token::kStop;  // a DOCTYPE inside an element is malformed
    } else {
        bool self_closing = false;
        p = tag_end(q, end, self_closing);
        if (p == nullptr) return Token::kStop;
        return self_closing ? Token::kEmpty : Token::kOpen;
    }
    return p == nullptr ? Token::kStop : Token::kNode;
}

}  // namespace

std::uint32_t non_element_nodes_between(std::string_view text, std::size_t from, int depth,
                                        std::size_t to) {
    if (from == 0 || to == 0 || from >= to || to > text.size()) return 0;
    const char* p = text.data() + from - 1;  // the '<' of the element at from
    const char* const end = text.data() + to - 1;
    std::uint32_t nodes = 0;
    for (;;) {
        switch (next_token(p, end)) {
            case Token::kNode:
                if (depth == 0) ++nodes;
                break;
            case Token::kOpen:
                ++depth;
                break;
            case Token::kEmpty:
                break;
            case Token::kClose:
                --depth;
                break;
            case Token::kStop:
                return nodes;
        }
    }
}

std::size_t end_of_element(std::string_view text, std::size_t from, int depth) {
    if (from == 0 || from > text.size()) return 0;
    const char* p = text.data() + from - 1;  // the '<' of the element at from
    const char* const end = text.data() + text.size();
    for (;;) {
        switch (next_token(p, end)) {
            case Token::kNode:
                break;
            case Token::kOpen:
                ++depth;
                break;
            case Token::kEmpty:
                if (depth < 0) return static_cast<std::size_t>(p - text.data());
                break;
            case Token::kClose:
                if (--depth < 0) return static_cast<std::size_t>(p - text.data());
                break;
            case Token::kStop:
                return 0;
        }
    }
}

std::size_t end_of_start_tag(std::string_view text, std::size_t from) {
    if (from == 0 || from > text.size()) return 0;
    bool self_closing = false;
    const char* p = tag_end(text.data() + from, text.data() + text.size(), self_closing);
    return p == nullptr ? 0 : static_cast<std::size_t>(p - text.data());
}

}  // namespace olcb::cdi
