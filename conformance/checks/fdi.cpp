// Function Description Information (FunctionDescriptionInformationS; TrainControlS §7.2): space
// 0xFA is there and read-only, its bytes are a NUL-terminated UTF-8 XML text whose root is <fdi>
// with one <segment>, each <function> has a number the standard allows, and each function the
// FDI lists answers Query Function as its kind says. Schema validation is cdi's (FDI schema).
#include <pugixml.hpp>

#include <algorithm>
#include <map>

#include "base/utf8.hpp"
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

using memory::Space;

constexpr std::uint8_t kFdi = train::kFdiSpace;
// The most FDI bytes read (a train's FDI is a few KB; the CDI limit bounds it likewise).
constexpr std::uint32_t kMaxFdiBytes = 1024 * 1024;
// Functions of the FDI queried at most (Query Function each).
constexpr std::size_t kMaxQueried = 32;
// The largest function number (FunctionDescriptionInformationS §5.1.4).
constexpr std::uint32_t kMaxFunctionNumber = 16777215;

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

// The FDI parsed: pugixml's verdict and the document.
struct FdiXml {
    std::shared_ptr<pugi::xml_document> doc = std::make_shared<pugi::xml_document>();
    pugi::xml_parse_result parsed;
    std::string text;

    static FdiXml ask(CheckRun& run) {
        FdiXml x;
        const FdiDownload& d = run.probe<FdiDownload>();
        x.text.assign(d.bytes.begin(), d.bytes.end());
        x.parsed = x.doc->load_buffer(x.text.data(), x.text.size(),
                                      pugi::parse_default | pugi::parse_declaration);
        return x;
    }
    bool ok() const { return !text.empty() && static_cast<bool>(parsed); }
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
    if (d.bytes.size() >= 3 && d.bytes[0] == 0xEF && d.bytes[1] == 0xBB && d.bytes[2] == 0xBF)
        return v.fail("the FDI starts with a byte-order mark", "no BOM (§5)", "EF BB BF");
    const std::string_view text(reinterpret_cast<const char*>(d.bytes.data()), d.bytes.size());
    if (!base::is_valid_utf8(text))
        return v.fail("the FDI is not valid UTF-8", "UTF-8 (§5)", "invalid bytes");
    if (info.present && d.read != info.highest_address + 1)
        return v.warn(std::to_string(d.read) + " bytes read to the NUL, but Space Info says " +
                      std::to_string(info.highest_address + 1) +
                      " (OlcbChecker fd20 fails a difference)");
    v.pass(std::to_string(d.bytes.size()) + " bytes of UTF-8 and a NUL, no BOM");
}

void fdi_well_formed(CheckRun& run, const CheckSpec& spec) {
    const FdiDownload& d = run.probe<FdiDownload>();
    if (d.bytes.empty()) return run.out(spec).skip("depends on fdi.read: no FDI text");
    const FdiXml& x = run.probe<FdiXml>();
    auto v = run.out(spec);
    if (!x.parsed)
        return v.fail(std::string("the FDI is not well-formed XML: ") + x.parsed.description() +
                          " at byte " + std::to_string(x.parsed.offset),
                      "XML 1.0 (§5)", x.parsed.description());
    if (!x.text.starts_with("<?xml"))
        return v.fail("the FDI does not start with an XML declaration",
                      "<?xml version=\"1.0\"?> as its first line (§5)", clip(x.text.substr(0, 40)));
    const pugi::xml_node root = x.doc->document_element();
    if (std::string_view(root.name()) != "fdi")
        return v.fail("the root element is <" + std::string(root.name()) + ">", "<fdi> (§5.1.1)",
                      root.name());
    const auto segments =
        std::distance(root.children("segment").begin(), root.children("segment").end());
    if (segments != 1)
        return v.fail("<fdi> has " + std::to_string(segments) + " <segment> elements",
                      "exactly one (§5.1.1)", std::to_string(segments));
    v.pass("well-formed XML, root <fdi> with one <segment>");
}

// One <function> of the FDI.
struct FdiFunction {
    std::uint32_t number = 0;
    std::string kind = "binary";
    std::optional<long> min, max;
    std::string name;
};

// Every <function> under node (groups walked iteratively); bad names the first broken one.
std::vector<FdiFunction> functions_of(pugi::xml_node segment, std::string& bad) {
    std::vector<FdiFunction> out;
    std::vector<pugi::xml_node> stack{segment};
    while (!stack.empty()) {
        const pugi::xml_node n = stack.back();
        stack.pop_back();
        for (pugi::xml_node c = n.last_child(); c; c = c.previous_sibling()) {
            if (std::string_view(c.name()) == "group") stack.push_back(c);
        }
        for (pugi::xml_node f : n.children("function")) {
            FdiFunction fn;
            fn.name = f.child_value("name");
            const std::string text = f.child_value("number");
            char* end = nullptr;
            const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
            if (text.empty() || *end != '\0' || text.front() == '-' || v > kMaxFunctionNumber) {
                if (bad.empty())
                    bad = "function " + quoted(fn.name) + " has number " + quoted(text) +
                          " (a decimal 0..16777215 is required, §5.1.4)";
                continue;
            }
            fn.number = static_cast<std::uint32_t>(v);
            if (auto k = f.attribute("kind")) fn.kind = k.value();
            if (f.child("min")) fn.min = std::strtol(f.child_value("min"), nullptr, 10);
            if (f.child("max")) fn.max = std::strtol(f.child_value("max"), nullptr, 10);
            if (bad.empty() && fn.kind != "binary" && fn.kind != "momentary" && fn.kind != "analog")
                bad = "function " + std::to_string(fn.number) + " has kind " + quoted(fn.kind);
            out.push_back(fn);
        }
    }
    return out;
}

// What the train says of each function (Query Function): "" when it fits its kind, else why not;
// fatal set when a query went unanswered.
std::string behaviour(CheckRun& run, const std::vector<FdiFunction>& fns, bool& fatal) {
    std::string odd;
    for (std::size_t i = 0; i < fns.size() && i < kMaxQueried; ++i) {
        const FdiFunction& f = fns[i];
        std::string why;
        const auto r = train_ask<train::FunctionReply>(run, {train::QueryFunction{f.number}}, why);
        if (!r) {
            fatal = true;
            return "Query Function " + std::to_string(f.number) + " (" + quoted(f.name) +
                   "): " + why;
        }
        const long lo = f.min.value_or(0);
        const long hi = f.max.value_or(255);
        const bool on_off = f.kind != "analog";
        if (odd.empty() && on_off && r->value > 1)
            odd = f.kind + " function " + std::to_string(f.number) + " reads " +
                  std::to_string(r->value) + " (0 or 1 expected, §6.3)";
        if (odd.empty() && !on_off && (r->value < lo || r->value > hi))
            odd = "analog function " + std::to_string(f.number) + " reads " +
                  std::to_string(r->value) + ", outside its " + std::to_string(lo) + ".." +
                  std::to_string(hi);
    }
    return odd;
}

void fdi_functions(CheckRun& run, const CheckSpec& spec) {
    const FdiXml& x = run.probe<FdiXml>();
    if (!x.ok()) return run.out(spec).skip("depends on fdi.well-formed: no FDI document");
    std::string bad;
    const auto fns = functions_of(x.doc->document_element().child("segment"), bad);
    if (!bad.empty()) return run.out(spec).fail(bad, "numbers and kinds as §5.1.4 says", bad);
    std::map<std::uint32_t, int> seen;
    for (const FdiFunction& f : fns) {
        if (++seen[f.number] == 2)
            return run.out(spec).warn("function number " + std::to_string(f.number) +
                                      " is described twice (a throttle cannot tell which)");
        if (f.kind == "analog" && f.min && f.max && *f.min > *f.max)
            return run.out(spec).warn("analog function " + std::to_string(f.number) +
                                      " has min > max");
    }
    const auto& pip = run.probe<PipProbe>().reply;
    if (!pip || !pip->has(Protocol::kTractionControl))
        return run.out(spec).pass(std::to_string(fns.size()) +
                                  " functions, numbers and kinds "
                                  "valid (no Traction Control to ask)");
    bool fatal = false;
    const std::string odd = behaviour(run, fns, fatal);
    if (fatal) return run.out(spec).fail(odd, "a Query Function Reply (TrainControlS §4.4)", odd);
    if (!odd.empty()) return run.out(spec).warn(odd);
    run.out(spec).pass(std::to_string(fns.size()) + " functions with valid numbers and kinds; " +
                       std::to_string(std::min(fns.size(), kMaxQueried)) +
                       " queried, each answering a value its kind allows");
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
        fdi({"fdi.space", 743, Category::kFdi,
             "FunctionDescriptionInformationS §1, §3; TrainControlS §7.2", Strength::kShall,
             "a node claiming FDI serves it in space 0xFA, a read-only space", "fd10, tr070",
             "Space Info 0xFA: present (WARN when not flagged read-only)", fdi_space}),
        fdi({"fdi.read", 744, Category::kFdi, "FunctionDescriptionInformationS §5",
             Strength::kShall, "the FDI is a zero-terminated UTF-8 string without a BOM", "fd20",
             "datagram reads of 0xFA to the NUL: UTF-8, no BOM (WARN when the length differs from "
             "Space Info's)",
             fdi_read}),
        fdi({"fdi.well-formed", 745, Category::kFdi, "FunctionDescriptionInformationS §5, §5.1.1",
             Strength::kShall,
             "XML 1.0 with its declaration first; root <fdi> with exactly one <segment>", "fd20",
             "the FDI parsed: well-formed, <?xml first, <fdi>, one <segment> (the schema is "
             "cdi's FDI validation)",
             fdi_well_formed}),
        fdi({"fdi.functions", 746, Category::kFdi,
             "FunctionDescriptionInformationS §5.1.4; TrainControlS §4.4, §6.3", Strength::kShall,
             "every function has a decimal number 0..16777215 and a known kind; the train "
             "answers Query Function for it",
             "",
             "numbers and kinds of every <function> (WARN for a number twice, min > max); Query "
             "Function for up to 32 of them: a reply, 0/1 for binary and momentary, min..max "
             "for analog (WARN otherwise)",
             fdi_functions}),
        fdi({"fdi.read-only", 747, Category::kFdi, "TrainControlS §7.2; MemoryConfigurationS §4.9",
             Strength::kShall,
             "0xFA is read-only: a write fails with an error code (0x1083 recommended)", "fd30",
             "byte 0 of 0xFA written back as read: refused (skipped with --read-only)",
             fdi_read_only}),
    };
}

}  // namespace olcb::conform::checks
