// Write faults: what the node does with a write it acknowledges.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

// Writes within a space that are not stored as acknowledged.
std::vector<FaultDecl> stored_writes() {
    return {
        {
            .name = "write-dropped",
            .order = 120,
            .access = flag_field<&FaultSet::write_dropped>(),
            .summary = "writes acknowledged but not stored",
            .rule_broken = "MemCfg write: Write Reply OK means the data was stored (fact sheet "
                           "5.2)",
            .client_sees = "every write is acknowledged OK, nothing changes; a "
                           "write-and-read-back shows it",
            .verdict = Verdict::kFail,
            .category = "encoding",
            .checks = {"encoding.eventid", "encoding.float", "encoding.int", "encoding.string"},
        },
        {
            .name = "write-not-persisted",
            .order = 130,
            .access = flag_field<&FaultSet::write_not_persisted>(),
            .summary = "writes kept in RAM only: lost on reboot",
            .rule_broken = "MemCfg + CDI: configuration is non-volatile (survives Reset/Reboot, "
                           "power loss)",
            .client_sees = "writes read back fine until Reset/Reboot or a restart, then the old "
                           "value is back (image on disk untouched); lcc-conform sees it with "
                           "`--reboot`",
            .verdict = Verdict::kWarn,
            .category = "encoding",
            .checks = {"encoding.persist-after-reboot"},
        },
        {
            .name = "readonly-writable",
            .order = 140,
            .access = flag_field<&FaultSet::readonly_writable>(),
            .summary = "writes to spaces 0xFF and 252 accepted",
            .rule_broken = "MemCfg: 0xFF and 252 are read-only, writes get `0x1083` (fact sheet "
                           "5.2, 5.5)",
            .client_sees = "writes to 0xFF and 252 answered Write Reply OK and read back changed "
                           "(in RAM; a reboot restores them)",
            .verdict = Verdict::kFail,
            .category = "memory",
            .checks = {"memory.readonly-refused.ff"},
        },
        {
            .name = "reboot-on-write",
            .order = 240,
            .param = {ParamKind::kNumber, "N", 1, 1, kMaxCount},
            .access = count_field<&FaultSet::reboot_on_write>(),
            .summary = "the Nth stored write restarts the node without its Write Reply (once)",
            .doc_parameter = "`N`, default 1",
            .rule_broken = "MemCfg write: the node answers Datagram Received OK with Reply "
                           "Pending, then the Write Reply, and stays up (fact sheet 5.2)",
            .client_sees = "the Nth stored write (one that gets Write Reply OK; rejected and "
                           "failed writes do not count) is stored and acknowledged OK with Reply "
                           "Pending, then the node restarts (CID..RID, AMD, Initialization "
                           "Complete) instead of sending the Write Reply; once per process, not "
                           "again at the 2N-th",
            .verdict = Verdict::kIncomplete,
            .category = "node",
            .checks = {"node.rebooted"},
        },
    };
}

// Writes past a space's end, and Write Under Mask.
std::vector<FaultDecl> crossing_writes() {
    return {
        {
            .name = "write-past-end-spills",
            .order = 340,
            .access = flag_field<&FaultSet::write_past_end_spills>(),
            .summary = "writes crossing a space's end accepted; 251's excess bytes land in 253 "
                       "at 0x80, past its first 128 bytes (251 is the start of 253's file, as on "
                       "OpenMRN)",
            .rule_broken = "none of MemCfg requires refusing a write that crosses the end (§4.3 "
                           "defines `0x1082` for it, the TN recommends it); storing bytes no "
                           "read reaches, or in another space, is what a tool must not trigger "
                           "unasked. Model of OpenMRN's file-backed 251 (`real-world.md` §1)",
            .client_sees = "a write to 251 starting inside it and running past byte 127 gets "
                           "Write Reply OK: the bytes up to 127 go to 251, the rest into space "
                           "253 at 0x80 on (251 is the first 128 bytes of 253's file, as on "
                           "OpenMRN, so they land on its \"Internal data\" version); a crossing "
                           "write of any other writable space gets Write Reply OK, the bytes "
                           "that fit are stored, the rest dropped. A write *starting* at/after "
                           "the end still fails `0x1082`. lcc-conform crosses an end only with "
                           "`--write-past-end`",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.write-past-end.fb"},
        },
        {
            .name = "write-past-end-grows",
            .order = 350,
            .access = flag_field<&FaultSet::write_past_end_grows>(),
            .summary = "writes crossing a space's end accepted; the excess bytes are kept beside "
                       "the image (FILE.past-end) where no read reaches them, as OpenMRN's "
                       "config file grows",
            .rule_broken = "as `write-past-end-spills`. Model of OpenMRN's 253 (`real-world.md` "
                           "§1): its config file grows by the bytes written past the end, which "
                           "survive a restart and no read reaches",
            .client_sees = "a crossing write of any writable space gets Write Reply OK: the "
                           "bytes that fit are stored, the rest kept beside the space's image in "
                           "`space-N.img.past-end` (synced; in RAM without an image directory), "
                           "never readable through any space; Space Info is unchanged. "
                           "lcc-conform crosses an end only with `--write-past-end`, then says "
                           "which bytes the node may keep and never calls its memory "
                           "byte-identical",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.write-past-end.fd", "memory.write-past-end.fb"},
        },
        {
            .name = "mask-ignored",
            .order = 360,
            .param = {ParamKind::kNumber, "MS", 5000, 1, kMaxDelayMs},
            .access = ms_field<&FaultSet::mask_ignored>(),
            .summary = "Write Under Mask stores the data bytes whole, ignoring the masks; then "
                       "silent MS ms and a restart",
            .doc_parameter = "`MS`, default 5000 (1..600000)",
            .rule_broken = "MemCfg §4.10: Write Under Mask changes only the bits its mask selects",
            .client_sees = "a Write Under Mask stores its data bytes whole, as a plain write, "
                           "answers as usual, then the node is silent for MS ms and restarts "
                           "(memory kept). A careful client saved the byte first and puts it "
                           "back when the node answers again, or keeps its backup and says how "
                           "to restore it",
            .verdict = Verdict::kIncomplete,
            .category = "memory",
            .checks = {"memory.write-under-mask"},
        },
    };
}

}  // namespace

std::vector<FaultDecl> write_faults() {
    auto all = stored_writes();
    for (FaultDecl& d : crossing_writes()) all.push_back(std::move(d));
    return all;
}

}  // namespace olcb::simnode
