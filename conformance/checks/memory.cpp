// Memory Configuration basics: Options, reply latency and forms, Space Info against the layout,
// unknown spaces and commands, Lock/Reserve and the read-only spaces refusing writes.
#include <set>
#include <variant>

#include "base/hex.hpp"
#include "base/timings.hpp"
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

using memory::Space;

// 8-byte reads of the data space in both forms (the short form only for 0xFD-0xFF): the form
// checks' probe.
struct FormProbe {
    std::uint8_t space = 0xFF;
    MemResult byte6;
    std::optional<MemResult> short_form;

    static FormProbe ask(CheckRun& run);
};

// The space the form checks read: a CDI space, 0xFD-0xFF preferred (so the short form is
// covered too); else 0xFF.
std::uint8_t data_space(CheckRun& run) {
    std::optional<std::uint8_t> best;
    for (std::uint8_t sp : layout_spaces(run))
        if (!best || (sp >= 0xFD && *best < 0xFD)) best = sp;
    return best.value_or(0xFF);
}

FormProbe FormProbe::ask(CheckRun& run) {
    FormProbe p;
    p.space = data_space(run);
    const auto space = static_cast<Space>(p.space);
    p.byte6 = run.note(run.session().read(run.node(), space, 0, 8, memory::SpaceForm::kByte6));
    if (p.space >= 0xFD)
        p.short_form =
            run.note(run.session().read(run.node(), space, 0, 8, memory::SpaceForm::kShort));
    return p;
}

// Lock/Reserve with id: the node ID the reply says holds the lock, nullopt without a reply.
std::optional<std::uint64_t> lock_cmd(CheckRun& run, std::uint64_t id, MemResult& last) {
    memory::Message reply;
    last = run.note(run.session().command(run.node(), memory::encode(memory::Lock{id}), &reply));
    if (auto* p = std::get_if<memory::LockReply>(&reply); last.ok && p) return p->node_id;
    return std::nullopt;
}

// The read reply command byte in one form, as on the wire: "20 53" (short form of 0xFF) or
// "20 50 .. FF" (the space in byte 6).
std::string read_reply(std::uint8_t sp, bool short_form) {
    using namespace memory::command_bits;
    const auto space = static_cast<Space>(sp);
    if (short_form)
        return "20 " + hex(kRead | kReply | memory::short_form_bits(space), 2).substr(2);
    return "20 " + hex(kRead | kReply, 2).substr(2) + " .. " + hex(sp, 2).substr(2);
}

// What a read's reply form was, against the one asked for.
std::string form_seen(std::uint8_t sp, bool asked_short, const MemResult& r) {
    const bool got_short = r.reply_in_request_form == asked_short;
    return "Read Reply " + read_reply(sp, got_short) + " (" +
           (got_short ? "short form" : "byte-6 form") + ")";
}

void memory_config_options(CheckRun& run, const CheckSpec& spec) {
    const OptionsProbe& options = run.probe<OptionsProbe>();
    const MemResult& r = options.result;
    if (options.reply) return run.out(spec).pass("Get Configuration Options answered");
    // The command is not mandatory: a rejection says the node does not implement it.
    if (r.rejected && !r.timed_out)
        return run.out(spec).skip("Get Configuration Options rejected with " + hex(r.error) +
                                  " (not implemented)");
    run.out(spec).fail("Get Configuration Options not answered", "reply 20 82 or Datagram Rejected",
                       r.ok ? options.described : describe(r));
}

void memory_reply_latency(CheckRun& run, const CheckSpec& spec) {
    // Every memory-config reply so far counts: with streams the CDI takes only a few datagram
    // reads, and a node slow on some replies only would pass a sample.
    run.probe<CdiDownload>();
    const Heard& heard = run.heard();
    if (!heard.slowest_reply)
        return run.out(spec).skip("depends on cdi.read: no memory-config reply to time");
    const Duration latency = *heard.slowest_reply;
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(latency).count();
    // MessageNetworkS §3.7: 750 ms "unless otherwise indicated": a Datagram Received OK with
    // timeout exponent N promises the reply within 2^N s (DatagramTransportS §4.2).
    const unsigned n = heard.slowest_exponent;
    const Duration limit = reply_limit(run.options(), n);
    const auto limit_ms = std::chrono::duration_cast<std::chrono::milliseconds>(limit).count();
    const std::string bound =
        n == 0 ? std::to_string(limit_ms) + " ms" : std::to_string(1u << n) + " s (announced)";
    const bool ok = latency <= limit;
    run.out(spec).judge(
        ok,
        ok ? "memory-config replies within " + bound
           : "slowest memory-config reply took " + std::to_string(ms) + " ms, over " + bound,
        "<= " + bound, "slowest " + std::to_string(ms) + " ms");
}

void memory_options_acdi_flags(CheckRun& run, const CheckSpec& spec) {
    const auto& options = run.probe<OptionsProbe>().reply;
    const AcdiProbe& acdi = run.probe<AcdiProbe>();
    if (!options) return run.out(spec).skip("depends on memory.config-options: no Options reply");
    // Readability is known from the ACDI reads, made only with <acdi/>.
    if (!acdi.acdi)
        return run.out(spec).skip("the CDI has no <acdi/>: spaces 252/251 are not read");
    const std::uint16_t c = options->available_commands;
    const bool r252 = acdi.manufacturer.has_value();
    const bool r251 = acdi.user.has_value();
    const bool w251 = r251 && !run.probe<SpaceInfoProbe>(0xFB).read_only;
    const bool ok =
        ((c & 0x0800) != 0) == r252 && ((c & 0x0400) != 0) == r251 && ((c & 0x0200) != 0) == w251;
    std::string want = std::string(r252 ? "0x0800 set" : "0x0800 clear") +
                       (r251 ? ", 0x0400 set" : ", 0x0400 clear") +
                       (w251 ? ", 0x0200 set" : ", 0x0200 clear");
    const std::string pass = "Options flags 0x0800/0x0400/0x0200 agree with spaces 252/251";
    run.out(spec).judge(ok,
                        ok ? pass
                           : "Options available commands " + hex(c) + " disagree with spaces " +
                                 "252/251 (wanted " + want + ")",
                        want, "available commands " + hex(c));
}

void memory_space_info_layout(CheckRun& run, const CheckSpec& spec) {
    const auto& layout = run.probe<CdiDownload>().layout;
    if (!layout) return run.out(spec, 0xFD).skip("depends on cdi.valid: no layout");
    for (const auto& e : layout->extents()) {
        const auto sp = static_cast<std::uint8_t>(e.space);
        if (!run.space_selected(spec, sp)) continue;
        const SpaceInfo& info = run.probe<SpaceInfoProbe>(sp);
        if (!info.answered) {
            run.out(spec, sp).skip("Get Address Space Information of " + hex(sp, 2) +
                                   " not answered (an optional command)");
            continue;
        }
        const bool big = info.present && e.end > 0 && info.highest_address + 1 >= e.end;
        const std::string seen =
            info.present ? "highest " + std::to_string(info.highest_address) : "not present";
        run.out(spec, sp).judge(big,
                                big ? "Space Info of space " + hex(sp, 2) + " covers the CDI layout"
                                    : "Space Info of space " + hex(sp, 2) + " says " + seen +
                                          ", the CDI lays out bytes to " +
                                          std::to_string(e.end - 1),
                                "highest >= " + std::to_string(e.end - 1), seen);
    }
}

// Why the form checks judge nothing: with no CDI layout they fall back to 0xFF, which a node
// whose PIP claims no CDI need not serve (OpenMRN's train node refuses it 0x1081, rightly).
std::string no_form_space(CheckRun& run) {
    if (!layout_spaces(run).empty()) return {};
    const auto& pip = run.probe<PipProbe>().reply;
    if (pip && pip->has(Protocol::kCdi)) return {};
    return "no CDI layout to pick a space from, and the PIP claims no CDI (space 0xFF)";
}

void memory_read_byte6_form(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = no_form_space(run); !why.empty()) return run.out(spec).skip(why);
    const FormProbe& p = run.probe<FormProbe>();
    const std::string what = "read of space " + hex(p.space, 2) + " in the byte-6 form";
    run.out(spec).judge(p.byte6.ok, p.byte6.ok ? what : what + ": " + describe(p.byte6),
                        "Read Reply OK with 8 bytes", describe(p.byte6));
}

void memory_read_short_form(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = no_form_space(run); !why.empty()) return run.out(spec).skip(why);
    const FormProbe& p = run.probe<FormProbe>();
    if (!p.short_form)
        return run.out(spec).skip("space " + hex(p.space, 2) + " has only the byte-6 form");
    const std::string what = "read of space " + hex(p.space, 2) + " in the short form";
    run.out(spec).judge(p.short_form->ok,
                        p.short_form->ok ? what : what + ": " + describe(*p.short_form),
                        "Read Reply OK with 8 bytes", describe(*p.short_form));
}

void memory_reply_form(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = no_form_space(run); !why.empty()) return run.out(spec).skip(why);
    const FormProbe& p = run.probe<FormProbe>();
    if (!p.byte6.ok)
        return run.out(spec).skip("depends on memory.read-byte6-form: " + describe(p.byte6));
    // The first read whose reply came in the other form, with both forms as on the wire.
    std::string expected, seen;
    const auto judge = [&](const std::string& what, std::uint8_t sp, bool asked_short,
                           const MemResult& r) {
        if (!seen.empty() || r.reply_in_request_form) return;
        expected = what + ": Read Reply " + read_reply(sp, asked_short);
        seen = what + ": " + form_seen(sp, asked_short, r);
    };
    judge("byte-6 read of " + hex(p.space, 2), p.space, false, p.byte6);
    if (p.short_form) judge("short-form read of " + hex(p.space, 2), p.space, true, *p.short_form);
    if (const MemResult& cdi = run.probe<CdiDownload>().datagram; cdi.ok)
        judge("CDI read of 0xFF", 0xFF, true, cdi);
    run.out(spec).judge(seen.empty(),
                        seen.empty() ? "replies use the form of the request"
                                     : seen + ", not the form of the request",
                        expected, seen);
}

void memory_read_short_at_end(CheckRun& run, const CheckSpec& spec) {
    const SpaceInfo ff = run.probe<SpaceInfoProbe>(0xFF);
    if (!ff.present || ff.highest_address < 3)
        return run.out(spec).skip("depends on cdi.space-info: 0xFF not present or too small");
    if (std::string doubt = highest_too_small(run, 0xFF); !doubt.empty())
        return run.out(spec).skip(doubt);
    const MemResult& e =
        run.note(run.session().read(run.node(), Space::kCdi, ff.highest_address - 3, 8));
    // MemoryConfigurationS §4.5: a reply may be shorter (at least one byte); the end is no error.
    const bool ok = e.ok && !e.data.empty() && e.data.size() <= 4;
    run.out(spec).judge(
        ok,
        "read of 8 across the end of 0xFF returns " +
            (e.ok ? std::to_string(e.data.size()) + " of the 4 bytes left" : describe(e)),
        "1 to 4 bytes", describe(e));
}

void memory_unknown_space(CheckRun& run, const CheckSpec& spec) {
    std::set<std::uint8_t> used = {0xFF, 0xFE, 0xFD, 0xFC, 0xFB, 0xFA, 0xF9, 0xF8, 0xEF};
    for (std::uint8_t sp : layout_spaces(run)) used.insert(sp);
    std::uint8_t unknown = 0x50;
    while (used.count(unknown)) ++unknown;
    const MemResult& u =
        run.note(run.session().read(run.node(), static_cast<Space>(unknown), 0, 8));
    const Refusal refused = judge_refusal(u, "read of unknown space " + std::to_string(unknown),
                                          base::to_u16(base::ErrorCode::kSpaceUnknown));
    run.out(spec).refusal(refused, "a failure with an error code (0x1081)");
}

// No MemoryConfigurationS command byte starts with 0xB (0x80-0x8D, 0xA0-0xAB are the highest
// assigned); OpenMRN and OpenLcbCLib reject it as unknown.
constexpr std::uint8_t kUnassignedCommand = 0xB0;

void memory_unknown_command(CheckRun& run, const CheckSpec& spec) {
    const std::uint8_t payload[] = {memory::kDatagramType, kUnassignedCommand};
    const MemResult& r = run.note(run.session().command(run.node(), payload));
    const std::string what = "unknown command 20 " + base::hex_digits(kUnassignedCommand, 2);
    if (r.rejected) {
        const std::string code = r.error ? hex(r.error) : "no error code";
        // The code is free: 0x1041 is only suggested.
        const bool suggested = r.error == base::to_u16(base::ErrorCode::kSubcommandUnknown);
        return run.out(spec).pass(what + " rejected with " + code +
                                  (suggested ? "" : " (0x1041 is the suggested code)"));
    }
    std::string seen = r.datagram_ok_seen ? "Datagram Received OK" : "no answer";
    if (r.datagram_ok_seen && !r.timed_out) seen += " and a reply datagram";
    run.out(spec).fail(what + " not rejected: " + seen, "Datagram Rejected", seen);
}

void memory_lock(CheckRun& run, const CheckSpec& spec) {
    MemResult last;
    const std::uint64_t me = run.session().tool_id().value();
    auto first = lock_cmd(run, me, last);
    if (!first && !last.ok && !last.timed_out) {
        // Refusing an optional command is allowed; the code it gave is still worth a look.
        // An optional command (MemoryConfigurationTN §2.4.17): not implemented is no finding.
        if (last.error == base::to_u16(base::ErrorCode::kSubcommandUnknown))
            return run.out(spec).skip("not implemented (0x1041): Lock/Reserve is optional");
        const std::string code = last.error ? hex(last.error) : "no error code";
        return run.out(spec).warn("Lock/Reserve rejected with " + code +
                                  " (optional command; not implemented would be 0x1041)");
    }
    if (!first) return run.out(spec).skip("Lock/Reserve not answered (optional)");
    if (*first != me && *first != 0) {
        // Another tool holds the lock: zeros would release it behind that tool's back.
        return run.out(spec).skip("the node is locked by " + NodeId(*first).to_string() +
                                  ": lock check not run");
    }
    auto second = lock_cmd(run, kOtherNodeId, last);
    auto released = lock_cmd(run, 0, last);
    auto id = [](const std::optional<std::uint64_t>& v) {
        return v ? NodeId(*v).to_string() : std::string("no reply");
    };
    // Another tool taking the lock between our commands is no fault of the node's.
    const auto foreign = [&](const std::optional<std::uint64_t>& v) {
        return v && *v != me && *v != kOtherNodeId && *v != 0;
    };
    if (foreign(second) || foreign(released))
        return run.out(spec).skip("another tool took the lock meanwhile (" + id(second) + ", " +
                                  id(released) + "): lock check not judged");
    const bool ok = *first == me && second && *second == me && released && *released == 0;
    const std::string seen = id(first) + ", " + id(second) + ", " + id(released);
    run.out(spec).judge(ok,
                        ok ? "reserve holds our ID, another ID does not take it, zeros release it"
                           : "lock reserve, reserve by another ID, release answered " + seen +
                                 " (ours: " + NodeId(me).to_string() + ")",
                        "ours, ours, 0", seen);
    if (released && *released != 0) lock_cmd(run, 0, last);
}

void memory_readonly_refused(CheckRun& run, const CheckSpec& spec) {
    if (run.options().read_only) return run.out(spec, 0xFF).skip("--read-only");
    for (std::uint8_t sp : run.selected_spaces(spec, {0xFF, 0xFC})) {
        const SpaceInfo& info = run.probe<SpaceInfoProbe>(sp);
        if (!info.present) continue;
        // Rewrite the byte already there: nothing changes even on a faulty node.
        const MemResult& r = run.note(run.session().read(run.node(), static_cast<Space>(sp), 0, 1));
        if (!r.ok || r.data.empty()) {
            run.out(spec, sp).skip("byte 0 of space " + hex(sp, 2) + " unreadable: " + describe(r));
            continue;
        }
        const std::vector<std::uint8_t> byte = r.data;
        const MemResult& w =
            run.note(run.session().write(run.node(), static_cast<Space>(sp), 0, byte));
        Refusal refused = judge_refusal(w, "write to read-only space " + hex(sp, 2),
                                        base::to_u16(base::ErrorCode::kReadOnly));
        // 0xFF is read-only by §4.2; 252 only by implication unless Space Info flags it.
        if (refused.status == Status::kFail && w.ok && sp == 0xFC && !info.read_only) {
            refused.status = Status::kWarn;
            refused.message +=
                " (252 is read-only only by implication: Space Info does not "
                "flag it read-only)";
        }
        run.out(spec, sp).refusal(refused, "a failure with an error code (0x1083)");
    }
}

}  // namespace

// The registry's text is compile-time and names the reply deadline in words (docs/checks.md is
// made from it); this keeps the words true to the constant.
static_assert(base::kReplyDue == std::chrono::milliseconds(750),
              "memory.reply-latency says 750 ms");

namespace {

// A check that needs Memory Configuration in the PIP: a read judged by its form means nothing
// on a node that claims none.
CheckSpec mc(CheckSpec s) {
    s.needs = Protocol::kMemoryConfiguration;
    return s;
}

}  // namespace

std::vector<CheckSpec> memory_checks() {
    return {
        {"memory.config-options", 100, Category::kMemory,
         "DatagramTransportS §6; MemoryConfigurationS §4.3, §4.13, §4.14", Strength::kShall,
         "every datagram is answered; the command is optional, so a rejection is a SKIP", "mc10",
         "`20 80`: reply `20 82`", memory_config_options},
        {"memory.reply-latency", 150, Category::kMemory,
         "MessageNetworkS §3.7; DatagramTransportS §4.2", Strength::kShall,
         "a reply goes out within 750 ms unless its Datagram Received OK announced 2^N s", "",
         "(every memory-config reply before it) the slowest within 750 ms or its 2^N s",
         memory_reply_latency},
        {"memory.options-acdi-flags", 360, Category::kMemory, "MemoryConfigurationS §4.14",
         Strength::kShall, "0x0800/0x0400/0x0200 announce reads of 252, reads and writes of 251",
         "mc10",
         "Options 0x0800 iff 252 readable, 0x0400 iff 251 readable, 0x0200 iff 251 writable",
         memory_options_acdi_flags},
        {"memory.space-info-layout.<sp>", 370, Category::kMemory,
         "MemoryConfigurationS §4.16; ConfigurationDescriptionInformationS §5.1.3", Strength::kNone,
         "no clause requires Space Info to cover the CDI layout (consistency only: WARN)", "mc20",
         "`20 84 SP` per space a CDI segment uses: present, highest address + 1 >= end of the "
         "layout in that space",
         memory_space_info_layout},
        mc({"memory.read-byte6-form", 380, Category::kMemory, "MemoryConfigurationS §4.2, §4.4",
            Strength::kShall, "any space may be named in byte 6", "mc30",
            "8-byte read of the data space (0xFD preferred) in the byte-6 form: Read Reply OK",
            memory_read_byte6_form}),
        mc({"memory.read-short-form", 390, Category::kMemory, "MemoryConfigurationS §4.2, §4.4",
            Strength::kShall, "spaces 0xFD-0xFF may be named by the command byte", "mc30",
            "the same read in the short form (0xFD-0xFF): Read Reply OK", memory_read_short_form}),
        {"memory.reply-form", 400, Category::kMemory, "MemoryConfigurationS §4.5", Strength::kNone,
         "both reply forms are defined; nothing ties the reply to the request's form", "mc30",
         "(those reads and the CDI reads) every reply uses the request's form", memory_reply_form},
        {"memory.read-short-at-end", 410, Category::kMemory, "MemoryConfigurationS §4.5",
         Strength::kShall,
         "a read reply may carry fewer bytes (at least one); reaching the end of the space is no "
         "error",
         "",
         "read 8 at highest-3 of 0xFF: OK with 4 bytes (SKIP \"depends on\" the check that found "
         "the highest address too small)",
         memory_read_short_at_end},
        {"memory.unknown-space", 420, Category::kMemory,
         "MemoryConfigurationS §4.3, §4.5; MemoryConfigurationTN §2.4.3", Strength::kShall,
         "a read that yields no bytes fails with an error code; 0x1081 is the recommended one "
         "(another "
         "code WARNs)",
         "", "read of an unused space (0x50 up): rejected or failed with exactly 0x1081",
         memory_unknown_space},
        {"memory.unknown-command", 425, Category::kMemory, "MemoryConfigurationS §4.3",
         Strength::kShall,
         "an unknown command byte is answered with Datagram Rejected (0x1041 suggested, not "
         "required)",
         "", "`20 B0` (no such command): Datagram Rejected with any error code",
         memory_unknown_command},
        {"memory.lock", 730, Category::kMemory,
         "MemoryConfigurationS §4.17, §4.18; MemoryConfigurationTN §2.4.17", Strength::kShall,
         "when implemented, Lock/Reserve is a test-and-set of a node ID and zeros release it; not "
         "implemented (0x1041) SKIPs",
         "mc40",
         "`20 88` our ID, another ID, zeros: replies ours, ours, 0 (not implemented, 0x1041: SKIP; "
         "another rejection: WARN quoting the code; held or taken meanwhile by another tool: SKIP; "
         "while another lcc-conform run is on the segment: SKIP)",
         memory_lock, false, true},
        {"memory.readonly-refused.<sp>", 740, Category::kMemory,
         "MemoryConfigurationS §4.2, §4.3, §4.9; MemoryConfigurationTN §2.4.3", Strength::kShall,
         "a write to a read-only space fails with an error code; 0x1083 is recommended (another "
         "code "
         "WARNs)",
         "cd40",
         "write of byte 0 of 0xFF and 252 with the value read from it: refused with exactly 0x1083 "
         "(skipped with --read-only)",
         memory_readonly_refused},
        {"memory.short-read.<sp>", 960, Category::kMemory,
         "MemoryConfigurationS §4.5; MemoryConfigurationTN §2.4.5", Strength::kNone,
         "a reply may carry fewer bytes than asked; short replies away from the end are noted "
         "(WARN)",
         "",
         "(every read of the run) no Read Reply OK shorter than asked except at the end of the "
         "space"},
    };
}

}  // namespace olcb::conform::checks
