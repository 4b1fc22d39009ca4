#include "conformance/encoding_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "cdi/event_id_text.hpp"
#include "cdi/float_codec.hpp"
#include "cdi/string_codec.hpp"
#include "cdi/value_codec.hpp"
#include "memory/acdi.hpp"

namespace olcb::conform {
namespace {

using cdi::ElementKind;
using cdi::Value;
using cdi::WideInt;

constexpr std::uint8_t kAcdiUserSpace = 251;
constexpr const char* kSnipTestName = "lcc-conform \xC3\xA9t\xC3\xA9";  // "lcc-conform été"

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

std::vector<std::vector<std::uint8_t>> blob_patterns(std::uint64_t size) {
    std::vector<std::uint8_t> a(size), b(size);
    for (std::uint64_t i = 0; i < size; ++i) {
        a[i] = static_cast<std::uint8_t>(i * 7 + 1);
        b[i] = static_cast<std::uint8_t>(~a[i]);
    }
    return {a, b};
}

bool blob_testable(const cdi::Element& e, bool blob) {
    return blob && e.kind == ElementKind::kBlob && e.blob_mode == "readwrite" && e.size > 0 &&
           e.size <= 4096;
}

std::string check_id(ElementKind kind) {
    switch (kind) {
        case ElementKind::kInt:
        case ElementKind::kBit:
            return "encoding.int";
        case ElementKind::kString:
            return "encoding.string";
        case ElementKind::kEventId:
            return "encoding.eventid";
        case ElementKind::kFloat:
            return "encoding.float";
        case ElementKind::kBlob:
            return "encoding.blob";
        default:
            return "encoding.other";
    }
}

std::string section_of(ElementKind kind) {
    switch (kind) {
        case ElementKind::kInt:
        case ElementKind::kBit:
            return "CDI S 5.1.4.2";
        case ElementKind::kString:
            return "CDI S 5.1.4.3";
        case ElementKind::kEventId:
            return "CDI S 5.1.4.4";
        case ElementKind::kFloat:
            return "CDI S 5.1.4.5";
        case ElementKind::kBlob:
            return "CDI S 5.1.4.7";
        default:
            return "CDI S 5.1.4";
    }
}

std::string code_text(std::uint16_t code) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%04X", code);
    return buf;
}

// Findings of one check kind, summarised into one CheckResult.
struct Tally {
    std::size_t values = 0;
    std::size_t variables = 0;
    std::size_t failures = 0;
    std::string first_message, expected, seen;
    void fail(std::string message, std::string want, std::string got) {
        if (failures++ == 0) {
            first_message = std::move(message);
            expected = std::move(want);
            seen = std::move(got);
        }
    }
};

std::string describe_value(const cdi::Element& e, const Value& v) {
    std::string text = cdi::format_value(e, v);
    if (v.as_float() && *v.as_float() == 0 && std::signbit(*v.as_float())) text = "-0";
    if (v.as_string()) text = "\"" + (text.size() > 24 ? text.substr(0, 24) + "..." : text) + "\"";
    return text;
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
            (static_cast<long double>(count - 1) * i) / (sample - 1) + 0.5L);
        if (pick == index) return true;
    }
    return false;
}

std::vector<Probe> plan_encoding(const cdi::Layout& layout, const EncodingOptions& options) {
    std::vector<Probe> probes;
    // Walking a layout with millions of replicas is bounded: stop after this many cursor steps.
    std::uint64_t steps = 0;
    constexpr std::uint64_t kMaxSteps = 4'000'000;
    for (cdi::Cursor c = layout.begin(); c.valid() && steps < kMaxSteps; c.next(), ++steps) {
        if (probes.size() >= options.max_variables) break;
        bool sampled = true;
        for (std::size_t level = 0; level < c.group_depth() && sampled; ++level) {
            sampled = replica_sampled(c.replica(level), c.group(level).replication, options.sample);
        }
        if (!sampled) continue;
        const cdi::Element& e = c.element();
        if (c.address() + c.size() > 0x1'0000'0000ull || c.space() > 255) continue;
        Probe p{&e,
                static_cast<std::uint8_t>(c.space()),
                static_cast<std::uint32_t>(c.address()),
                static_cast<std::uint32_t>(c.size()),
                c.path(),
                boundary_values(e, options.blob)};
        if (p.values.empty() && !blob_testable(e, options.blob)) continue;
        probes.push_back(std::move(p));
    }
    return probes;
}

std::vector<RangeRequest> ranges_to_backup(const std::vector<Probe>& probes,
                                           const EncodingOptions& options) {
    std::vector<RangeRequest> ranges;
    for (const Probe& p : probes) ranges.push_back({p.space, p.address, p.size});
    if (options.acdi_user) {
        ranges.push_back({kAcdiUserSpace, static_cast<std::uint32_t>(memory::acdi::kUserNameOffset),
                          static_cast<std::uint32_t>(memory::acdi::kUserNameSize)});
    }
    return merge_ranges(std::move(ranges));
}

std::vector<CheckResult> run_encoding_checks(const std::vector<Probe>& probes, MemoryAccess& memory,
                                             const EncodingOptions& options,
                                             const EncodingHooks& hooks) {
    std::map<std::string, Tally> tallies;
    for (const char* id :
         {"encoding.int", "encoding.string", "encoding.eventid", "encoding.float"}) {
        tallies[id];
    }
    if (options.blob) tallies["encoding.blob"];
    Tally stored;  // the node's own content before any write
    std::size_t planned = 0, done = 0;
    for (const Probe& p : probes) {
        planned += p.values.empty() ? 2 : p.values.size();
    }
    bool stopped = false;
    // What each probe should hold after its last write (for the persistence check).
    std::vector<std::pair<const Probe*, std::vector<std::uint8_t>>> last_written;

    for (const Probe& p : probes) {
        const cdi::Element& e = *p.element;
        Tally& t = tallies[check_id(e.kind)];
        ++t.variables;
        if (e.kind == ElementKind::kString) {
            AccessResult original = memory.read(p.space, p.address, p.size);
            if (original.ok && original.data.size() == p.size) {
                auto s = cdi::decode_string(original.data);
                if (!s.terminated) {
                    stored.fail(p.path + ": stored string has no NUL terminator",
                                "a NUL within " + std::to_string(p.size) + " bytes",
                                hex_bytes(original.data));
                } else if (!s.valid_utf8) {
                    stored.fail(p.path + ": stored string is not valid UTF-8", "UTF-8 text",
                                hex_bytes(original.data));
                }
            }
            ++stored.values;
        }
        std::vector<std::pair<std::string, std::vector<std::uint8_t>>> writes;
        if (p.values.empty()) {
            for (auto& pattern : blob_patterns(p.size)) writes.emplace_back("pattern", pattern);
        } else {
            for (const Value& v : p.values) {
                auto bytes = cdi::encode(e, v);
                if (bytes) writes.emplace_back(describe_value(e, v), std::move(*bytes));
            }
        }
        for (auto& [label, bytes] : writes) {
            if (hooks.stop && hooks.stop()) {
                stopped = true;
                break;
            }
            ++t.values;
            AccessResult w = memory.write(p.space, p.address, bytes);
            if (!w.ok) {
                t.fail(p.path + ": write of " + label + " refused (" + code_text(w.error) + ")",
                       "write accepted", "error " + code_text(w.error));
            } else {
                AccessResult r = memory.read(p.space, p.address, p.size);
                if (!r.ok) {
                    t.fail(p.path + ": read back after writing " + label + " failed (" +
                               code_text(r.error) + ")",
                           hex_bytes(bytes), "error " + code_text(r.error));
                } else if (r.data != bytes) {
                    t.fail(p.path + ": " + label + " reads back as different bytes",
                           hex_bytes(bytes), hex_bytes(r.data));
                }
                if (&bytes == &writes.back().second) last_written.emplace_back(&p, bytes);
            }
            if (hooks.progress) hooks.progress(++done, planned);
        }
        if (stopped) break;
    }

    std::vector<CheckResult> results;
    auto interrupted = [&](CheckResult& c) {
        c.status = Status::kSkip;
        c.message = "interrupted before completion";
    };
    {
        CheckResult c{"encoding.stored-strings",
                      Category::kEncoding,
                      Status::kPass,
                      "",
                      "CDI S 5.1.4.3",
                      "",
                      ""};
        if (stored.values == 0) {
            c.status = Status::kSkip;
            c.message = "no string variable";
        } else if (stored.failures) {
            c.status = Status::kFail;
            c.message = std::to_string(stored.failures) + " of " + std::to_string(stored.values) +
                        " stored strings malformed; first: " + stored.first_message;
            c.expected = stored.expected;
            c.seen = stored.seen;
        } else {
            c.message = std::to_string(stored.values) + " stored strings NUL-terminated UTF-8";
        }
        results.push_back(std::move(c));
    }
    for (auto& [id, t] : tallies) {
        ElementKind kind = id == "encoding.int"       ? ElementKind::kInt
                           : id == "encoding.string"  ? ElementKind::kString
                           : id == "encoding.eventid" ? ElementKind::kEventId
                           : id == "encoding.float"   ? ElementKind::kFloat
                                                      : ElementKind::kBlob;
        CheckResult c{id, Category::kEncoding, Status::kPass, "", section_of(kind), "", ""};
        if (t.failures) {
            c.status = Status::kFail;
            c.message = std::to_string(t.failures) + " of " + std::to_string(t.values) +
                        " written values wrong; first: " + t.first_message;
            c.expected = t.expected;
            c.seen = t.seen;
        } else if (stopped) {
            interrupted(c);
        } else if (t.values == 0) {
            c.status = Status::kSkip;
            c.message = std::string("no ") + cdi::kind_name(kind) + " variable to write";
        } else {
            c.message = std::to_string(t.values) + " values on " + std::to_string(t.variables) +
                        " variables read back exactly as encoded";
        }
        results.push_back(std::move(c));
    }

    // Persistence: what was last written must survive a reset.
    CheckResult persist{"encoding.persist-after-reboot",
                        Category::kEncoding,
                        Status::kSkip,
                        "",
                        "MemoryConfigurationS 4.23 (Reset/Reboot)",
                        "",
                        ""};
    if (!options.reboot) {
        persist.message = "not asked (--reboot)";
    } else if (stopped) {
        interrupted(persist);
    } else if (last_written.empty()) {
        persist.message = "nothing was written";
    } else if (!hooks.reboot || !hooks.reboot()) {
        persist.status = Status::kFail;
        persist.message = "node did not come back (Initialization Complete) after Reset/Reboot";
    } else {
        Tally t;
        for (auto& [p, bytes] : last_written) {
            ++t.values;
            AccessResult r = memory.read(p->space, p->address, p->size);
            if (!r.ok || r.data != bytes) {
                t.fail(p->path + ": value written before the reset was lost", hex_bytes(bytes),
                       r.ok ? hex_bytes(r.data) : "error " + code_text(r.error));
            }
        }
        persist.status = t.failures ? Status::kFail : Status::kPass;
        persist.message =
            t.failures ? std::to_string(t.failures) + " of " + std::to_string(t.values) +
                             " variables lost their value on reset; first: " + t.first_message
                       : std::to_string(t.values) + " written values survived a reset";
        persist.expected = t.expected;
        persist.seen = t.seen;
    }
    results.push_back(std::move(persist));

    // SNIP must follow a write of the ACDI user name (space 251).
    CheckResult snip{"snip.follows-acdi-user-write",
                     Category::kSnip,
                     Status::kSkip,
                     "",
                     "SNIP S 5.1 / CDI S 5.1.2 (ACDI)",
                     "",
                     ""};
    if (!options.acdi_user) {
        snip.message = "node has no ACDI user space (251)";
    } else if (stopped || (hooks.stop && hooks.stop())) {
        interrupted(snip);
    } else if (!hooks.snip_user_name) {
        snip.message = "no SNIP access";
    } else {
        auto bytes = cdi::encode_string(kSnipTestName, memory::acdi::kUserNameSize);
        AccessResult w = memory.write(
            kAcdiUserSpace, static_cast<std::uint32_t>(memory::acdi::kUserNameOffset), *bytes);
        if (!w.ok) {
            snip.status = Status::kFail;
            snip.message =
                "write of the user name to space 251 refused (" + code_text(w.error) + ")";
        } else {
            auto name = hooks.snip_user_name();
            snip.expected = kSnipTestName;
            if (!name) {
                snip.status = Status::kFail;
                snip.message = "no SNIP reply after writing the user name";
                snip.seen = "no reply";
            } else if (*name != kSnipTestName) {
                snip.status = Status::kFail;
                snip.message = "SNIP user name does not follow space 251";
                snip.seen = *name;
            } else {
                snip.status = Status::kPass;
                snip.message = "SNIP user name follows a write to space 251";
                snip.expected.clear();
            }
        }
    }
    results.push_back(std::move(snip));
    return results;
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
