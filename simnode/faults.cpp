#include "simnode/faults.hpp"

#include <algorithm>
#include <charconv>
#include <utility>

#include "simnode/faults/fault_catalog.hpp"
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {
namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

std::optional<std::uint32_t> parse_uint(std::string_view text, std::uint32_t max) {
    std::uint32_t v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || v > max) return std::nullopt;
    return v;
}

// MS[:JITTER]: both whole milliseconds; MS >= 1 unless a jitter is given.
std::optional<FaultValue> parse_ms_jitter(const FaultDecl& d, std::optional<std::string_view> value,
                                          std::string& error) {
    std::optional<std::uint32_t> ms = d.param.fallback, jitter = 0;
    if (value) {
        const auto colon = value->find(':');
        ms = parse_uint(value->substr(0, colon), d.param.max);
        if (colon != std::string_view::npos)
            jitter = parse_uint(value->substr(colon + 1), d.param.max);
    }
    if (!ms || !jitter || *ms + *jitter == 0) {
        error = "fault '" + std::string(d.name) + "': value '" + std::string(value.value_or("")) +
                "' is not MS or MS:JITTER (whole milliseconds 0.." + std::to_string(d.param.max) +
                ", not both 0)";
        return std::nullopt;
    }
    return FaultValue{*ms, *jitter};
}

// N[:MS]: a timeout exponent and a delay within the 2^N s it promises (kExponentMs).
std::optional<FaultValue> parse_exponent_ms(const FaultDecl& d,
                                            std::optional<std::string_view> value,
                                            std::string& error) {
    std::optional<std::uint32_t> n = d.param.fallback;
    std::optional<std::string_view> ms_text;
    if (value) {
        const auto colon = value->find(':');
        n = parse_uint(value->substr(0, colon), d.param.max);
        if (colon != std::string_view::npos) ms_text = value->substr(colon + 1);
    }
    const std::string what = "fault '" + std::string(d.name) + "': value '" +
                             std::string(value.value_or("")) + "' is not N or N:MS";
    if (!n || *n < d.param.min) {
        error = what + " (N a whole number in " + std::to_string(d.param.min) + ".." +
                std::to_string(d.param.max) + ")";
        return std::nullopt;
    }
    // The delay stays below the promise: a reply later than 2^N s would break it.
    const std::uint32_t promised_ms = (1u << *n) * 1000u;
    const std::uint32_t max_ms = std::min(promised_ms - 1, kMaxDelayMs);
    if (!ms_text) return FaultValue{*n, std::min(promised_ms / 2, kMaxDelayMs)};
    const auto ms = parse_uint(*ms_text, max_ms);
    if (!ms) {
        error = what + " (MS whole milliseconds 0.." + std::to_string(max_ms) + ", below the 2^" +
                std::to_string(*n) + " s promised)";
        return std::nullopt;
    }
    return FaultValue{*n, *ms};
}

std::optional<FaultValue> parse_choice(const FaultDecl& d, std::optional<std::string_view> value,
                                       std::string& error) {
    if (!value) return FaultValue{d.param.fallback};
    std::string known;
    for (std::size_t i = 0; i < d.param.choices.size(); ++i) {
        if (*value == d.param.choices[i]) return FaultValue{static_cast<std::uint32_t>(i + 1)};
        known += (known.empty() ? "" : ", ") + std::string(d.param.choices[i]);
    }
    error =
        "fault '" + std::string(d.name) + "': '" + std::string(*value) + "' is not one of " + known;
    return std::nullopt;
}

// The value of "name[=value]" for fault d; nullopt with error set when it is not valid.
std::optional<FaultValue> parse_value(const FaultDecl& d, std::optional<std::string_view> value,
                                      std::string& error) {
    switch (d.param.kind) {
        case ParamKind::kNone:
            if (!value) return FaultValue{1};
            error = "fault '" + std::string(d.name) + "' takes no value";
            return std::nullopt;
        case ParamKind::kChoice:
            return parse_choice(d, value, error);
        case ParamKind::kMsJitter:
            return parse_ms_jitter(d, value, error);
        case ParamKind::kExponentMs:
            return parse_exponent_ms(d, value, error);
        case ParamKind::kNumber:
            break;
    }
    std::optional<std::uint32_t> v = d.param.fallback;
    if (value) v = parse_uint(*value, d.param.max);
    if (!v || *v < d.param.min) {
        error = "fault '" + std::string(d.name) + "': value '" + std::string(value.value_or("")) +
                "' is not a whole number in " + std::to_string(d.param.min) + ".." +
                std::to_string(d.param.max);
        return std::nullopt;
    }
    return FaultValue{*v};
}

// Applies one "name" or "name=value" to faults; false with error set when it is not valid.
bool apply(std::string_view item, FaultSet& faults, std::string& error) {
    std::string_view name = item;
    std::optional<std::string_view> value;
    if (const auto eq = item.find('='); eq != std::string_view::npos) {
        name = trim(item.substr(0, eq));
        value = trim(item.substr(eq + 1));
    }
    if (const FaultDecl* d = find_fault(name)) {
        const auto v = parse_value(*d, value, error);
        if (v) set_fault(faults, *d, *v);
        return v.has_value();
    }
    error = "unknown fault '" + std::string(name) + "' (known: ";
    bool first = true;
    for (const auto& f : fault_catalog()) {
        if (!first) error += ", ";
        error += f.name;
        first = false;
    }
    error += ")";
    return false;
}

// The name parse_faults() reads back to fault d of f; nullopt when it is off.
std::optional<std::string> name_if_set(const FaultSet& f, const FaultDecl& d) {
    const FaultValue v = fault_value(f, d);
    if (v == FaultValue{}) return std::nullopt;
    std::string text(d.name);
    switch (d.param.kind) {
        case ParamKind::kNone:
            return text;
        case ParamKind::kChoice:
            return text + "=" + std::string(d.param.choices.at(v.value - 1));
        case ParamKind::kNumber:
            return text + "=" + std::to_string(v.value);
        case ParamKind::kExponentMs:
            return text + "=" + std::to_string(v.value) + ":" + std::to_string(v.jitter);
        case ParamKind::kMsJitter:
            break;
    }
    text += "=" + std::to_string(v.value);
    if (v.jitter > 0) text += ":" + std::to_string(v.jitter);
    return text;
}

}  // namespace

FaultValue FaultSet::value(std::string_view name) const {
    const auto it = by_name.find(name);
    return it == by_name.end() ? FaultValue{} : it->second;
}

const std::vector<FaultInfo>& fault_catalog() {
    // FaultInfo holds views: the generated parameter texts live as long as the catalogue.
    static const std::vector<std::string> parameters = [] {
        std::vector<std::string> out;
        for (const FaultDecl& d : fault_decls()) out.push_back(help_parameter(d));
        return out;
    }();
    static const std::vector<FaultInfo> catalog = [] {
        std::vector<FaultInfo> out;
        for (std::size_t i = 0; i < fault_decls().size(); ++i) {
            const FaultDecl& d = fault_decls()[i];
            out.push_back({d.name, parameters[i], d.summary});
        }
        return out;
    }();
    return catalog;
}

std::vector<std::string> fault_names() {
    std::vector<std::string> names;
    for (const auto& f : fault_catalog()) names.emplace_back(f.name);
    return names;
}

std::optional<FaultSet> parse_faults(const std::vector<std::string>& names, std::string& error) {
    FaultSet faults;
    for (const std::string& entry : names) {
        std::string_view rest = entry;
        while (true) {
            const auto comma = rest.find(',');
            const std::string_view item = trim(rest.substr(0, comma));
            if (!item.empty() && !apply(item, faults, error)) return std::nullopt;
            if (comma == std::string_view::npos) break;
            rest.remove_prefix(comma + 1);
        }
    }
    return faults;
}

std::vector<std::string> to_names(const FaultSet& f) {
    std::vector<std::string> out;
    for (const FaultDecl& d : fault_decls()) {
        if (auto name = name_if_set(f, d)) out.push_back(std::move(*name));
    }
    return out;
}

}  // namespace olcb::simnode
