#include "conformance/run/encoding_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "cdi/event_id_text.hpp"
#include "cdi/float_codec.hpp"
#include "cdi/string_codec.hpp"
#include "cdi/value_codec.hpp"
#include "conformance/run/config_backup.hpp"
#include "memory/acdi.hpp"

namespace olcb::conform {
namespace {

using cdi::ElementKind;
using cdi::Value;
using cdi::WideInt;

constexpr std::uint8_t kAcdiUserSpace = 251;

bool contains(const std::vector<Value>& values, const Value& v) {
    return std::any_of(values.begin(), values.end(), [&](const Value& x) {
        // -0 and +0 compare equal but encode differently: keep both.
        if (x.as_float() && v.as_float()) {
            return *x.as_float() == *v.as_float() &&
                   std::signbit(*x.as_float()) == std::signbit(*v.as_float());
        }
        return x == v;
    });
}

void add_if_valid(const cdi::Element& e, std::vector<Value>& out, Value v) {
    if (contains(out, v)) return;
    if (!cdi::check_value(e, v)) return;
    if (!cdi::encode(e, v)) return;
    out.push_back(std::move(v));
}

std::vector<Value> int_values(const cdi::Element& e) {
    std::vector<Value> out;
    auto size = cdi::value_size(e);
    if (!size || *size == 0 || *size > 8) return out;
    unsigned bits = static_cast<unsigned>(*size * 8);
    WideInt one = 1;
    bool is_signed = e.is_signed();
    WideInt lo = e.int_min.value_or(0);
    WideInt hi = e.int_max ? *e.int_max : (is_signed ? (one << (bits - 1)) - 1 : (one << bits) - 1);
    add_if_valid(e, out, Value::integer(lo));
    add_if_valid(e, out, Value::integer(hi));
    add_if_valid(e, out, Value::integer(0));
    if (e.map) {
        for (const cdi::MapEntry& m : e.map->entries) {
            auto v = cdi::parse_value_text(e, m.property);
            if (v) add_if_valid(e, out, *v);
        }
    }
    // The signedness edge: the value whose top bit tells signed and unsigned storage apart.
    add_if_valid(e, out, Value::integer(is_signed ? WideInt(-1) : (one << (bits - 1))));
    return out;
}

std::vector<Value> string_values(const cdi::Element& e) {
    std::vector<Value> out;
    if (e.size == 0 || e.size > cdi::kMaxStringSize) return out;
    std::size_t room = static_cast<std::size_t>(e.size - 1);
    add_if_valid(e, out, Value::text(""));
    std::string full;
    for (std::size_t i = 0; i < room; ++i) full.push_back(static_cast<char>('A' + i % 26));
    add_if_valid(e, out, Value::text(full));
    // A two-byte and a three-byte character ending exactly at the last byte before the NUL.
    if (room >= 2) add_if_valid(e, out, Value::text(std::string(room - 2, 'x') + "\xC3\xA9"));
    if (room >= 3) add_if_valid(e, out, Value::text(std::string(room - 3, 'y') + "\xE2\x82\xAC"));
    if (e.map) {
        for (const cdi::MapEntry& m : e.map->entries) add_if_valid(e, out, Value::text(m.property));
    }
    return out;
}

std::vector<Value> eventid_values(const cdi::Element& e) {
    std::vector<Value> out;
    for (cdi::EventIdValue v :
         {0x0102030405060708ull, 0x0501010122FF00FEull, 0ull, 0xFFFFFFFFFFFFFFFFull}) {
        add_if_valid(e, out, Value::event_id(v));
    }
    if (e.map) {
        for (const cdi::MapEntry& m : e.map->entries) {
            auto v = cdi::parse_event_id(m.property);
            if (v) add_if_valid(e, out, Value::event_id(*v));
        }
    }
    return out;
}

std::vector<Value> float_values(const cdi::Element& e) {
    std::vector<Value> out;
    if (!cdi::is_valid_float_size(e.size)) return out;
    double lo = e.float_min.value_or(0.0);
    double hi = e.float_max.value_or(cdi::float_highest(e.size));
    add_if_valid(e, out, Value::real(0.0));
    if (e.float_min && *e.float_min < 0) add_if_valid(e, out, Value::real(-0.0));
    add_if_valid(e, out, Value::real(cdi::round_to_float_size(lo, e.size)));
    add_if_valid(e, out, Value::real(cdi::round_to_float_size(hi, e.size)));
    // Exact in every width (binary16 included), so any width or rounding mix-up shows.
    add_if_valid(e, out, Value::real(1.5));
    add_if_valid(e, out, Value::real(cdi::round_to_float_size(lo / 2 + hi / 2, 2)));
    // Values using every mantissa bit of the size: a narrower stored width loses some of them.
    add_if_valid(e, out, Value::real(cdi::round_to_float_size(0.1, e.size)));
    add_if_valid(e, out, Value::real(cdi::round_to_float_size(lo + (hi - lo) / 3, e.size)));
    if (e.map) {
        for (const cdi::MapEntry& m : e.map->entries) {
            auto v = cdi::parse_value_text(e, m.property);
            if (v) add_if_valid(e, out, *v);
        }
    }
    return out;
}

bool blob_testable(const cdi::Element& e, bool blob) {
    return blob && e.kind == ElementKind::kBlob && e.blob_mode == "readwrite" && e.size > 0 &&
           e.size <= 4096;
}

}  // namespace

std::vector<Value> boundary_values(const cdi::Element& element, bool /*blob*/) {
    switch (element.kind) {
        case ElementKind::kInt:
        case ElementKind::kBit:
            return int_values(element);
        case ElementKind::kString:
            return string_values(element);
        case ElementKind::kEventId:
            return eventid_values(element);
        case ElementKind::kFloat:
            return float_values(element);
        default:
            return {};  // <action> triggers something; <blob> is raw; unknown is unknown
    }
}

bool replica_sampled(std::uint64_t index, std::uint64_t count, std::size_t sample) {
    if (sample == 0 || count <= sample) return true;
    if (sample == 1) return index == 0;
    // `sample` indices spread evenly from the first to the last replica.
    for (std::size_t i = 0; i < sample; ++i) {
        std::uint64_t pick = static_cast<std::uint64_t>(
            std::round((static_cast<long double>(count - 1) * i) / (sample - 1)));
        if (pick == index) return true;
    }
    return false;
}

namespace {

// Bound on the unwritten variables listed (a CDI may replicate a protected group 10^6 times).
constexpr std::size_t kMaxUnwritten = 4096;

bool cursor_sampled(const cdi::Cursor& c, std::size_t sample) {
    for (std::size_t level = 0; level < c.group_depth(); ++level) {
        if (!replica_sampled(c.replica(level), c.group(level).replication, sample)) return false;
    }
    return true;
}

void leave_alone(EncodingPlan& plan, std::string key, std::string reason, bool is_protected) {
    if (plan.unwritten.size() < kMaxUnwritten) {
        plan.unwritten.push_back({std::move(key), std::move(reason), is_protected});
    }
}

}  // namespace

EncodingPlan plan_encoding(const cdi::Layout& layout, const EncodingOptions& options) {
    EncodingPlan plan;
    // Walking a layout with millions of replicas is bounded: stop after this many cursor steps.
    std::uint64_t steps = 0;
    constexpr std::uint64_t kMaxSteps = 4'000'000;
    for (cdi::Cursor c = layout.begin(); c.valid() && steps < kMaxSteps; c.next(), ++steps) {
        if (plan.probes.size() >= options.max_variables) break;
        if (!cursor_sampled(c, options.sample)) continue;
        const cdi::Element& e = c.element();
        if (c.address() + c.size() > 0x1'0000'0000ull || c.space() > 255) continue;
        std::string key = jmri_backup_key(layout, c);
        std::string protection = protection_reason(layout, c);
        // An <action> is a command, not a setting: never written, even with --write-protected.
        if (e.kind == ElementKind::kAction) {
            leave_alone(plan, std::move(key), std::move(protection), true);
            continue;
        }
        Probe p{&e,
                static_cast<std::uint8_t>(c.space()),
                static_cast<std::uint32_t>(c.address()),
                static_cast<std::uint32_t>(c.size()),
                key,
                boundary_values(e, options.blob),
                protection,
                c.ordinal()};
        if (p.values.empty() && !blob_testable(e, options.blob)) continue;
        if (auto why = selection_reason(options.protection, key); !why.empty()) {
            leave_alone(plan, std::move(key), std::move(why), false);
        } else if (!protection.empty() && !options.protection.write_protected) {
            leave_alone(plan, std::move(key), std::move(protection), true);
        } else {
            plan.probes.push_back(std::move(p));
        }
    }
    return plan;
}

std::vector<CheckResult> unwritten_checks(const std::vector<Unwritten>& unwritten,
                                          bool write_protected) {
    std::vector<CheckResult> out;
    std::size_t deselected = 0;
    std::string first_deselected;
    for (const Unwritten& u : unwritten) {
        if (!u.is_protected) {
            if (deselected++ == 0) first_deselected = u.key + " (" + u.reason + ")";
            continue;
        }
        std::string hint = write_protected ? "" : "; --write-protected probes it";
        if (u.reason.starts_with("<action>")) hint = "; never written";
        out.push_back({"encoding.protected", Category::kEncoding, Status::kSkip,
                       u.key + ": not written: " + u.reason + hint, "", "", ""});
    }
    if (deselected != 0) {
        out.push_back(
            {"encoding.excluded", Category::kEncoding, Status::kSkip,
             std::to_string(deselected) + " variables not written; first: " + first_deselected, "",
             "", ""});
    }
    return out;
}

std::vector<RangeRequest> ranges_to_backup(const std::vector<Probe>& probes,
                                           const EncodingOptions& options) {
    std::vector<RangeRequest> ranges;
    ranges.reserve(probes.size() + 1);
    for (const Probe& p : probes) ranges.push_back({p.space, p.address, p.size});
    if (options.acdi_user) {
        ranges.push_back({kAcdiUserSpace, static_cast<std::uint32_t>(memory::acdi::kUserNameOffset),
                          static_cast<std::uint32_t>(memory::acdi::kUserNameSize)});
    }
    return merge_ranges(std::move(ranges));
}

std::vector<CheckResult> skipped_encoding_checks(const std::string& reason) {
    std::vector<CheckResult> out;
    for (const char* id : {"encoding.stored-strings", "encoding.eventid", "encoding.float",
                           "encoding.int", "encoding.string", "encoding.persist-after-reboot"}) {
        out.push_back({id, Category::kEncoding, Status::kSkip, reason, "", "", ""});
    }
    out.push_back(
        {"snip.follows-acdi-user-write", Category::kSnip, Status::kSkip, reason, "", "", ""});
    return out;
}

}  // namespace olcb::conform
