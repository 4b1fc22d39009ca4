#include "simnode/faults.hpp"

#include <charconv>
#include <utility>

namespace olcb::simnode {
namespace {

constexpr std::chrono::milliseconds kDefaultSlowReply{1200};
constexpr std::uint32_t kDefaultRejectTemporary = 3;
constexpr std::chrono::milliseconds kDefaultUnsolicitedPeriod{1000};
constexpr std::chrono::milliseconds kDefaultAbortSilence{3000};
constexpr std::uint32_t kDefaultRebootOnWrite = 1;
constexpr std::chrono::milliseconds kDefaultLatency{200};
constexpr std::chrono::milliseconds kDefaultMaskIgnoredSilence{5000};
// Bounds keep a typo from stalling a node for days or rejecting forever.
constexpr std::uint32_t kMaxDelayMs = 600'000;
constexpr std::uint32_t kMaxCount = 1'000'000;

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

// The faults without a parameter: one flag of FaultSet each.
struct FlagFault {
    std::string_view name;
    bool FaultSet::*member;
};

constexpr FlagFault kFlagFaults[] = {
    {"snip-mismatch", &FaultSet::snip_mismatch},
    {"snip-invalid-utf8", &FaultSet::snip_invalid_utf8},
    {"stream-wrong-count", &FaultSet::stream_wrong_count},
    {"stream-no-complete", &FaultSet::stream_no_complete},
    {"stream-ignore-proceed", &FaultSet::stream_ignore_proceed},
    {"stream-exceed-buffer", &FaultSet::stream_exceed_buffer},
    {"acdi-version", &FaultSet::acdi_version},
    {"cdi-unterminated", &FaultSet::cdi_unterminated},
    {"cdi-padding", &FaultSet::cdi_padding},
    {"cdi-invalid", &FaultSet::cdi_invalid},
    {"int-byte-order", &FaultSet::int_byte_order},
    {"string-unterminated", &FaultSet::string_unterminated},
    {"eventid-byte-order", &FaultSet::eventid_byte_order},
    {"float-width", &FaultSet::float_width},
    {"write-dropped", &FaultSet::write_dropped},
    {"write-not-persisted", &FaultSet::write_not_persisted},
    {"readonly-writable", &FaultSet::readonly_writable},
    {"read-past-end", &FaultSet::read_past_end},
    {"space-info-short", &FaultSet::space_info_short},
    {"reply-form", &FaultSet::reply_form},
    {"no-datagram-ack", &FaultSet::no_datagram_ack},
    {"alias-conflict-ignored", &FaultSet::alias_conflict_ignored},
    {"reset-rejected", &FaultSet::reset_rejected},
    {"lock-rejected", &FaultSet::lock_rejected},
    {"factory-reset-on-version-change", &FaultSet::factory_reset_on_version_change},
    {"new-alias-on-reboot", &FaultSet::new_alias_on_reboot},
    {"field-reads-only", &FaultSet::field_reads_only},
    {"unknown-space-0x1041", &FaultSet::unknown_space_0x1041},
    {"readonly-0x1041", &FaultSet::readonly_0x1041},
    {"read-past-end-garbage", &FaultSet::read_past_end_garbage},
    {"write-past-end-spills", &FaultSet::write_past_end_spills},
    {"write-past-end-grows", &FaultSet::write_past_end_grows},
    {"highest-unreadable", &FaultSet::highest_unreadable},
    {"events-stale-after-write", &FaultSet::events_stale_after_write},
    {"events-missing", &FaultSet::events_missing},
    {"duplicate-id-silent", &FaultSet::duplicate_id_silent},
    {"burst-drops", &FaultSet::burst_drops},
    {"answers-standard-frames", &FaultSet::answers_standard_frames},
};

// The faults with a whole-number parameter (0 = off, so min >= 1).
struct NumberFault {
    std::string_view name;
    std::uint32_t fallback, min, max;
    std::uint32_t (*get)(const FaultSet&);
    void (*set)(FaultSet&, std::uint32_t);
};

using Ms = std::chrono::milliseconds;
constexpr NumberFault kNumberFaults[] = {
    {"slow-reply", kDefaultSlowReply.count(), 1, kMaxDelayMs,
     [](const FaultSet& f) { return static_cast<std::uint32_t>(f.slow_reply.count()); },
     [](FaultSet& f, std::uint32_t v) { f.slow_reply = Ms(v); }},
    {"reject-temporary", kDefaultRejectTemporary, 1, kMaxCount,
     [](const FaultSet& f) { return f.reject_temporary; },
     [](FaultSet& f, std::uint32_t v) { f.reject_temporary = v; }},
    {"unsolicited-traffic", kDefaultUnsolicitedPeriod.count(), 10, kMaxDelayMs,
     [](const FaultSet& f) { return static_cast<std::uint32_t>(f.unsolicited_period.count()); },
     [](FaultSet& f, std::uint32_t v) { f.unsolicited_period = Ms(v); }},
    {"abort-on-value", kDefaultAbortSilence.count(), 1, kMaxDelayMs,
     [](const FaultSet& f) { return static_cast<std::uint32_t>(f.abort_on_value.count()); },
     [](FaultSet& f, std::uint32_t v) { f.abort_on_value = Ms(v); }},
    {"mask-ignored", kDefaultMaskIgnoredSilence.count(), 1, kMaxDelayMs,
     [](const FaultSet& f) { return static_cast<std::uint32_t>(f.mask_ignored.count()); },
     [](FaultSet& f, std::uint32_t v) { f.mask_ignored = Ms(v); }},
    {"reboot-on-write", kDefaultRebootOnWrite, 1, kMaxCount,
     [](const FaultSet& f) { return f.reboot_on_write; },
     [](FaultSet& f, std::uint32_t v) { f.reboot_on_write = v; }},
};

// latency=MS[:JITTER]: both whole milliseconds; MS >= 1 unless a jitter is given.
bool apply_latency(std::optional<std::string_view> value, FaultSet& faults, std::string& error) {
    std::optional<std::uint32_t> ms = kDefaultLatency.count(), jitter = 0;
    if (value) {
        const auto colon = value->find(':');
        ms = parse_uint(value->substr(0, colon), kMaxDelayMs);
        if (colon != std::string_view::npos)
            jitter = parse_uint(value->substr(colon + 1), kMaxDelayMs);
    }
    if (!ms || !jitter || *ms + *jitter == 0) {
        error = "fault 'latency': value '" + std::string(value.value_or("")) +
                "' is not MS or MS:JITTER (whole milliseconds 0.." + std::to_string(kMaxDelayMs) +
                ", not both 0)";
        return false;
    }
    faults.latency = Ms(*ms);
    faults.latency_jitter = Ms(*jitter);
    return true;
}

bool apply_pip_missing(std::optional<std::string_view> value, FaultSet& faults,
                       std::string& error) {
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

// Applies one "name" or "name=value" to faults; false with error set when it is not valid.
bool apply(std::string_view item, FaultSet& faults, std::string& error) {
    std::string_view name = item;
    std::optional<std::string_view> value;
    if (const auto eq = item.find('='); eq != std::string_view::npos) {
        name = trim(item.substr(0, eq));
        value = trim(item.substr(eq + 1));
    }
    for (const FlagFault& f : kFlagFaults) {
        if (name != f.name) continue;
        if (value) {
            error = "fault '" + std::string(name) + "' takes no value";
            return false;
        }
        faults.*f.member = true;
        return true;
    }
    for (const NumberFault& f : kNumberFaults) {
        if (name != f.name) continue;
        std::optional<std::uint32_t> v = f.fallback;
        if (value) v = parse_uint(*value, f.max);
        if (!v || *v < f.min) {
            error = "fault '" + std::string(name) + "': value '" + std::string(*value) +
                    "' is not a whole number in " + std::to_string(f.min) + ".." +
                    std::to_string(f.max);
            return false;
        }
        f.set(faults, *v);
        return true;
    }
    if (name == "pip-missing-bit") return apply_pip_missing(value, faults, error);
    if (name == "latency") return apply_latency(value, faults, error);
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

// The name parse_faults() reads back to fault `name` of f; nullopt when it is off.
std::optional<std::string> name_if_set(const FaultSet& f, std::string_view name) {
    for (const FlagFault& flag : kFlagFaults) {
        if (name == flag.name) {
            return f.*flag.member ? std::optional<std::string>(name) : std::nullopt;
        }
    }
    for (const NumberFault& n : kNumberFaults) {
        if (name != n.name) continue;
        if (n.get(f) == 0) return std::nullopt;
        return std::string(name) + "=" + std::to_string(n.get(f));
    }
    if (name == "latency" && (f.latency.count() > 0 || f.latency_jitter.count() > 0)) {
        std::string text = "latency=" + std::to_string(f.latency.count());
        if (f.latency_jitter.count() > 0) text += ":" + std::to_string(f.latency_jitter.count());
        return text;
    }
    if (name == "pip-missing-bit" && f.pip_missing) {
        for (const auto& [text, bit] : kPipBits) {
            if (bit == *f.pip_missing) return "pip-missing-bit=" + std::string(text);
        }
    }
    return std::nullopt;
}

}  // namespace

bool FaultSet::none() const {
    return *this == FaultSet{};
}

const std::vector<FaultInfo>& fault_catalog() {
    static const std::vector<FaultInfo> catalog = {
        {"snip-mismatch", "", "SNIP model string differs from ACDI space 252 and the CDI"},
        {"snip-invalid-utf8", "",
         "SNIP user name ends in the bytes FF FE, which are not UTF-8 (space 251 stays valid)"},
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
        {"abort-on-value", "MS (default 3000)",
         "a SNIP request while the first 253 int was changed: silent MS ms, then a restart"},
        {"reboot-on-write", "N (default 1)",
         "the Nth stored write restarts the node without its Write Reply (once)"},
        {"reset-rejected", "", "Reset/Reboot rejected with 0x1041; the node does not restart"},
        {"lock-rejected", "", "Lock/Reserve rejected with 0x1041"},
        {"factory-reset-on-version-change", "",
         "a restart while the first 253 int was changed factory-resets the configuration"},
        {"new-alias-on-reboot", "", "every restart reserves a different alias"},
        {"field-reads-only", "",
         "spaces 251/252 return one ACDI field per read, 1 byte off a field start"},
        {"unknown-space-0x1041", "", "read/write of an unknown space rejected 0x1041, not 0x1081"},
        {"readonly-0x1041", "", "write to a read-only space rejected 0x1041, not 0x1083"},
        {"latency", "MS[:JITTER] (default 200)",
         "every answer sent MS ms (plus 0..JITTER ms, random) after its request, in order"},
        {"read-past-end-garbage", "",
         "a read of 0xFD at/after its end returns count 0xA5 bytes, not 0x1082"},
        {"write-past-end-spills", "",
         "writes crossing a space's end accepted; 251's excess bytes land in 253 at 0x80, past "
         "its first 128 bytes (251 is the start of 253's file, as on OpenMRN)"},
        {"write-past-end-grows", "",
         "writes crossing a space's end accepted; the excess bytes are kept beside the image "
         "(FILE.past-end) where no read reaches them, as OpenMRN's config file grows"},
        {"mask-ignored", "MS (default 5000)",
         "Write Under Mask stores the data bytes whole, ignoring the masks; then silent MS ms "
         "and a restart"},
        {"highest-unreadable", "",
         "Space Info of 251 and 253 reports the size as highest address (one too high)"},
        {"events-stale-after-write", "",
         "events identified as at start-up: written event IDs not identified until a restart"},
        {"events-missing", "",
         "every second eventid of the CDI (slots 1, 3, 5...) never identified"},
        {"duplicate-id-silent", "", "no duplicate-node-ID PCER on a duplicate node ID"},
        {"burst-drops", "",
         "addressed messages dropped while more than 16 frames arrived in the last 10 ms"},
        {"answers-standard-frames", "",
         "every standard (11-bit) frame answered with a Verified Node ID"},
        {"stream-wrong-count", "",
         "a stream read's Data Complete counts one byte more than the stream carried"},
        {"stream-no-complete", "", "a stream read never ends with Data Complete"},
        {"stream-ignore-proceed", "",
         "a stream read is sent whole, past the granted buffer, without waiting for Proceed"},
        {"stream-exceed-buffer", "",
         "a stream read sends twice the granted buffer before waiting for each Proceed"},
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
    for (const FaultInfo& info : fault_catalog()) {
        if (auto name = name_if_set(f, info.name)) out.push_back(std::move(*name));
    }
    return out;
}

}  // namespace olcb::simnode
