// Read faults: reads, Get Address Space Information, and the form and reject codes of memory
// replies.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

// What reads and Space Info return.
std::vector<FaultDecl> read_contents() {
    return {
        {
            .name = "read-past-end",
            .access = flag_field<&FaultSet::read_past_end>(),
            .summary = "a read at/after the end of a space returns zeros, not 0x1082",
            .rule_broken = "MemCfg: a read starting at/after the end fails with `0x1082` (fact "
                           "sheet 5.3)",
            .client_sees = "such a read gets Read Reply OK with `count` zero bytes, so a client "
                           "never sees the end",
            .verdict = Verdict::kFail,
            .category = "memory",
            .checks = {"memory.read-past-end.ff", "memory.read-past-end.fd",
                       "memory.read-past-end.fc", "memory.read-past-end.fb"},
        },
        {
            .name = "read-past-end-garbage",
            .access = flag_field<&FaultSet::read_past_end_garbage>(),
            .summary = "a read of 0xFD at/after its end returns count 0xA5 bytes, not 0x1082",
            .rule_broken = "MemCfg: a read starting at/after the end fails with `0x1082` (fact "
                           "sheet 5.3)",
            .client_sees = "on space 0xFD only, such a read gets Read Reply OK with `count` "
                           "bytes of `0xA5` (at the end, or 0x100 past it alike); a read "
                           "crossing the end is still cut short there, other spaces still fail "
                           "`0x1082`",
            .verdict = Verdict::kFail,
            .category = "memory",
            .checks = {"memory.read-past-end.fd"},
        },
        {
            .name = "space-info-short",
            .access = flag_field<&FaultSet::space_info_short>(),
            .summary = "Get Address Space Information reports a too small highest address",
            .rule_broken = "MemCfg Get Address Space Information: highest address covers every "
                           "byte the CDI layout uses (fact sheet 5.4)",
            .client_sees = "every present space reports a highest address 16 lower than real",
            .verdict = Verdict::kFail,
            .category = "acdi",
            .checks = {"acdi.space-info"},
        },
        {
            .name = "highest-unreadable",
            .access = flag_field<&FaultSet::highest_unreadable>(),
            .summary = "Space Info of 251 and 253 reports the size as highest address (one too "
                       "high)",
            .rule_broken = "MemCfg Get Address Space Information: the highest address is the "
                           "last readable byte, size − 1 (fact sheet 5.4). Model of OpenMRN's "
                           "`FileMemorySpace` (`real-world.md` §1)",
            .client_sees = "Space Info of 251 and 253 reports their size as highest address "
                           "(251: 128, default 253: 179); a read at that address fails `0x1082`. "
                           "0xFF and 252 report as usual",
            .verdict = Verdict::kFail,
            .category = "memory",
            .checks = {"memory.read-at-highest.fd", "memory.read-at-highest.fb"},
        },
        {
            .name = "field-reads-only",
            .access = flag_field<&FaultSet::field_reads_only>(),
            .summary = "spaces 251/252 return one ACDI field per read, 1 byte off a field start",
            .rule_broken = "MemCfg read: a read returns `count` bytes, fewer only at the end of "
                           "the space (fact sheet 5.3); ACDI 252/251 are plain byte spaces (fact "
                           "sheet 7). Model of OpenLcbCLib (`real-world.md` §5)",
            .client_sees = "reads of 252/251 that start at a field (252: 0, 1, 42, 83, 104; 251: "
                           "0, 1, 64) return that field only: the version byte alone, a string "
                           "up to and including its first NUL (the whole field if it has none), "
                           "never more than asked; a read starting anywhere else inside the "
                           "space returns 1 byte; all as Read Reply OK (a 64-byte read of 252 at "
                           "0 returns 1 byte). Reads at/after the end still fail `0x1082`",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.short-read.fb", "memory.short-read.fc"},
        },
    };
}

// The form and reject codes of memory replies.
std::vector<FaultDecl> reply_codes() {
    return {
        {
            .name = "reply-form",
            .access = flag_field<&FaultSet::reply_form>(),
            .summary = "replies in byte-6 form to short-form requests and vice versa",
            .rule_broken = "MemCfg: answer in the form of the request (fact sheet 5.1, 11)",
            .client_sees = "reads/writes of 0xFD–0xFF in the short form are answered in the "
                           "byte-6 form and vice versa (252/251 have only the byte-6 form)",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.reply-form"},
        },
        {
            .name = "unknown-space-0x1041",
            .access = flag_field<&FaultSet::unknown_space_0x1041>(),
            .summary = "read/write of an unknown space rejected 0x1041, not 0x1081",
            .rule_broken = "MemCfg: a read or write of an unknown space is rejected `0x1081` "
                           "(fact sheet 5.2)",
            .client_sees = "Datagram Rejected `0x1041` (subcommand unknown) instead, as "
                           "OpenLcbCLib does (`real-world.md` §5); Get Address Space Information "
                           "of an unknown space still answers \"not present\"",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.unknown-space"},
        },
        {
            .name = "readonly-0x1041",
            .access = flag_field<&FaultSet::readonly_0x1041>(),
            .summary = "write to a read-only space rejected 0x1041, not 0x1083",
            .rule_broken = "MemCfg: a write to a read-only space is rejected `0x1083` (fact "
                           "sheet 5.2, 5.5)",
            .client_sees = "writes to 0xFF and 252 get Datagram Rejected `0x1041` instead, as "
                           "OpenLcbCLib does (`real-world.md` §5)",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.readonly-refused.ff", "memory.readonly-refused.fc"},
        },
    };
}

}  // namespace

std::vector<FaultDecl> read_faults() {
    auto all = read_contents();
    for (FaultDecl& d : reply_codes()) all.push_back(std::move(d));
    return all;
}

}  // namespace olcb::simnode
