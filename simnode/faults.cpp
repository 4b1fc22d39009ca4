#include "simnode/faults.hpp"

#include <charconv>
#include <utility>

namespace olcb::simnode {
namespace {

constexpr std::chrono::milliseconds kDefaultSlowReply{1200};
constexpr std::uint32_t kDefaultRejectTemporary = 3;
constexpr std::chrono::milliseconds kDefaultUnsolicitedPeriod{1000};
// Bounds keep a typo from stalling a node for days or rejecting forever.
constexpr std::uint32_t kMaxDelayMs = 600'000;
constexpr std::uint32_t kMaxRejects = 1'000'000;

constexpr std::pair<std::string_view, PipBit> kPipBits[] = {
    {"cdi", PipBit::kCdi},
    {"acdi", PipBit::kAcdi},
    {"snip", PipBit::kSnip},
    {"datagram", PipBit::kDatagram},
    {"memory", PipBit::kMemoryConfiguration},
    {"events", PipBit::kEvents},
};

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

// Applies one "name" or "name=value" to faults; false with error set when it is not valid.
bool apply(std::string_view item, FaultSet& faults, std::string& error) {
    std::string_view name = item;
    std::optional<std::string_view> value;
    if (const auto eq = item.find('='); eq != std::string_view::npos) {
        name = trim(item.substr(0, eq));
        value = trim(item.substr(eq + 1));
    }
    const auto no_value = [&](bool& flag) {
        if (value) {
            error = "fault '" + std::string(name) + "' takes no value";
            return false;
        }
        flag = true;
        return true;
    };
    const auto number = [&](std::uint32_t fallback, std::uint32_t max,
                            std::uint32_t min) -> std::optional<std::uint32_t> {
        if (!value) return fallback;
        auto v = parse_uint(*value, max);
        if (!v || *v < min) {
            error = "fault '" + std::string(name) + "': value '" + std::string(*value) +
                    "' is not a whole number in " + std::to_string(min) + ".." +
                    std::to_string(max);
            return std::nullopt;
        }
        return v;
    };

    if (name == "snip-mismatch") return no_value(faults.snip_mismatch);
    if (name == "acdi-version") return no_value(faults.acdi_version);
    if (name == "cdi-unterminated") return no_value(faults.cdi_unterminated);
    if (name == "cdi-padding") return no_value(faults.cdi_padding);
    if (name == "cdi-invalid") return no_value(faults.cdi_invalid);
    if (name == "int-byte-order") return no_value(faults.int_byte_order);
    if (name == "string-unterminated") return no_value(faults.string_unterminated);
    if (name == "eventid-byte-order") return no_value(faults.eventid_byte_order);
    if (name == "float-width") return no_value(faults.float_width);
    if (name == "write-dropped") return no_value(faults.write_dropped);
    if (name == "write-not-persisted") return no_value(faults.write_not_persisted);
    if (name == "readonly-writable") return no_value(faults.readonly_writable);
    if (name == "read-past-end") return no_value(faults.read_past_end);
    if (name == "space-info-short") return no_value(faults.space_info_short);
    if (name == "reply-form") return no_value(faults.reply_form);
    if (name == "no-datagram-ack") return no_value(faults.no_datagram_ack);
    if (name == "alias-conflict-ignored") return no_value(faults.alias_conflict_ignored);
    if (name == "pip-missing-bit") {
        if (!value) {
            faults.pip_missing = PipBit::kCdi;
            return true;
        }
        for (const auto& [text, bit] : kPipBits) {
            if (*value == text) {
                faults.pip_missing = bit;
                return true;
            }
        }
        error = "fault 'pip-missing-bit': '" + std::string(*value) +
                "' is not one of cdi, acdi, snip, datagram, memory, events";
        return false;
    }
    if (name == "slow-reply") {
        auto ms = number(kDefaultSlowReply.count(), kMaxDelayMs, 1);
        if (!ms) return false;
        faults.slow_reply = std::chrono::milliseconds(*ms);
        return true;
    }
    if (name == "reject-temporary") {
        auto n = number(kDefaultRejectTemporary, kMaxRejects, 1);
        if (!n) return false;
        faults.reject_temporary = *n;
        return true;
    }
    if (name == "unsolicited-traffic") {
        auto ms = number(kDefaultUnsolicitedPeriod.count(), kMaxDelayMs, 10);
        if (!ms) return false;
        faults.unsolicited_period = std::chrono::milliseconds(*ms);
        return true;
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

}  // namespace

bool FaultSet::none() const {
    return *this == FaultSet{};
}

const std::vector<FaultInfo>& fault_catalog() {
    static const std::vector<FaultInfo> catalog = {
        {"snip-mismatch", "", "SNIP model string differs from ACDI space 252 and the CDI"},
        {"acdi-version", "", "version bytes of spaces 252/251 are fixed+1 and var+1"},
        {"pip-missing-bit", "cdi|acdi|snip|datagram|memory|events (default cdi)",
         "Protocol Support Reply lacks a bit for a protocol the node serves"},
        {"cdi-unterminated", "", "space 0xFF holds the CDI without its terminating NUL"},
        {"cdi-padding", "", "space 0xFF has extra NULs and garbage after the NUL"},
        {"cdi-invalid", "", "served CDI violates the schema (no XML declaration, unknown element)"},
        {"int-byte-order", "", "<int> values stored little-endian"},
        {"string-unterminated", "", "<string> values fill the field with spaces, no NUL"},
        {"eventid-byte-order", "", "<eventid> values stored little-endian"},
        {"float-width", "", "<float> values stored with the next smaller precision"},
        {"write-dropped", "", "writes acknowledged but not stored"},
        {"write-not-persisted", "", "writes kept in RAM only: lost on reboot"},
        {"readonly-writable", "", "writes to spaces 0xFF and 252 accepted"},
        {"read-past-end", "", "a read at/after the end of a space returns zeros, not 0x1082"},
        {"space-info-short", "",
         "Get Address Space Information reports a too small highest address"},
        {"reply-form", "", "replies in byte-6 form to short-form requests and vice versa"},
        {"no-datagram-ack", "", "reply datagram sent before the Datagram Received OK"},
        {"slow-reply", "MS (default 1200)", "reply datagrams sent MS milliseconds late"},
        {"reject-temporary", "N (default 3)",
         "the first N datagrams are rejected with 0x2020, then it works"},
        {"alias-conflict-ignored", "", "alias not defended: no RID on CID, no AMR on conflict"},
        {"unsolicited-traffic", "MS (default 1000)",
         "a Verify Node ID Global every MS milliseconds"},
    };
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
    const auto flag = [&](bool on, const char* name) {
        if (on) out.emplace_back(name);
    };
    flag(f.snip_mismatch, "snip-mismatch");
    flag(f.acdi_version, "acdi-version");
    if (f.pip_missing) {
        for (const auto& [text, bit] : kPipBits) {
            if (bit == *f.pip_missing) out.push_back("pip-missing-bit=" + std::string(text));
        }
    }
    flag(f.cdi_unterminated, "cdi-unterminated");
    flag(f.cdi_padding, "cdi-padding");
    flag(f.cdi_invalid, "cdi-invalid");
    flag(f.int_byte_order, "int-byte-order");
    flag(f.string_unterminated, "string-unterminated");
    flag(f.eventid_byte_order, "eventid-byte-order");
    flag(f.float_width, "float-width");
    flag(f.write_dropped, "write-dropped");
    flag(f.write_not_persisted, "write-not-persisted");
    flag(f.readonly_writable, "readonly-writable");
    flag(f.read_past_end, "read-past-end");
    flag(f.space_info_short, "space-info-short");
    flag(f.reply_form, "reply-form");
    flag(f.no_datagram_ack, "no-datagram-ack");
    if (f.slow_reply.count() > 0) {
        out.push_back("slow-reply=" + std::to_string(f.slow_reply.count()));
    }
    if (f.reject_temporary > 0) {
        out.push_back("reject-temporary=" + std::to_string(f.reject_temporary));
    }
    flag(f.alias_conflict_ignored, "alias-conflict-ignored");
    if (f.unsolicited_period.count() > 0) {
        out.push_back("unsolicited-traffic=" + std::to_string(f.unsolicited_period.count()));
    }
    return out;
}

}  // namespace olcb::simnode
