#include "conformance/checks/protection.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <cctype>

namespace olcb::conform {
namespace {

// Phrasings real CDIs use to say "leave this alone" (OpenMRN: "Do not change these settings.",
// "Set to 2 and do not change"); matched case-insensitively, straight or curly apostrophes.
constexpr std::string_view kPhrases[] = {
    "do not change",         "don't change",  "dont change",  "must not be changed",
    "must not change",       "do not modify", "don't modify", "must not be modified",
    "should not be changed", "never change",  "do not edit",  "don't edit",
};

std::string lower(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        // U+2019 (right single quotation mark) is written as an apostrophe by many editors.
        if (text.compare(i, 3, "\xE2\x80\x99") == 0) {
            out.push_back('\'');
            i += 2;
            continue;
        }
        out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(text[i]))));
    }
    return out;
}

std::string quoted(std::string_view what, const std::string& name) {
    return name.empty() ? std::string(what) : std::string(what) + " '" + name + "'";
}

// The reason a named element (variable, group or segment) carries in its texts, or "".
std::string text_reason(std::string_view what, const std::string& name,
                        const std::string& description) {
    if (says_do_not_change(name) || says_do_not_change(description)) {
        return "'do not change' in " + quoted(what, name);
    }
    return {};
}

}  // namespace

bool says_do_not_change(std::string_view text) {
    if (text.empty()) return false;
    const std::string l = lower(text);
    return std::any_of(std::begin(kPhrases), std::end(kPhrases),
                       [&](std::string_view p) { return l.find(p) != std::string::npos; });
}

std::string protection_reason(const cdi::Layout& layout, const cdi::Cursor& c) {
    const cdi::Element& v = c.element();
    if (v.kind == cdi::ElementKind::kAction) return "<action> triggers a command";
    if (auto r = text_reason("variable", v.name, v.description); !r.empty()) return r;
    // Innermost group first: the nearest reason is the one a user recognises.
    for (std::size_t level = c.group_depth(); level-- > 0;) {
        const cdi::Element& g = c.group(level);
        if (g.hints.read_only) return quoted("read-only hint of group", g.name);
        if (auto r = text_reason("group", g.name, g.description); !r.empty()) return r;
    }
    const cdi::Segment& seg = layout.document().segments[c.segment_index()];
    return text_reason("segment", seg.name, seg.description);
}

bool key_matches(std::string_view pattern, std::string_view key) {
    const std::string p(pattern), k(key);
    return ::fnmatch(p.c_str(), k.c_str(), 0) == 0;
}

std::string selection_reason(const ProtectionRules& rules, std::string_view key) {
    for (const std::string& glob : rules.exclude) {
        if (key_matches(glob, key)) return "--exclude '" + glob + "'";
    }
    if (rules.only.empty()) return {};
    for (const std::string& glob : rules.only) {
        if (key_matches(glob, key)) return {};
    }
    return "not matched by --only";
}

}  // namespace olcb::conform
