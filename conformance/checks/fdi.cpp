// Function Description Information (FunctionDescriptionInformationS; TrainControlS §7.2): space
// 0xFA is there and read-only, and its NUL-terminated text is judged by cdi's FDI support
// (validate_fdi, check_fdi_rules: the schema it names and the rules, as `lcc-cdi validate`
// judges a file); the functions it names answer Query Function (and, on a train named with
// --node, Set Function) as their kind says.
#include <algorithm>
#include <map>

#include "cdi/fdi_validator.hpp"
#include "cdi/rule_finding.hpp"
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

using memory::Space;

constexpr std::uint8_t kFdi = train::kFdiSpace;
// The most FDI bytes read (a train's FDI is a few KB; the CDI limit bounds it likewise).
constexpr std::uint32_t kMaxFdiBytes = 1024 * 1024;
// Functions of the FDI queried at most (Query Function each).
constexpr std::size_t kMaxQueried = 32;

// Space 0xFA read by datagrams to its NUL (at most to its highest address, or kMaxFdiBytes).
struct FdiDownload {
    std::vector<std::uint8_t> bytes;  // up to, excluding, the NUL
    bool nul = false;                 // the read ended at a NUL
    std::string failed;               // why the read stopped early ("" when it did not)
    std::uint32_t read = 0;           // bytes read, the NUL included

    static FdiDownload ask(CheckRun& run) {
        FdiDownload d;
        const SpaceInfo& info = run.probe<SpaceInfoProbe>(kFdi);
        const std::uint32_t end =
            info.present ? std::min(info.highest_address + 1, kMaxFdiBytes) : kMaxFdiBytes;
        for (std::uint32_t at = 0; at < end && !d.nul;) {
            const auto n = static_cast<std::uint8_t>(std::min<std::uint32_t>(64, end - at));
            const MemResult& r = run.note(run.session().read(run.node(), Space{kFdi}, at, n));
            if (!r.ok || r.data.empty()) {
                d.failed = "read at " + std::to_string(at) + ": " + describe(r);
                break;
            }
            for (std::uint8_t b : r.data) {
                ++d.read;
                if (b == 0) {
                    d.nul = true;
                    break;
                }
                d.bytes.push_back(b);
            }
            at += static_cast<std::uint32_t>(r.data.size());
        }
        return d;
    }
};

void fdi_space(CheckRun& run, const CheckSpec& spec) {
    const SpaceInfo& fa = run.probe<SpaceInfoProbe>(kFdi);
    if (!fa.answered)
        return run.out(spec).fail("no Space Info reply for 0xFA", "space 0xFA present", "no reply");
    if (!fa.present)
        return run.out(spec).fail("the PIP claims FDI, but space 0xFA is not present",
                                  "space 0xFA present", "not present");
    const std::string where =
        "space 0xFA present, highest address " + std::to_string(fa.highest_address);
    if (!fa.read_only)
        return run.out(spec).warn(where +
                                  ", but not flagged read-only (TrainControlS §7.2 "
                                  "defines it read-only)");
    run.out(spec).pass(where + ", read-only");
}

void fdi_read(CheckRun& run, const CheckSpec& spec) {
    const FdiDownload& d = run.probe<FdiDownload>();
    const SpaceInfo& info = run.probe<SpaceInfoProbe>(kFdi);
    auto v = run.out(spec);
    if (!info.present) return v.skip("depends on fdi.space: 0xFA not present");
    if (d.bytes.empty() && !d.nul)
        return v.fail("space 0xFA could not be read: " + d.failed, "the FDI text", d.failed);
    if (!d.nul)
        return v.fail("no NUL after " + std::to_string(d.bytes.size()) + " bytes of FDI" +
                          (d.failed.empty() ? "" : " (" + d.failed + ")"),
                      "a zero-terminated string (§5)", "no NUL");
    if (info.present && d.read != info.highest_address + 1)
        return v.warn(std::to_string(d.read) + " bytes read to the NUL, but Space Info says " +
                      std::to_string(info.highest_address + 1) +
                      " (OlcbChecker fd20 fails a difference)");
    v.pass(std::to_string(d.bytes.size()) + " bytes and a NUL");
}

// The FDI judged by cdi's FDI support, as `lcc-cdi validate` judges a file: the schema it names,
// the model and the text rules, each under its fdi.* check ID.
struct FdiText {
    std::string text;
    cdi::ValidatedFdi validated;
    std::vector<cdi::RuleFinding> rules;

    static FdiText ask(CheckRun& run) {
        FdiText t;
        const FdiDownload& d = run.probe<FdiDownload>();
        t.text.assign(d.bytes.begin(), d.bytes.end());
        t.validated = cdi::validate_fdi(t.text);
        t.rules = cdi::check_fdi_rules(t.text, t.validated);
        return t;
    }
};

// The text-only checks: each reports check_fdi_rules()' finding for its own ID, so a node's FDI
// gets the verdicts `lcc-cdi validate` gives the same text in a file.
void fdi_text_rule(CheckRun& run, const CheckSpec& spec) {
    if (run.probe<FdiDownload>().bytes.empty())
        return run.out(spec).skip("depends on fdi.read: no FDI text");
    for (const cdi::RuleFinding& f : run.probe<FdiText>().rules) {
        if (f.check_id != spec.id) continue;
        std::vector<std::string> details;
        details.reserve(f.diagnostics.size());
        for (const cdi::Diagnostic& d : f.diagnostics) details.push_back(cdi::located(d));
        return run.out(spec).add(status_of(f.status), f.message, f.expected, f.seen,
                                 std::move(details));
    }
    run.out(spec).fail("cdi::check_fdi_rules() has no rule for this check", std::string(spec.id),
                       "none");
}

std::string number_text(std::uint32_t n) {
    return "function " + std::to_string(n);
}

// The value a function is set to for the check: another than it has, one its kind allows.
std::uint16_t other_value(const cdi::FdiFunction& f, std::uint16_t now) {
    if (f.kind != cdi::FunctionKind::kAnalog) return now == 0 ? 1 : 0;
    const auto lo = static_cast<std::uint16_t>(std::clamp<std::int64_t>(f.value_min(), 0, 0xFFFF));
    const auto hi = static_cast<std::uint16_t>(std::clamp<std::int64_t>(f.value_max(), 0, 0xFFFF));
    return now == hi ? lo : hi;
}

// Why a function's value does not fit its kind ("" when it does).
std::string misfit(const cdi::FdiFunction& f, std::uint16_t value) {
    if (f.kind != cdi::FunctionKind::kAnalog) {
        if (value <= 1) return {};
        return std::string(cdi::function_kind_name(f.kind)) + " " + number_text(f.number) +
               " reads " + std::to_string(value) + " (0 or 1 expected, §6.3)";
    }
    if (value >= f.value_min() && value <= f.value_max()) return {};
    return "analog " + number_text(f.number) + " reads " + std::to_string(value) +
           ", outside its " + std::to_string(f.value_min()) + ".." + std::to_string(f.value_max());
}

// What the train says of each function the FDI names (Query Function): "" when each fits its
// kind, else why not; fatal set when a query went unanswered.
std::string queried(CheckRun& run, const std::vector<cdi::FdiFunction>& fns, bool& fatal) {
    std::string odd;
    for (std::size_t i = 0; i < fns.size() && i < kMaxQueried; ++i) {
        const cdi::FdiFunction& f = fns[i];
        std::string why;
        const auto r = train_ask<train::FunctionReply>(run, {train::QueryFunction{f.number}}, why);
        if (!r) {
            fatal = true;
            return "Query Function " + std::to_string(f.number) + " (" + quoted(f.name) +
                   "): " + why;
        }
        if (odd.empty()) odd = misfit(f, r->value);
    }
    return odd;
}

// The first function number the FDI does not name (from 1 up: F0 is named almost always).
std::uint32_t unnamed_number(const cdi::FdiDocument& doc) {
    std::uint32_t n = 1;
    while (doc.find(n) != nullptr && n < cdi::kMaxFunctionNumber) ++n;
    return n;
}

// On a train the user named: the first function the FDI names is set to another value, read
// back and restored; a number the FDI does not name is queried after it and must still be
// answered. "" when the train behaves; fail set when a reply the standard asks for is missing.
std::string set_and_query(CheckRun& run, const cdi::FdiDocument& doc, bool& fail) {
    const cdi::FdiFunction& f = doc.functions.front();
    const std::string q = "Query Function " + std::to_string(f.number) + ": ";
    std::string why;
    const auto before = train_ask<train::FunctionReply>(run, {train::QueryFunction{f.number}}, why);
    if (!before) {
        fail = true;
        return q + why;
    }
    const TrainDriving driving(run);
    if (!driving.blocked().empty()) return {};
    const std::uint16_t want = other_value(f, before->value);
    train_send(run, {train::SetFunction{f.number, want}});
    const auto after = train_ask<train::FunctionReply>(run, {train::QueryFunction{f.number}}, why);
    train_send(run, {train::SetFunction{f.number, before->value}});
    if (!after) {
        fail = true;
        return q + why;
    }
    if (after->value != want)
        return "Set Function " + std::to_string(f.number) + " (" + quoted(f.name) +
               ") = " + std::to_string(want) + " reads back " + std::to_string(after->value);
    const std::uint32_t other = unnamed_number(doc);
    if (!train_ask<train::FunctionReply>(run, {train::QueryFunction{other}}, why)) {
        fail = true;
        return "Query Function " + std::to_string(other) +
               " (a number the FDI does not name): " + why;
    }
    return {};
}

void fdi_functions(CheckRun& run, const CheckSpec& spec) {
    const FdiText& t = run.probe<FdiText>();
    if (!t.validated.document) return run.out(spec).skip("depends on fdi.valid: no FDI document");
    const cdi::FdiDocument& doc = *t.validated.document;
    std::map<std::uint32_t, int> seen;
    for (const cdi::FdiFunction& f : doc.functions) {
        if (++seen[f.number] == 2)
            return run.out(spec).warn(number_text(f.number) +
                                      " is described twice (a throttle cannot tell which)");
    }
    const std::string expected = "a Query Function Reply (TrainControlS §4.4)";
    bool fatal = false;
    const std::string odd = queried(run, doc.functions, fatal);
    if (fatal) return run.out(spec).fail(odd, expected, odd);
    if (!odd.empty()) return run.out(spec).warn(odd);
    const std::string may = train_may_drive(run);
    std::string drove = "; Set Function not tried (" + may + ")";
    if (!doc.functions.empty() && may.empty()) {
        const std::string bad = set_and_query(run, doc, fatal);
        if (fatal) return run.out(spec).fail(bad, expected, bad);
        if (!bad.empty()) return run.out(spec).warn(bad + " (§6.3, §7.1)");
        drove =
            "; the first set to another value reads it back, and a number the FDI does not "
            "name is answered";
    }
    run.out(spec).pass(std::to_string(doc.functions.size()) + " functions; " +
                       std::to_string(std::min(doc.functions.size(), kMaxQueried)) +
                       " queried, each answering a value its kind allows" + drove);
}

void fdi_read_only(CheckRun& run, const CheckSpec& spec) {
    if (run.options().read_only) return run.out(spec).skip("--read-only");
    const SpaceInfo& info = run.probe<SpaceInfoProbe>(kFdi);
    if (!info.present) return run.out(spec).skip("depends on fdi.space: 0xFA not present");
    // Rewrite the byte already there: nothing changes even on a faulty node.
    const MemResult& r = run.note(run.session().read(run.node(), Space{kFdi}, 0, 1));
    if (!r.ok || r.data.empty())
        return run.out(spec).skip("byte 0 of space 0xFA unreadable: " + describe(r));
    const std::vector<std::uint8_t> byte = r.data;
    const MemResult& w = run.note(run.session().write(run.node(), Space{kFdi}, 0, byte));
    run.out(spec).refusal(
        judge_refusal(w, "write to the FDI space 0xFA", base::to_u16(base::ErrorCode::kReadOnly)),
        "a failure with an error code (0x1083)");
}

}  // namespace

std::vector<CheckSpec> fdi_checks() {
    const auto fdi = [](CheckSpec s) {
        s.needs = Protocol::kFdi;
        return s;
    };
    return {
        fdi({"fdi.space", 731, Category::kFdi,
             "FunctionDescriptionInformationS §1, §3; TrainControlS §7.2", Strength::kShall,
             "a node claiming FDI serves it in space 0xFA, a read-only space", "fd10, tr070",
             "Space Info 0xFA: present (WARN when not flagged read-only)", fdi_space}),
        fdi({"fdi.read", 732, Category::kFdi, "FunctionDescriptionInformationS §5",
             Strength::kShall, "the FDI is a zero-terminated string", "fd20",
             "datagram reads of 0xFA to the NUL (WARN when the length differs from Space Info's)",
             fdi_read}),
        fdi({"fdi.no-bom", 733, Category::kFdi, "FunctionDescriptionInformationS §5",
             Strength::kShall, "the FDI string carries no byte-order mark", "fd20",
             "cdi::check_fdi_rules: no UTF-8 byte-order mark", fdi_text_rule}),
        fdi({"fdi.utf8", 734, Category::kFdi, "FunctionDescriptionInformationS §5",
             Strength::kShall, "the FDI string is UTF-8", "fd20",
             "cdi::check_fdi_rules: valid UTF-8 (FAIL: where the first invalid sequence is)",
             fdi_text_rule}),
        fdi({"fdi.xml-declaration", 735, Category::kFdi, "FunctionDescriptionInformationS §5",
             Strength::kShall, "the first line is the XML 1.0 declaration", "fd20",
             "cdi::check_fdi_rules: the first line starts with <?xml version=\"1.0\"?>",
             fdi_text_rule}),
        fdi({"fdi.well-formed", 736, Category::kFdi, "FunctionDescriptionInformationS §5",
             Strength::kShall, "the FDI is XML 1.0", "fd20",
             "cdi::check_fdi_rules: libxml2's parse (FAIL quotes the first error)", fdi_text_rule}),
        fdi({"fdi.valid", 737, Category::kFdi, "FunctionDescriptionInformationS §5, §5.1",
             Strength::kShall,
             "the FDI validates against the FDI schema it names and follows §5.1's element rules",
             "fd20",
             "cdi::validate_fdi: FAIL with every error (details), WARN with every warning, PASS "
             "when none",
             fdi_text_rule}),
        fdi({"fdi.schema-location", 738, Category::kFdi, "FunctionDescriptionInformationS §5",
             Strength::kNone, "naming the schema lets a tool pick its version (advice)", "",
             "cdi::check_fdi_rules: the root names an FDI schema (WARN when not)", fdi_text_rule}),
        fdi({"fdi.functions", 739, Category::kFdi,
             "FunctionDescriptionInformationS §5.1.4; TrainControlS §4.4, §6.3, §7.1",
             Strength::kShall,
             "the train answers Query Function for every function its FDI names, with a value its "
             "kind allows",
             "",
             "Query Function for up to 32 functions of the FDI: a reply, 0/1 for binary and "
             "momentary, min..max for analog (WARN otherwise, and for a number described twice); "
             "on a train named with --node the first set to another value, read back, restored, "
             "and a number the FDI does not name queried: a reply (a value not kept: WARN)",
             fdi_functions}),
        fdi({"fdi.read-only", 743, Category::kFdi, "TrainControlS §7.2; MemoryConfigurationS §4.9",
             Strength::kShall,
             "0xFA is read-only: a write fails with an error code (0x1083 recommended)", "fd30",
             "byte 0 of 0xFA written back as read: refused (skipped with --read-only)",
             fdi_read_only}),
    };
}

}  // namespace olcb::conform::checks
