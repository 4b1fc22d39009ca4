#include "openlcb/train_search.hpp"

#include <vector>

namespace olcb::train_search {
namespace {

// The flag byte's protocol field split as table 4 splits it.
struct ProtocolField {
    unsigned family = 0;  // bits 4-3
    bool bit2 = false;
    unsigned low = 0;  // bits 1-0
};

ProtocolField field_of(std::uint8_t flag_byte) {
    const unsigned p = flag_byte & flags::kProtocolMask;
    return {p >> 3U, (p & 0x04U) != 0, p & 0x03U};
}

// The maximal runs of digit nibbles, as digit characters ("12", "4").
std::vector<std::string> digit_runs(const Query& q) {
    std::vector<std::string> runs;
    std::string current;
    for (std::uint8_t n : q.nibbles) {
        if (n <= 9) {
            current += static_cast<char>('0' + n);
            continue;
        }
        if (!current.empty()) runs.push_back(current);
        current.clear();
    }
    if (!current.empty()) runs.push_back(current);
    return runs;
}

bool is_digit(char c) {
    return c >= '0' && c <= '9';
}

// The address condition of §6.3 that only concerns DCC's short and long addresses.
bool dcc_address_form_fits(const Query& q, const TrainIdentity& t, std::uint32_t value) {
    if (t.protocol != TrackProtocol::kDcc || value >= 128) return true;
    const bool want_long = requests_long_address(q.flags);
    if (want_long) return t.long_address;
    return !t.long_address || (q.flags & flags::kAllocate) == 0;
}

bool address_matches(const Query& q, const TrainIdentity& t) {
    const std::vector<std::string> runs = digit_runs(q);
    if (runs.size() != 1) return false;
    const std::string& digits = runs.front();
    std::uint32_t value = 0;
    for (char c : digits) value = value * 10 + static_cast<std::uint32_t>(c - '0');
    if (!dcc_address_form_fits(q, t, value)) return false;
    if ((q.flags & flags::kExact) != 0) return value == t.address;
    return std::to_string(t.address).starts_with(digits);
}

// One maximal run against the name: it equals the digits of the name from the start of one of
// its digit groups on (other characters skipped); exact: ending where a digit group ends.
bool run_matches_name(const std::string& run, std::string_view name, bool exact) {
    struct Digit {
        char c;
        bool starts_group;
        bool ends_group;
    };
    std::vector<Digit> digits;
    for (std::size_t i = 0; i < name.size(); ++i) {
        if (!is_digit(name[i])) continue;
        const bool starts = i == 0 || !is_digit(name[i - 1]);
        const bool ends = i + 1 == name.size() || !is_digit(name[i + 1]);
        digits.push_back({name[i], starts, ends});
    }
    for (std::size_t from = 0; from + run.size() <= digits.size(); ++from) {
        if (!digits[from].starts_group) continue;
        bool same = true;
        for (std::size_t k = 0; k < run.size() && same; ++k) same = digits[from + k].c == run[k];
        if (same && (!exact || digits[from + run.size() - 1].ends_group)) return true;
    }
    return false;
}

bool name_matches(const Query& q, std::string_view name) {
    const std::vector<std::string> runs = digit_runs(q);
    if (runs.empty()) return false;
    const bool exact = (q.flags & flags::kExact) != 0;
    for (const std::string& run : runs)
        if (!run_matches_name(run, name, exact)) return false;
    return true;
}

}  // namespace

std::optional<Query> Query::of(std::string_view text, std::uint8_t flag_byte) {
    Query q;
    q.nibbles.fill(kEmptyNibble);
    q.flags = flag_byte;
    std::size_t at = 0;
    for (char c : text) {
        if (at == q.nibbles.size()) return std::nullopt;
        if (is_digit(c)) {
            q.nibbles[at++] = static_cast<std::uint8_t>(c - '0');
        } else if (c == ' ') {
            q.nibbles[at++] = kEmptyNibble;
        } else {
            return std::nullopt;
        }
    }
    return q;
}

std::optional<Query> Query::from_event(EventId id) {
    if (!in_range(id)) return std::nullopt;
    Query q;
    const std::uint64_t v = id.value();
    for (std::size_t i = 0; i < q.nibbles.size(); ++i)
        q.nibbles[i] = static_cast<std::uint8_t>((v >> (28 - 4 * i)) & 0xF);
    q.flags = static_cast<std::uint8_t>(v & 0xFF);
    return q;
}

EventId Query::event() const {
    std::uint64_t v = kPrefix;
    for (std::size_t i = 0; i < nibbles.size(); ++i)
        v |= static_cast<std::uint64_t>(nibbles[i] & 0xF) << (28 - 4 * i);
    return EventId{v | flags};
}

bool Query::has_reserved() const {
    for (std::uint8_t n : nibbles)
        if (n >= 0xA && n <= 0xE) return true;
    const ProtocolField f = field_of(flags);
    if (f.family >= 2) return true;
    return f.family == 0 && !f.bit2 && f.low == 3;
}

std::string Query::to_string() const {
    std::string s;
    for (std::uint8_t n : nibbles) {
        if (n == kEmptyNibble) {
            if (!s.empty() && s.back() != ' ') s += ' ';
        } else {
            s += "0123456789ABCDEF"[n & 0xF];
        }
    }
    while (!s.empty() && s.back() == ' ') s.pop_back();
    if (s.empty()) s = "(empty)";
    if ((flags & flags::kExact) != 0) s += " exact";
    if ((flags & flags::kAddressOnly) != 0) s += " address-only";
    if ((flags & flags::kAllocate) != 0) s += " allocate";
    const auto p = requested_protocol(flags);
    if (has_reserved()) {
        s += " (reserved values)";
    } else if (p == TrackProtocol::kDcc) {
        s += requests_long_address(flags) ? " DCC long" : " DCC";
    } else if (p == TrackProtocol::kNative) {
        s += " native";
    } else if (p == TrackProtocol::kMarklinMotorola) {
        s += " MM";
    } else if (p == TrackProtocol::kMfx) {
        s += " MFX";
    }
    return s;
}

std::optional<TrackProtocol> requested_protocol(std::uint8_t flag_byte) {
    const ProtocolField f = field_of(flag_byte);
    if (f.family == 1) return TrackProtocol::kDcc;
    if (f.family != 0) return std::nullopt;
    if (f.bit2) return TrackProtocol::kMarklinMotorola;
    if (f.low == 1) return TrackProtocol::kNative;
    if (f.low == 2) return TrackProtocol::kMfx;
    return std::nullopt;
}

bool requests_long_address(std::uint8_t flag_byte) {
    const ProtocolField f = field_of(flag_byte);
    return f.family == 1 && f.bit2;
}

bool matches(const Query& query, const TrainIdentity& train) {
    if (query.has_reserved()) return false;
    const auto wanted = requested_protocol(query.flags);
    if (wanted && *wanted != train.protocol) return false;
    if (address_matches(query, train)) return true;
    return (query.flags & flags::kAddressOnly) == 0 && name_matches(query, train.name);
}

}  // namespace olcb::train_search
