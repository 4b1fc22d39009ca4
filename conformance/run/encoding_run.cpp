// run_encoding_checks(): the write / read-back cycle of every probe, one variable at a time.
// Safety rule: before the next variable, or any other request, the variable under test holds its
// original bytes again and they read back; the one request made while a test value is in place
// is that variable's own read-back (for the ACDI user name: the SNIP reply that reports it).
#include <algorithm>
#include <cmath>
#include <map>

#include "base/hex.hpp"
#include "cdi/string_codec.hpp"
#include "cdi/value_codec.hpp"
#include "conformance/report/report.hpp"
#include "conformance/run/encoding_checks.hpp"
#include "memory/acdi.hpp"

namespace olcb::conform {
namespace {

using cdi::ElementKind;
using cdi::Value;
using Bytes = std::vector<std::uint8_t>;

constexpr std::uint8_t kAcdiUserSpace = 251;
constexpr const char* kSnipTestName = "lcc-conform \xC3\xA9t\xC3\xA9";  // "lcc-conform été"
constexpr const char* kEncodingIds[] = {"encoding.int", "encoding.string", "encoding.eventid",
                                        "encoding.float"};

std::vector<Bytes> blob_patterns(std::uint64_t size) {
    Bytes a(size), b(size);
    for (std::uint64_t i = 0; i < size; ++i) {
        a[i] = static_cast<std::uint8_t>(i * 7 + 1);
        b[i] = static_cast<std::uint8_t>(~a[i]);
    }
    return {a, b};
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
        default:
            return "encoding.blob";
    }
}

std::string code_text(const AccessResult& r) {
    if (r.error == 0) return r.ok ? "no data" : "no error code";
    const std::string code = base::hex(r.error, 4);
    return r.error == base::to_u16(base::ErrorCode::kTimeout) ? code + " (timed out)" : code;
}

// Findings of one check kind, summarised into one CheckResult.
struct Tally {
    std::size_t values = 0;
    std::size_t variables = 0;
    std::size_t failures = 0;
    std::string first_message, expected, seen;
    // Values the node refused: no clause makes a node take every value its CDI allows.
    std::size_t refusals = 0;
    std::string first_refusal;
    void fail(std::string message, std::string want, std::string got) {
        if (failures++ == 0) {
            first_message = std::move(message);
            expected = std::move(want);
            seen = std::move(got);
        }
    }
    void refuse(std::string message) {
        if (refusals++ == 0) first_refusal = std::move(message);
    }
};

std::string describe_value(const cdi::Element& e, const Value& v) {
    std::string text = cdi::format_value(e, v);
    if (v.as_float() && *v.as_float() == 0 && std::signbit(*v.as_float())) text = "-0";
    if (v.as_string()) text = "\"" + (text.size() > 24 ? text.substr(0, 24) + "..." : text) + "\"";
    return text;
}

// What bytes of a variable decode to, for people ("" when they do not decode).
std::string decoded_text(const cdi::Element& e, std::span<const std::uint8_t> bytes) {
    auto v = cdi::decode(e, bytes, cdi::CodecMode::kLenient);
    return v ? describe_value(e, *v) : std::string();
}

// Bound on the bytes shown per value and on the values kept per variable for the memory map.
constexpr std::size_t kHexShown = 32;
constexpr std::size_t kValuesKept = 32;
// Bytes of a value shown in a headline (expected and seen carry more).
constexpr std::size_t kHeadlineHex = 8;

// "6396 (18 FC)": bytes decoded as the variable's type, with the bytes.
std::string value_and_bytes(const cdi::Element& e, std::uint32_t size, const Bytes& bytes) {
    const std::string value = bytes.size() == size ? decoded_text(e, bytes) : std::string();
    const std::string hex = hex_bytes(bytes, kHeadlineHex);
    return value.empty() ? hex : value + " (" + hex + ")";
}

// The headline of a value that read back wrong: what was written and what came back, each
// decoded, and the pattern when it is one a reader would otherwise have to spot in the bytes
// (the bytes in reverse order, the node keeping the value it had before the write).
std::string wrong_value(const Probe& p, const std::string& label, const Bytes& wrote,
                        const Bytes& read, const Bytes& before) {
    const std::string written = label + " (" + hex_bytes(wrote, kHeadlineHex) + ")";
    const std::string got = value_and_bytes(*p.element, p.size, read);
    if (read == before) return p.key + ": node kept " + got + " after writing " + written;
    std::string out = p.key + ": wrote " + written + ", read back " + got;
    if (read.size() > 1 && read.size() == wrote.size() &&
        std::equal(read.begin(), read.end(), wrote.rbegin()))
        out += read.size() == 2 ? ": bytes swapped" : ": bytes reversed";
    return out;
}

// (label, bytes) of every test value of a probe, in order.
std::vector<std::pair<std::string, Bytes>> test_writes(const Probe& p) {
    std::vector<std::pair<std::string, Bytes>> writes;
    if (p.values.empty()) {
        for (auto& pattern : blob_patterns(p.size)) writes.emplace_back("pattern", pattern);
        return writes;
    }
    for (const Value& v : p.values) {
        if (auto bytes = cdi::encode(*p.element, v)) {
            writes.emplace_back(describe_value(*p.element, v), *bytes);
        }
    }
    return writes;
}

// Why a cycle stopped early.
enum class Stop : std::uint8_t { kNone, kAsked, kNodeDied, kRestoreFailed, kNotSent };

class EncodingRun {
public:
    EncodingRun(MemoryAccess& memory, const EncodingOptions& options, const EncodingHooks& hooks)
        : memory_(memory), options_(options), hooks_(hooks) {
        for (const char* id : kEncodingIds) tallies_[id];
        if (options.blob) tallies_["encoding.blob"];
    }

    // Only reads: the original of every string probe judged, nothing written.
    CheckResult stored_strings(const std::vector<Probe>& probes) {
        for (const Probe& p : probes) {
            if (p.element->kind != ElementKind::kString || asked_to_stop()) continue;
            auto original = read_original(p.space, p.address, p.size, p.key);
            if (stop_ != Stop::kNone) break;  // the node died: the runner reports it
            if (original) check_stored_string(p, *original);
        }
        std::vector<CheckResult> out;
        add_stored_result(out);
        return std::move(out.front());
    }

    EncodingOutcome run(const std::vector<Probe>& probes) {
        for (const Probe& p : probes) planned_ += p.values.empty() ? 2 : p.values.size();
        for (const Probe& p : probes) {
            probe(p);
            if (stop_ != Stop::kNone) break;
        }
        EncodingOutcome out;
        add_stored_result(out.results);
        add_tally_results(out.results);
        out.results.push_back(snip_follows());
        out.results.push_back(persistence());
        add_problem_results(out.results);
        out.in_flight = in_flight_;
        out.node_died = stop_ == Stop::kNodeDied;
        out.restore_failed = stop_ == Stop::kRestoreFailed;
        out.variables = std::move(variables_);
        return out;
    }

private:
    // One access through the hooks; false when the node died (the run stops at once).
    bool step(const std::string& what, const std::string& key, const AccessResult& r) {
        if (!r.not_sent.empty()) {
            // Our own safety gate, not the node: writing stops, nothing is judged.
            stop_ = Stop::kNotSent;
            not_sent_ = r.not_sent;
            return false;
        }
        if (!hooks_.after_access) return true;
        AccessStep s{what, key, last_label_, last_bytes_, &r};
        if (hooks_.after_access(s)) return true;
        stop_ = Stop::kNodeDied;
        return false;
    }
    bool asked_to_stop() {
        if (hooks_.stop && hooks_.stop()) stop_ = Stop::kAsked;
        return stop_ != Stop::kNone;
    }

    // Reads the original; nullopt (variable skipped, or the node died) when it cannot.
    std::optional<Bytes> read_original(std::uint8_t space, std::uint32_t address,
                                       std::uint32_t size, const std::string& key) {
        last_label_.clear();
        last_bytes_ = {};
        AccessResult r = memory_.read(space, address, size);
        if (!step("reading the original of", key, r)) return std::nullopt;
        if (!r.ok || r.data.size() != size) {
            unreadable_.push_back(key + ": " +
                                  (r.ok ? std::to_string(r.data.size()) + " of " +
                                              std::to_string(size) + " bytes came back"
                                        : "read failed (" + code_text(r) + ")"));
            return std::nullopt;
        }
        return std::move(r.data);
    }

    // Writes the original back and reads it again; false (writing stops) when it differs.
    bool put_back(const InFlight& f) {
        AccessResult w = memory_.write(f.space, f.address, f.original);
        if (!step("restoring", f.key, w)) return false;
        AccessResult r =
            memory_.read(f.space, f.address, static_cast<std::uint32_t>(f.original.size()));
        if (!step("reading back the original of", f.key, r)) return false;
        if (w.ok && r.ok && r.data == f.original) return true;
        restore_seen_ = !w.ok  ? "write refused (" + code_text(w) + ")"
                        : r.ok ? hex_bytes(r.data)
                               : "read failed (" + code_text(r) + ")";
        restore_expected_ = hex_bytes(f.original);
        restore_problem_ = f.key + ": original " + restore_expected_ + " did not read back (" +
                           restore_seen_ + ")";
        stop_ = Stop::kRestoreFailed;
        return false;
    }

    void check_stored_string(const Probe& p, const Bytes& original) {
        ++stored_.values;
        auto s = cdi::decode_string(original);
        if (!s.terminated) {
            stored_.fail(p.key + ": stored string has no NUL terminator",
                         "a NUL within " + std::to_string(p.size) + " bytes", hex_bytes(original));
        } else if (!s.valid_utf8) {
            stored_.fail(p.key + ": stored string is not valid UTF-8", "UTF-8 text",
                         hex_bytes(original));
        }
    }

    // Write, read back, compare one test value, noted in the variable's verdict; false when the
    // node died.
    bool try_value(const Probe& p, Tally& t, const std::string& label, const Bytes& bytes,
                   VariableVerdict& verdict) {
        ++t.values;
        last_label_ = label;
        last_bytes_ = bytes;
        TestedValue tried{label, hex_bytes(bytes, kHexShown), "", "", "", false};
        auto fail = [&](std::string message, std::string want, std::string got) {
            if (verdict.verdict != MapVerdict::kFailed) verdict.reason = message;
            verdict.verdict = MapVerdict::kFailed;
            t.fail(std::move(message), std::move(want), std::move(got));
        };
        AccessResult w = memory_.write(p.space, p.address, bytes);
        if (!step("writing", p.key, w)) return false;
        AccessResult r;
        if (!w.ok) {
            tried.error = "write refused (" + code_text(w) + ")";
            const std::string message =
                p.key + ": write of " + label + " refused (" + code_text(w) + ")";
            if (verdict.verdict != MapVerdict::kFailed) verdict.reason = message;
            verdict.verdict = MapVerdict::kFailed;  // not verified: the value never went in
            t.refuse(message);
        } else {
            r = memory_.read(p.space, p.address, p.size);
            if (!step("reading back", p.key, r)) return false;
            if (!r.ok) {
                tried.error = "read back failed (" + code_text(r) + ")";
                fail(
                    p.key + ": read back after writing " + label + " failed (" + code_text(r) + ")",
                    hex_bytes(bytes), "error " + code_text(r));
            } else if (r.data != bytes) {
                fail(wrong_value(p, label, bytes, r.data, in_flight_.front().original),
                     hex_bytes(bytes), hex_bytes(r.data));
            }
        }
        if (r.ok) {
            tried.read = hex_bytes(r.data, kHexShown);
            tried.read_value = r.data.size() == p.size ? decoded_text(*p.element, r.data) : "";
            tried.ok = r.data == bytes;
        }
        if (verdict.values.size() < kValuesKept) verdict.values.push_back(std::move(tried));
        return true;
    }

    void probe(const Probe& p) {
        if (asked_to_stop()) return;
        Tally& t = tallies_[check_id(p.element->kind)];
        VariableVerdict& verdict = variables_.emplace_back(TestedVariable{p.ordinal, {}}).verdict;
        auto original = read_original(p.space, p.address, p.size, p.key);
        if (!original) {
            verdict.reason = stop_ == Stop::kNone
                                 ? "original could not be saved: " + unreadable_.back()
                                 : not_run_reason();
            return;
        }
        ++t.variables;
        verdict.original_value = decoded_text(*p.element, *original);
        verdict.original_bytes = hex_bytes(*original, kHexShown);
        if (p.element->kind == ElementKind::kString) check_stored_string(p, *original);
        in_flight_ = {InFlight{p.space, p.address, *original, p.key}};
        const auto writes = test_writes(p);
        std::size_t tried = 0;
        for (const auto& [label, bytes] : writes) {
            if (asked_to_stop()) break;
            if (!try_value(p, t, label, bytes, verdict)) {  // the runner restores in_flight_
                conclude(verdict, tried, writes.size());
                return;
            }
            ++tried;
            if (hooks_.progress) hooks_.progress(++done_, planned_);
        }
        const Stop asked = stop_;
        stop_ = Stop::kNone;
        if (put_back(in_flight_.front())) {
            in_flight_.clear();
            stop_ = asked;
        } else if (stop_ == Stop::kRestoreFailed) {
            // The first wrong value is the cause; the original not reading back its consequence.
            verdict.reason +=
                (verdict.verdict == MapVerdict::kFailed ? "; then " : "") + restore_problem_;
            verdict.verdict = MapVerdict::kFailed;
        }
        conclude(verdict, tried, writes.size());
        if (stop_ == Stop::kNone) tested_.push_back({&p, *original});
    }

    // Verified when every value was tried and read back (a failure stays a failure).
    void conclude(VariableVerdict& verdict, std::size_t tried, std::size_t planned) const {
        if (verdict.verdict == MapVerdict::kFailed) return;
        if (tried == planned && stop_ != Stop::kNodeDied) {
            verdict.verdict = MapVerdict::kVerified;
            return;
        }
        verdict.verdict = MapVerdict::kSkipped;
        const std::string why = not_run_reason();
        verdict.reason = "stopped after " + std::to_string(tried) + " of " +
                         std::to_string(planned) + " values" + (why.empty() ? "" : ": " + why);
    }

    void add_stored_result(std::vector<CheckResult>& out) const;
    void add_tally_results(std::vector<CheckResult>& out) const;
    void add_problem_results(std::vector<CheckResult>& out) const;
    // The probes given a test value before the reset, with the value each must keep.
    using Written = std::vector<std::pair<const Probe*, Bytes>>;
    CheckResult persistence();
    bool write_before_reset(Written& set);
    bool judge_reset(const RebootOutcome& rb, const Written& set, CheckResult& c);
    bool put_back_all();
    CheckResult snip_follows();
    bool judge_snip_name(const std::string& key, CheckResult& c);
    std::string not_run_reason() const;

    MemoryAccess& memory_;
    const EncodingOptions& options_;
    const EncodingHooks& hooks_;
    std::map<std::string, Tally> tallies_;
    Tally stored_;  // the node's own strings before any write
    std::vector<std::string> unreadable_;
    std::size_t planned_ = 0, done_ = 0;
    Stop stop_ = Stop::kNone;
    std::vector<InFlight> in_flight_;
    std::string restore_problem_, restore_expected_, restore_seen_;
    std::string not_sent_;  // why our gate kept a write back (Stop::kNotSent)
    std::string last_label_;
    Bytes last_bytes_;
    std::vector<std::pair<const Probe*, Bytes>> tested_;  // probes cycled, with their originals
    std::vector<TestedVariable> variables_;               // each probe reached, with its verdict
};

std::string EncodingRun::not_run_reason() const {
    switch (stop_) {
        case Stop::kAsked:
            return "interrupted before completion";
        case Stop::kNodeDied:
            return "not run: the node stopped answering or restarted (see node.*)";
        case Stop::kRestoreFailed:
            // Named as the cause, so the report shows these SKIPs under that FAIL.
            return "depends on encoding.original-restored: an original value did not read back, "
                   "writing stopped";
        case Stop::kNotSent:
            return "not run: lcc-conform kept a write back (" + not_sent_ + ")";
        case Stop::kNone:
            break;
    }
    return {};
}

void EncodingRun::add_stored_result(std::vector<CheckResult>& out) const {
    CheckResult c{"encoding.stored-strings", Category::kEncoding, Status::kPass, "", "", "", ""};
    if (stored_.values == 0) {
        c.status = Status::kSkip;
        c.message = "no string variable read";
    } else if (stored_.failures) {
        c.status = Status::kFail;
        c.message = std::to_string(stored_.failures) + " of " + std::to_string(stored_.values) +
                    " stored strings malformed; first: " + stored_.first_message;
        c.expected = stored_.expected;
        c.seen = stored_.seen;
    } else {
        c.message = std::to_string(stored_.values) + " stored strings NUL-terminated UTF-8";
    }
    out.push_back(std::move(c));
}

void EncodingRun::add_problem_results(std::vector<CheckResult>& out) const {
    for (const std::string& u : unreadable_) {
        out.push_back({"encoding.unreadable", Category::kEncoding, Status::kSkip,
                       u + "; not tested (its original could not be saved)", "", "", ""});
    }
    if (!restore_problem_.empty()) {
        out.push_back({"encoding.original-restored", Category::kEncoding, Status::kFail,
                       restore_problem_ + "; no further variable was written", "",
                       restore_expected_, restore_seen_});
    }
}

void EncodingRun::add_tally_results(std::vector<CheckResult>& out) const {
    for (const auto& [id, t] : tallies_) {
        CheckResult c{id, Category::kEncoding, Status::kPass, "", "", "", ""};
        const std::string cut = not_run_reason();
        if (t.failures) {
            c.status = Status::kFail;
            c.message = t.first_message + "; " + std::to_string(t.failures) + " of " +
                        std::to_string(t.values) + " written values wrong";
            c.expected = t.expected;
            c.seen = t.seen;
        } else if (t.refusals) {
            c.status = Status::kWarn;
            c.message = std::to_string(t.refusals) + " of " + std::to_string(t.values) +
                        " values the CDI allows were refused (no clause makes a node take every "
                        "one; each accepted value read back as encoded); first: " +
                        t.first_refusal;
        } else if (t.values == 0) {
            c.status = Status::kSkip;
            c.message = cut.empty() ? "no " + id.substr(9) + " variable to write" : cut;
        } else {
            c.message = std::to_string(t.values) + " values on " + std::to_string(t.variables) +
                        " variables read back exactly as encoded";
            if (!cut.empty()) c.message += " (then stopped: " + cut + ")";
        }
        out.push_back(std::move(c));
    }
}

// Puts every variable in flight back; false (writing stops) at the first that does not read back.
bool EncodingRun::put_back_all() {
    while (!in_flight_.empty()) {
        if (!put_back(in_flight_.back())) return false;
        in_flight_.pop_back();
    }
    return true;
}

CheckResult EncodingRun::snip_follows() {
    CheckResult c{"snip.follows-acdi-user-write", Category::kSnip, Status::kSkip, "", "", "", ""};
    if (!options_.acdi_user) {
        c.message = options_.acdi_user_skipped.empty() ? "node has no ACDI user space (251)"
                                                       : options_.acdi_user_skipped;
        return c;
    }
    if (stop_ != Stop::kNone || asked_to_stop()) {
        c.message = not_run_reason();
        return c;
    }
    if (!hooks_.snip_user_name) {
        c.message = "no SNIP access";
        return c;
    }
    const auto at = static_cast<std::uint32_t>(memory::acdi::kUserNameOffset);
    const auto size = static_cast<std::uint32_t>(memory::acdi::kUserNameSize);
    const std::string key = "ACDI user name (space 251 @1)";
    auto original = read_original(kAcdiUserSpace, at, size, key);
    if (!original) {
        c.message = stop_ == Stop::kNone ? "the user name could not be read" : not_run_reason();
        return c;
    }
    in_flight_ = {InFlight{kAcdiUserSpace, at, *original, key}};
    last_label_ = std::string("\"") + kSnipTestName + "\"";
    last_bytes_ = *cdi::encode_string(kSnipTestName, size);
    AccessResult w = memory_.write(kAcdiUserSpace, at, last_bytes_);
    if (!step("writing", key, w)) return c;
    if (!w.ok) {
        c.status = Status::kFail;
        c.message = "write of the user name to space 251 refused (" + code_text(w) + ")";
        c.expected = "the write accepted";
        c.seen = "refused with " + code_text(w);
    } else if (!judge_snip_name(key, c)) {
        return c;
    }
    put_back_all();
    return c;
}

// The variable's own read-back: SNIP reports the user name from space 251. False when the node
// stopped answering.
bool EncodingRun::judge_snip_name(const std::string& key, CheckResult& c) {
    auto name = hooks_.snip_user_name();
    const AccessResult unanswered{false, base::to_u16(base::ErrorCode::kTimeout), {}};
    if (!name && !step("asking SNIP for", key, unanswered)) return false;
    c.expected = show_node_text(kSnipTestName);
    c.seen = name ? show_node_text(*name, true, name->size()) : "no SNIP reply";
    c.status = name && *name == kSnipTestName ? Status::kPass : Status::kFail;
    c.message =
        c.status == Status::kPass ? "SNIP user name follows a write to space 251"
        : name ? "SNIP user name reads " + c.seen + " after writing " + c.expected + " to space 251"
               : "no SNIP reply after writing the user name";
    if (c.status == Status::kPass) c.expected.clear(), c.seen.clear();
    return true;
}

CheckResult EncodingRun::persistence() {
    CheckResult c{
        "encoding.persist-after-reboot", Category::kEncoding, Status::kSkip, "", "", "", ""};
    if (!options_.reboot) {
        c.message = "not asked (--reboot)";
        return c;
    }
    if (stop_ != Stop::kNone || asked_to_stop()) {
        c.message = not_run_reason();
        return c;
    }
    Written set;
    if (!write_before_reset(set)) return c;
    if (set.empty()) {
        c.message = "no unprotected variable took a test value";
        put_back_all();
        return c;
    }
    const RebootOutcome rb = hooks_.reboot ? hooks_.reboot() : RebootOutcome{};
    if (rb.stopped) {
        stop_ = Stop::kNodeDied;
        c.message = not_run_reason();
        return c;
    }
    if (!judge_reset(rb, set, c)) return c;
    put_back_all();
    return c;
}

// Test values go only into unprotected variables: a protected one (a stack's own version byte)
// changed across a reset can make the node wipe its whole configuration. False when writing
// stops.
bool EncodingRun::write_before_reset(Written& set) {
    for (const auto& [p, original] : tested_) {
        if (!p->protection.empty()) continue;
        for (const auto& [label, bytes] : test_writes(*p)) {
            if (bytes == original) continue;
            last_label_ = label;
            last_bytes_ = bytes;
            in_flight_.push_back({p->space, p->address, original, p->key});
            AccessResult w = memory_.write(p->space, p->address, bytes);
            if (!step("writing (before the reset)", p->key, w)) return false;
            if (w.ok) set.emplace_back(p, bytes);
            break;
        }
    }
    return true;
}

// The verdict on what the reset did to the values set; false when the node stopped answering.
bool EncodingRun::judge_reset(const RebootOutcome& rb, const Written& set, CheckResult& c) {
    if (rb.rejected != 0) {
        c.message =
            "Reset/Reboot rejected with " + base::hex(rb.rejected, 4) + "; persistence not tested";
        return true;
    }
    if (!rb.back) {
        c.status = Status::kFail;
        c.message = "no Initialization Complete after Reset/Reboot";
        c.expected = "Initialization Complete after 20 A9";
        c.seen = "none while lcc-conform waited";
        return true;
    }
    Tally t;
    for (const auto& [p, bytes] : set) {
        ++t.values;
        AccessResult r = memory_.read(p->space, p->address, p->size);
        if (!step("reading back after the reset", p->key, r)) return false;
        if (!r.ok || r.data != bytes) {
            t.fail(p->key + ": value written before the reset was lost", hex_bytes(bytes),
                   r.ok ? hex_bytes(r.data) : "error " + code_text(r));
        }
    }
    c.status = t.failures ? Status::kFail : Status::kPass;
    c.message = t.failures ? std::to_string(t.failures) + " of " + std::to_string(t.values) +
                                 " variables lost their value on reset; first: " + t.first_message
                           : std::to_string(t.values) + " written values survived a reset";
    c.expected = t.expected;
    c.seen = t.seen;
    return true;
}

}  // namespace

EncodingOutcome run_encoding_checks(const std::vector<Probe>& probes, MemoryAccess& memory,
                                    const EncodingOptions& options, const EncodingHooks& hooks) {
    return EncodingRun(memory, options, hooks).run(probes);
}

CheckResult check_stored_strings(const std::vector<Probe>& probes, MemoryAccess& memory,
                                 const EncodingHooks& hooks) {
    const EncodingOptions options;
    return EncodingRun(memory, options, hooks).stored_strings(probes);
}

}  // namespace olcb::conform
