// The memory checks at the edges of each address space (the highest address, past the end, a
// write crossing the end), write under mask, Update Complete and the Options write-lengths byte.
// They run before the safety backup exists, so every write leaves memory as it was even on a
// node with the very bug looked for: it writes the bytes just read, and reads them back after.
#include <array>
#include <cstdint>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "conformance/backup/backup_keys.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/checks/protection.hpp"
#include "memory/memory_config_codec.hpp"

namespace olcb::conform::checks {
namespace {

using memory::Space;

constexpr std::uint8_t kCdiSpace = 0xFF;
constexpr std::uint8_t kConfigSpace = 0xFD;
constexpr std::uint8_t kAcdiManufacturer = 0xFC;
constexpr std::uint8_t kAcdiUser = 0xFB;
constexpr std::uint16_t kOutOfBounds = base::to_u16(base::ErrorCode::kOutOfBounds);
// OlcbChecker mc60 reads this far past the highest address of 0xFD, 64 bytes in the byte-6 form.
constexpr std::uint32_t kFarPastEnd = 0x100;
constexpr std::uint8_t kFarCount = 64;
// Most bytes memory.write-past-end watches (and would put back) for a spilling write.
constexpr std::size_t kMaxSnapshot = std::size_t{16} * 1024;
// Options write-lengths (§4.14): 0x80, 0x40, 0x20, 0x02 sent as 1 and 0x08, 0x04 as 0; 0x10 is
// reserved with no value to send and 0x01 is the stream bit, so neither is judged.
constexpr std::uint8_t kWriteLengthsMask = 0xEE;
constexpr std::uint8_t kWriteLengthsWant = 0xE2;

Space as_space(std::uint8_t sp) {
    return static_cast<Space>(sp);
}

std::string space_name(std::uint8_t sp) {
    return "space " + hex(sp, 2);
}

std::string byte_list(std::span<const std::uint8_t> bytes) {
    std::string s;
    for (std::uint8_t b : bytes) s += (s.empty() ? "" : " ") + hex(b, 2);
    return s;
}

MemResult read(CheckRun& run, std::uint8_t sp, std::uint32_t address, std::uint8_t count,
               memory::SpaceForm form = memory::SpaceForm::kAuto) {
    MemResult r = run.session().read(run.node(), as_space(sp), address, count, form);
    run.note(r);
    return r;
}

MemResult write(CheckRun& run, std::uint8_t sp, std::uint32_t address,
                std::span<const std::uint8_t> data) {
    MemResult r = run.session().write(run.node(), as_space(sp), address, data);
    run.note(r);
    return r;
}

// The spaces whose edges are checked: those every tool reads plus every space the CDI lays out,
// each only when Space Info says it is present; 0xFF first.
std::vector<std::uint8_t> bounded_spaces(CheckRun& run) {
    std::set<std::uint8_t> spaces = {kCdiSpace, kConfigSpace, kAcdiManufacturer, kAcdiUser};
    for (std::uint8_t sp : layout_spaces(run)) spaces.insert(sp);
    std::vector<std::uint8_t> out;
    for (auto it = spaces.rbegin(); it != spaces.rend(); ++it)
        if (run.probe<SpaceInfoProbe>(*it).present) out.push_back(*it);
    return out;
}

// True when the CDI uses 0xFB: a segment in it, or <acdi/> (which lays out its user block).
bool acdi_user_used(CheckRun& run) {
    const CdiDownload& cdi = run.probe<CdiDownload>();
    const std::vector<std::uint8_t> used = layout_spaces(run);
    const bool in_layout = std::find(used.begin(), used.end(), kAcdiUser) != used.end();
    return in_layout || (cdi.document && cdi.document->acdi);
}

// Spaces a write may touch: writable per Space Info and used by the CDI; never 0xFF or 0xFC.
std::vector<std::uint8_t> writable_spaces(CheckRun& run) {
    std::vector<std::uint8_t> out;
    for (std::uint8_t sp : bounded_spaces(run)) {
        if (sp == kCdiSpace || sp == kAcdiManufacturer || run.probe<SpaceInfoProbe>(sp).read_only)
            continue;
        if (sp == kConfigSpace || sp == kAcdiUser) {
            const std::vector<std::uint8_t> used = layout_spaces(run);
            const bool in_layout = std::find(used.begin(), used.end(), sp) != used.end();
            if (!in_layout && !(sp == kAcdiUser && acdi_user_used(run))) continue;
        }
        out.push_back(sp);
    }
    return out;
}

// Why the byte must not be written ("" when it may be): the protected variable holding it.
std::string protected_at(CheckRun& run, std::uint8_t sp, std::uint32_t address) {
    const auto& layout = run.probe<CdiDownload>().layout;
    if (!layout) return {};
    const cdi::Cursor c = layout->find(sp, address);
    if (!c.valid()) return {};
    const std::string why = protection_reason(*layout, c);
    return why.empty() ? "" : jmri_backup_key(*layout, c) + " (" + why + ")";
}

// Writes original back at once and reads it again: "" when it came back, else what is wrong.
std::string restore(CheckRun& run, std::uint8_t sp, std::uint32_t address,
                    std::span<const std::uint8_t> original) {
    const MemResult w = write(run, sp, address, original);
    const MemResult back = read(run, sp, address, static_cast<std::uint8_t>(original.size()));
    if (back.ok && back.data.size() == original.size() &&
        std::equal(original.begin(), original.end(), back.data.begin()))
        return {};
    return "original not restored: writing " + byte_list(original) + " back to " + space_name(sp) +
           " at " + hex(address, 8) + " got " + describe(w) + ", then its read got " +
           (back.ok ? byte_list(back.data) : describe(back));
}

// ---- memory.read-at-highest.<sp> ----

void read_at_highest(CheckRun& run, const CheckSpec& spec) {
    for (std::uint8_t sp : run.selected_spaces(spec, bounded_spaces(run))) {
        const std::uint32_t highest = run.probe<SpaceInfoProbe>(sp).highest_address;
        const MemResult r = read(run, sp, highest, 1);
        const std::string what = "1-byte read at " + hex(highest, 8) + " of " + space_name(sp) +
                                 " (Space Info's highest address)";
        if (r.ok && !r.data.empty()) {
            run.out(spec, sp).pass(what + " returned data");
            continue;
        }
        std::string message =
            what + (r.error ? " failed with " + hex(r.error) : ": " + describe(r));
        // OpenMRN's file-backed spaces give their size here, one past the last byte.
        if (highest > 0 && r.error == kOutOfBounds) {
            const MemResult before = read(run, sp, highest - 1, 1);
            if (before.ok && !before.data.empty())
                message += "; " + hex(highest - 1, 8) +
                           " reads: Space Info gives the size, not the highest address";
        }
        run.out(spec, sp).fail(message, "1 byte", describe(r));
    }
}

// ---- memory.read-past-end.<sp> ----

void read_past_end(CheckRun& run, const CheckSpec& spec) {
    for (std::uint8_t sp : run.selected_spaces(spec, bounded_spaces(run))) {
        // Past a highest address that is too small lies data: that is the other check's finding.
        if (std::string doubt = highest_too_small(run, sp); !doubt.empty()) {
            run.out(spec, sp).skip(doubt);
            continue;
        }
        const std::uint32_t highest = run.probe<SpaceInfoProbe>(sp).highest_address;
        if (highest == 0xFFFFFFFFu) {
            run.out(spec, sp).skip(space_name(sp) + " ends at 0xFFFFFFFF: no address past it");
            continue;
        }
        const MemResult next = read(run, sp, highest + 1, 8);
        Refusal verdict = judge_refusal(
            next,
            "8-byte read at " + hex(highest + 1, 8) + ", past the end of " + space_name(sp) + ",",
            kOutOfBounds);
        std::string also;
        // OlcbChecker mc60's read, well past the end of 0xFD.
        if (sp == kConfigSpace && highest <= 0xFFFFFFFFu - kFarPastEnd) {
            const std::uint32_t far = highest + kFarPastEnd;
            const MemResult r = read(run, sp, far, kFarCount, memory::SpaceForm::kByte6);
            const Refusal v = judge_refusal(
                r, "64-byte read at " + hex(far, 8) + ", past the end of " + space_name(sp) + ",",
                kOutOfBounds);
            // The worse of the two verdicts (FAIL before WARN before PASS); the first on a tie.
            const auto rank = [](Status st) {
                return st == Status::kFail ? 2 : st == Status::kWarn;
            };
            if (rank(v.status) > rank(verdict.status)) verdict = v;
            also = " and at " + hex(far, 8);
        }
        if (verdict.status == Status::kPass)
            run.out(spec, sp).pass("reads past the end of " + space_name(sp) + " (at " +
                                   hex(highest + 1, 8) + also + ") refused with 0x1082");
        else
            run.out(spec, sp).refusal(verdict, "a failure with an error code (0x1082)");
    }
}

// ---- memory.write-past-end.<sp> ----

// The last byte of a space and its value. When Space Info's highest address does not read (it
// gives the size), the byte before it is the last one.
struct LastByte {
    std::uint32_t address = 0;
    std::uint8_t value = 0;
    bool below_highest = false;
};

std::optional<LastByte> last_byte(CheckRun& run, std::uint8_t sp, std::string& why) {
    const std::uint32_t highest = run.probe<SpaceInfoProbe>(sp).highest_address;
    const MemResult r = read(run, sp, highest, 1);
    if (r.ok && !r.data.empty()) return LastByte{highest, r.data[0], false};
    if (highest > 0 && r.error == kOutOfBounds) {
        const MemResult before = read(run, sp, highest - 1, 1);
        if (before.ok && !before.data.empty()) return LastByte{highest - 1, before.data[0], true};
    }
    why = "the last byte of " + space_name(sp) + " does not read (" + describe(r) +
          "), so nothing is written";
    return std::nullopt;
}

// Every byte a spilling write could reach that a tool can read back: the extents the CDI lays
// out in each writable space, and 251 bytes 1..127 (OpenMRN's 251 spills into its config file,
// onto whatever 253 holds there: its "Internal data" version, real-world.md §1).
struct Snapshot {
    struct Range {
        std::uint8_t space = 0;
        std::uint32_t address = 0;
        std::vector<std::uint8_t> bytes;
    };
    std::vector<Range> ranges;
};

std::optional<Snapshot> snapshot(CheckRun& run, std::string& why) {
    Snapshot snap;
    std::vector<std::pair<std::uint8_t, std::pair<std::uint32_t, std::uint32_t>>> wanted;
    const std::vector<std::uint8_t> writable = writable_spaces(run);
    auto is_writable = [&](std::uint32_t sp) {
        return std::find(writable.begin(), writable.end(), sp) != writable.end();
    };
    if (const auto& layout = run.probe<CdiDownload>().layout)
        for (const auto& e : layout->extents())
            if (e.end > e.begin && is_writable(e.space))
                wanted.push_back({static_cast<std::uint8_t>(e.space),
                                  {static_cast<std::uint32_t>(e.begin),
                                   static_cast<std::uint32_t>(e.end - e.begin)}});
    if (is_writable(kAcdiUser)) wanted.push_back({kAcdiUser, {1, 127}});
    std::size_t total = 0;
    for (const auto& [sp, range] : wanted) {
        total += range.second;
        if (total > kMaxSnapshot) {
            why = "the writable spaces hold more than " + std::to_string(kMaxSnapshot) +
                  " bytes: too many to watch for a spilling write";
            return std::nullopt;
        }
        // Saved in the safety backup first: a spill undone here is restored at the end too.
        std::string unsaved;
        if (!run.session().ledger().save_ahead(run.node().id, sp, range.first, range.second,
                                               unsaved)) {
            why = space_name(sp) + " bytes " + hex(range.first, 8) + ".. cannot be saved (" +
                  unsaved + "), so a write spilling into them could not be undone";
            return std::nullopt;
        }
        const MemResult r = run.note(run.session().read_range(
            run.node(), static_cast<memory::Space>(sp), range.first, range.second, false));
        if (!r.ok || r.data.size() != range.second) {
            why = space_name(sp) + " bytes " + hex(range.first, 8) + ".. do not read back (" +
                  describe(r) + "), so a write spilling into them could not be undone";
            return std::nullopt;
        }
        snap.ranges.push_back({sp, range.first, r.data});
    }
    return snap;
}

// What the write changed, each difference already written back: "" when nothing changed.
std::string undo_changes(CheckRun& run, std::uint8_t sp, const LastByte& last,
                         const Snapshot& before) {
    std::string found;
    auto note = [&](const std::string& what, std::span<const std::uint8_t> original,
                    std::uint8_t space, std::uint32_t address) {
        const std::string undone = restore(run, space, address, original);
        found +=
            (found.empty() ? "" : "; ") + what + (undone.empty() ? "; restored" : "; " + undone);
    };
    const MemResult back = read(run, sp, last.address, 1);
    if (!back.ok || back.data.empty() || back.data[0] != last.value) {
        note("the last byte (" + hex(last.address, 8) + ") reads " +
                 (back.ok && !back.data.empty() ? hex(back.data[0], 2) : describe(back)) +
                 " instead of " + hex(last.value, 2),
             std::span(&last.value, 1), sp, last.address);
    }
    for (const Snapshot::Range& r : before.ranges) {
        const MemResult now = run.note(
            run.session().read_range(run.node(), static_cast<memory::Space>(r.space), r.address,
                                     static_cast<std::uint32_t>(r.bytes.size()), false));
        for (std::size_t i = 0; i < r.bytes.size(); ++i) {
            if (now.ok && i < now.data.size() && now.data[i] == r.bytes[i]) continue;
            const auto at = static_cast<std::uint32_t>(r.address + i);
            note(space_name(r.space) + " byte " + hex(at, 8) + " changed (the write spilled)",
                 std::span(&r.bytes[i], 1), r.space, at);
        }
    }
    return found;
}

// The byte of a 2-byte crossing write that lies past the end: no tool can read or restore it.
std::string stored_past_end(std::uint8_t sp, const LastByte& last) {
    return "1 byte past the end of " + space_name(sp) + " (at " + hex(last.address + 1, 8) + ")";
}

// No "shall" of MemoryConfigurationS makes a node refuse a write crossing the end of a space
// (§4.3 defines 0x1082 for use; the TN says "should"), so an accepted one is a WARN; an unanswered
// write breaks DatagramTransportS §6 (every datagram answered) and FAILs.
void judge_crossing(CheckRun& run, const CheckSpec& spec, std::uint8_t sp, const LastByte& last,
                    const MemResult& w, const std::string& past_end, const std::string& changed) {
    std::string what =
        "2-byte write at " + hex(last.address, 8) + " crossing the end of " + space_name(sp);
    if (last.below_highest)
        what += " (Space Info's highest address " + hex(last.address + 1, 8) + " does not read)";
    const std::string after = changed.empty() ? "" : "; memory changed: " + changed;
    const std::string kept = past_end.empty()
                                 ? ""
                                 : "; the node may have stored " + past_end +
                                       ", where no tool can read it back or restore it";
    if (w.ok) {
        run.out(spec, sp).warn(what + " was accepted" + kept +
                               (changed.empty() ? "; no byte a tool can read changed" : after) +
                               " (0x1082 is the code MemoryConfigurationS §4.3 defines for it)");
    } else if (w.timed_out) {
        run.out(spec, sp).fail(what + ": no answer" + kept + after +
                                   " (DatagramTransportS §6: every datagram is answered)",
                               "Datagram Rejected or a Write Reply", "no answer");
    } else if (!changed.empty()) {
        run.out(spec, sp).warn(what + " was refused with " + hex(w.error) + after);
    } else {
        const std::string code = w.error ? hex(w.error) : "no error code";
        run.out(spec, sp).pass(
            what + " refused with " + code +
            (w.error == kOutOfBounds ? "" : " (0x1082 is the code defined for it)"));
    }
}

void write_past_end_space(CheckRun& run, const CheckSpec& spec, std::uint8_t sp) {
    // Below the real end a 2-byte write at "the last byte" crosses nothing.
    if (std::string doubt = highest_too_small(run, sp); !doubt.empty())
        return run.out(spec, sp).skip(doubt);
    std::string why;
    const std::optional<LastByte> last = last_byte(run, sp, why);
    if (!last) return run.out(spec, sp).skip(why);
    if (std::string p = protected_at(run, sp, last->address); !p.empty())
        return run.out(spec, sp).skip("the last byte of " + space_name(sp) + " belongs to " + p);
    // Where a spilling node puts the extra byte is its own business (OpenMRN's 251: onto 253's
    // internal data): everything a tool can read is saved and put back at once when it changed.
    std::string unsafe;
    const std::optional<Snapshot> before = snapshot(run, unsafe);
    if (!before) return run.out(spec, sp).skip(unsafe);
    const std::array<std::uint8_t, 2> data{last->value, last->value};
    MemResult w;
    {
        // The one write of the run allowed past the end of a space (--write-past-end).
        WriteLedger::PastEndPermit permit(run.session().ledger(), sp);
        w = write(run, sp, last->address, data);
    }
    if (!w.not_sent.empty()) return run.out(spec, sp).skip("not sent: " + w.not_sent);
    judge_crossing(run, spec, sp, *last, w, stored_past_end(sp, *last),
                   undo_changes(run, sp, *last, *before));
}

void write_past_end(CheckRun& run, const CheckSpec& spec) {
    for (std::uint8_t sp : run.selected_spaces(spec, writable_spaces(run))) {
        if (run.options().read_only)
            run.out(spec, sp).skip("--read-only");
        else
            write_past_end_space(run, spec, sp);
    }
}

// ---- memory.write-under-mask ----

struct MaskTarget {
    std::uint8_t space = 0;
    std::uint32_t address = 0;
    std::string path;
};

// The first byte of the first unprotected variable (int, string, eventid, float) of a writable
// CDI space.
std::optional<MaskTarget> mask_target(CheckRun& run) {
    const auto& layout = run.probe<CdiDownload>().layout;
    if (!layout) return std::nullopt;
    const std::vector<std::uint8_t> writable = writable_spaces(run);
    std::optional<MaskTarget> found;
    layout->visit([&](const cdi::Cursor& c) {
        const auto sp = static_cast<std::uint8_t>(c.space());
        if (c.space() > 0xFF || c.address() > 0xFFFFFFFFu || !is_backed_up(c.element()) ||
            std::find(writable.begin(), writable.end(), sp) == writable.end() ||
            !protection_reason(*layout, c).empty())
            return true;
        found =
            MaskTarget{sp, static_cast<std::uint32_t>(c.address()), jmri_backup_key(*layout, c)};
        return false;
    });
    return found;
}

MemResult write_masked(CheckRun& run, const MaskTarget& t, std::uint8_t mask, std::uint8_t value) {
    const memory::WriteUnderMask wum{as_space(t.space), t.address, {{mask, value}}};
    MemResult r = run.session().command(run.node(), memory::encode(wum));
    run.note(r);
    return r;
}

// One write under mask that must leave the byte at v; "" when it did, else what went wrong
// (the byte already put back).
std::string masked_step(CheckRun& run, const MaskTarget& t, std::uint8_t v, std::uint8_t mask,
                        std::uint8_t data) {
    const std::string what = "write under mask (mask " + hex(mask, 2) + ", data " + hex(data, 2) +
                             ") to " + t.path + " (" + space_name(t.space) + " at " +
                             hex(t.address, 8) + ")";
    const MemResult w = write_masked(run, t, mask, data);
    const MemResult back = read(run, t.space, t.address, 1);
    const bool kept = back.ok && !back.data.empty() && back.data[0] == v;
    std::string problem;
    if (!w.ok) problem = what + ": " + describe(w) + " although Options advertise it (0x8000)";
    if (!kept) {
        problem = what + (back.ok && !back.data.empty()
                              ? " left " + hex(back.data[0], 2) + " instead of " + hex(v, 2)
                              : ": the byte does not read back (" + describe(back) + ")");
        const std::string undone = restore(run, t.space, t.address, std::span(&v, 1));
        problem += undone.empty() ? "; restored" : "; " + undone;
    }
    return problem;
}

void write_under_mask(CheckRun& run, const CheckSpec& spec) {
    Verdict out = run.out(spec);
    if (run.options().read_only) return out.skip("--read-only");
    const auto& options = run.probe<OptionsProbe>().reply;
    if (!options) return out.skip("no Get Configuration Options reply");
    if ((options->available_commands & memory::available_commands::kWriteUnderMask) == 0)
        return out.skip("write under mask not advertised (Options bit 0x8000 clear)");
    const std::optional<MaskTarget> t = mask_target(run);
    if (!t) return out.skip("no unprotected variable in a writable CDI space");
    const MemResult first = read(run, t->space, t->address, 1);
    if (!first.ok || first.data.empty())
        return out.skip(t->path + " does not read (" + describe(first) + "): nothing written");
    const std::uint8_t v = first.data[0];
    // Mask 0x00 must change nothing whatever the data; mask 0xFF with the byte's own value
    // writes it unchanged: neither leaves a test value, even on a node that gets masks wrong.
    std::string problem = masked_step(run, *t, v, 0x00, static_cast<std::uint8_t>(~v));
    if (problem.empty()) problem = masked_step(run, *t, v, 0xFF, v);
    if (!problem.empty())
        return out.fail(problem, "the byte unchanged (" + hex(v, 2) + ")", problem);
    out.pass("write under mask to " + t->path + ": mask 0x00 with data " +
             hex(static_cast<std::uint8_t>(~v), 2) + " left " + hex(v, 2) + ", mask 0xFF with " +
             hex(v, 2) + " kept it");
}

// ---- memory.update-complete ----

void update_complete(CheckRun& run, const CheckSpec& spec) {
    Verdict out = run.out(spec);
    // It writes nothing, but tells the node its configuration changed: not under --read-only.
    if (run.options().read_only) return out.skip("--read-only");
    Session& s = run.session();
    const std::uint32_t inits = s.track(run.node().id).initializations;
    MemResult r = s.command(run.node(), memory::encode(memory::UpdateComplete{}));
    run.note(r);
    const bool alive = s.ping(run.node(), run.options().answer_window);
    const bool restarted = s.track(run.node().id).initializations > inits;
    if (!alive)
        return out.fail("the node stopped answering after Update Complete (20 A8)",
                        "Datagram Received OK, node answering", "no Verified Node ID");
    if (r.rejected)
        return out.fail("Update Complete (20 A8) rejected with " +
                            (r.error ? hex(r.error) : std::string("no error code")),
                        "Datagram Received OK", describe(r));
    if (r.unacknowledged)
        return out.skip(
            "depends on datagram.ok-before-reply: Update Complete (20 A8) got no answer from a "
            "node that acknowledges no datagram");
    if (!r.ok && !restarted)
        return out.fail("Update Complete (20 A8): " + describe(r), "Datagram Received OK",
                        describe(r));
    out.pass(restarted ? "Update Complete (20 A8): the node re-initialized (allowed) and answers"
                       : "Update Complete (20 A8) acknowledged; the node still answers");
}

// ---- memory.options-write-lengths ----

void options_write_lengths(CheckRun& run, const CheckSpec& spec) {
    Verdict out = run.out(spec);
    const auto& options = run.probe<OptionsProbe>().reply;
    if (!options) return out.skip("no Get Configuration Options reply");
    const std::uint8_t wl = options->write_lengths;
    const std::string what = "Options write-lengths byte " + hex(wl, 2);
    if ((wl & kWriteLengthsMask) == kWriteLengthsWant)
        return out.pass(what + ": 0x80, 0x40, 0x20, 0x02 set, 0x08, 0x04 clear" +
                        ((wl & 1) ? ", streams" : ""));
    out.fail(what + ": the standard sends 0x80, 0x40, 0x20 and 0x02 as 1 and 0x08, 0x04 as 0",
             "(byte & 0xEE) == 0xE2", hex(wl, 2));
}

}  // namespace

std::vector<CheckSpec> memory_bounds_checks() {
    return {
        {"memory.read-at-highest.<sp>", 550, Category::kMemory, "MemoryConfigurationS §4.5, §4.16",
         Strength::kShall,
         "the highest address is the highest valid address, so a read there returns data",
         "mc20, mc30",
         "1-byte read at Space Info's highest address of 0xFF, 0xFD, 0xFC, 0xFB and every CDI "
         "space (each present per Space Info): data; 0x1082 there means Space Info gives the size",
         read_at_highest},
        {"memory.read-past-end.<sp>", 560, Category::kMemory,
         "MemoryConfigurationS §4.3, §4.5; MemoryConfigurationTN §2.4.3", Strength::kShall,
         "a read that yields no bytes fails with an error code; 0x1082 is the recommended one "
         "(another code WARNs)",
         "mc60",
         "8-byte read at highest+1 of each space (and 64 bytes at highest+0x100 of 0xFD): refused "
         "with exactly 0x1082 (Datagram Rejected or Read Reply Fail); data or OK fails; SKIP "
         "\"depends on\" the check that found the highest address too small",
         read_past_end},
        {"memory.write-past-end.<sp>", 570, Category::kMemory, "MemoryConfigurationS §4.3, §4.8",
         Strength::kNone,
         "no clause makes a node refuse a write crossing the end of a space (0x1082 is defined for "
         "it): accepted WARNs, unanswered FAILs by DatagramTransportS §6",
         "",
         "(--write-past-end only) writable spaces the CDI uses (0xFB, CDI spaces): every byte the "
         "CDI lays out there saved first, 2 bytes written at the last byte (its value twice), "
         "everything read again: refused passes (0x1082 preferred); accepted WARNs (no clause "
         "requires the refusal), naming the bytes the node may keep past the end, which no tool "
         "can read back or restore (OpenMRN: 253's config file grows by a byte; 251's lands on "
         "253's internal data, put back at once); no answer FAILs; SKIP on a protected last byte "
         "and with --read-only",
         write_past_end, false, false, true},
        {"memory.write-under-mask", 580, Category::kMemory, "MemoryConfigurationS §4.10, §4.14",
         Strength::kShall,
         "when advertised, mask bits 1 take the data and mask bits 0 keep the memory", "mc70",
         "when Options advertise 0x8000: write under mask mask 0x00 data ~v, then mask 0xFF data "
         "v, on the first byte of the first unprotected writable CDI variable: reads v after each "
         "(a changed byte is written back at once)",
         write_under_mask},
        {"memory.update-complete", 590, Category::kMemory, "MemoryConfigurationS §4.23",
         Strength::kShall,
         "receiving Update Complete must be permitted; the node may answer with a "
         "re-initialization",
         "",
         "Update Complete (20 A8): Datagram Received OK (or a re-initialization), then the node "
         "still answers Verify Node ID",
         update_complete},
        {"memory.options-write-lengths", 600, Category::kMemory, "MemoryConfigurationS §4.14",
         Strength::kShall,
         "write-lengths bits 0x80, 0x40, 0x20, 0x02 are sent as 1 and 0x08, 0x04 as 0", "mc10",
         "Get Configuration Options write-lengths byte: (byte & 0xEE) == 0xE2 (0x10 reserved, 0x01 "
         "streams)",
         options_write_lengths},
    };
}

}  // namespace olcb::conform::checks
