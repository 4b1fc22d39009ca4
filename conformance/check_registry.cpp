#include "conformance/check_registry.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <array>
#include <sstream>

#include "conformance/checks/checks.hpp"

namespace olcb::conform {
namespace {

using C = Category;
namespace k = checks;

// The protocol checks before the ones whose lists live with their topic files, in run order.
constexpr CheckSpec kEarlyChecks[] = {
    {"frame.ame-answered", C::kFrame, "CanFrameTransferS §6.2.3", Strength::kShall,
     "a permitted node answers an AME that is empty or carries its node ID with an AMD carrying "
     "its node ID",
     "fr20",
     "AME without data and AME with the node ID: 2 AMD frames from the node's alias with its "
     "node ID",
     k::ame_answered},
    {"frame.cid-defended", C::kFrame, "CanFrameTransferS §6.2.5", Strength::kShall,
     "a node receiving a CID frame with an alias it holds answers with RID", "fr30",
     "CID7 with the node's alias (foreign node ID bits): RID from the node", k::cid_defended},
    {"message.oir-unknown-mti", C::kMessage, "MessageNetworkS §3.5.1, §3.5.5", Strength::kShall,
     "an addressed message of an interaction the node does not take part in is answered with OIR "
     "carrying an error code and the rejected MTI; the code may be 0x0000",
     "me40", "addressed frame with unassigned MTI 0x04F9: OIR with a permanent code echoing 0x04F9",
     k::oir_unknown_mti},
    {"message.verify-addressed", C::kMessage, "MessageNetworkS §3.4.2", Strength::kShall,
     "a Verify Node ID addressed to the node is answered with Verified Node ID", "me20",
     "Verify Node ID addressed: Verified Node ID with the node's ID", k::verify_addressed},
    {"message.verify-global", C::kMessage, "MessageNetworkS §3.4.2", Strength::kShall,
     "a global Verify Node ID carrying the node's ID is answered with Verified Node ID", "me20",
     "Verify Node ID global with the node's ID: Verified Node ID", k::verify_global},
    {"message.unknown-global-ignored", C::kMessage, "MessageNetworkS §3.5.2", Strength::kMay,
     "a node may drop an unaddressed message of an interaction it does not take part in without a "
     "reply (answering is not forbidden)",
     "me40",
     "global frame with unassigned MTI 0x0930: nothing addressed to lcc-conform within the "
     "silence window",
     k::unknown_global_ignored},
    {"message.pip-answered", C::kMessage, "MessageNetworkS §3.4.3", Strength::kShall,
     "a Protocol Support Inquiry is answered with a Protocol Support Reply", "me30",
     "Protocol Support Inquiry: Protocol Support Reply", k::pip_answered},
    {"snip.version-bytes", C::kSnip, "SimpleNodeInformationS §5.1, §5.2", Strength::kShall,
     "the section version bytes are 0x01 or 0x04 (manufacturer) and 0x01 or 0x02 (user); higher "
     "values are future versions",
     "sn10", "SNIP request: version bytes 4 and 2", k::snip_version_bytes},
    {"snip.utf8", C::kSnip, "SimpleNodeInformationS §5.1; CommonInformationTN §2.5",
     Strength::kNone,
     "OpenLCB text is UTF-8 (a technical note; SNIP itself only says NUL-terminated strings)", "",
     "(the same reply) each of the six strings is valid UTF-8; FAIL names each invalid one with "
     "its bytes in hex",
     k::snip_utf8},
    {"memory.config-options", C::kMemory,
     "DatagramTransportS §6; MemoryConfigurationS §4.3, §4.13, §4.14", Strength::kShall,
     "every datagram is answered; the command is optional, so a rejection is a SKIP", "mc10",
     "`20 80`: reply `20 82`", k::memory_config_options},
    {"cdi.space-info", C::kCdi, "MemoryConfigurationS §4.2, §4.16", Strength::kShall,
     "space 0xFF is the read-only space holding the CDI; a rejected Get Address Space Information "
     "is a SKIP",
     "mc20", "`20 84 FF`: present (0x87) and read-only", k::cdi_space_info},
    {"cdi.read", C::kCdi, "MemoryConfigurationS §4.2, §4.4, §4.5", Strength::kShall,
     "a node that has a CDI makes it readable through space 0xFF", "cd20",
     "reads of up to 64 bytes of 0xFF, each going on where the previous reply's data ended, up "
     "to Space Info's highest address, a NUL or 0x1082 (at the highest address without a NUL it "
     "reads on: a CDI cut short by a too-small highest address is judged whole, the address by "
     "cdi.nul-at-highest): data returned",
     k::cdi_read},
    {"datagram.ok-before-reply", C::kDatagram,
     "DatagramTransportS §6; MemoryConfigurationS §4.4; MemoryConfigurationTN §2.4.5",
     Strength::kShall,
     "every datagram is answered with Datagram Received OK or Rejected; only the technical note "
     "orders the OK before the reply (a late OK WARNs)",
     "", "(every CDI read) Datagram Received OK arrives before each read reply",
     k::datagram_ok_before_reply},
    {"datagram.reply-pending", C::kDatagram, "MemoryConfigurationS §4.4", Strength::kShall,
     "the Datagram Received OK to a Read carries Reply Pending", "",
     "(every CDI read) the Datagram Received OK has Reply Pending", k::datagram_reply_pending},
    {"memory.reply-latency", C::kMemory, "MessageNetworkS §3.7; DatagramTransportS §4.2",
     Strength::kShall,
     "a reply goes out within 750 ms unless the Datagram Received OK announced a longer timeout "
     "(2^N s)",
     "", "(every CDI read) worst request-to-reply time <= 750 ms", k::memory_reply_latency},
    {"cdi.nul-terminated", C::kCdi, "ConfigurationDescriptionInformationS §5", Strength::kShall,
     "the CDI is provided as a NUL-terminated string", "cd20", "(CDI download) a NUL ends the text",
     k::cdi_nul_terminated},
    {"cdi.nul-at-highest", C::kCdi, "MemoryConfigurationS §4.16", Strength::kNone,
     "no clause ties the highest address to the NUL: padding after it is legal; a highest address "
     "before the NUL WARNs",
     "", "(CDI download) offset of the NUL == Space Info highest address", k::cdi_nul_at_highest},
    {"cdi.no-bom", C::kCdi, "ConfigurationDescriptionInformationS §5", Strength::kShall,
     "the CDI string carries no byte-order mark", "", "no UTF-8 byte-order mark", k::cdi_no_bom},
    {"cdi.utf8", C::kCdi, "ConfigurationDescriptionInformationS §5", Strength::kShall,
     "the CDI string is UTF-8", "",
     "the CDI is valid UTF-8 (FAIL: offset, line and bytes of the first invalid sequence)",
     k::cdi_utf8},
    {"cdi.xml-declaration", C::kCdi, "ConfigurationDescriptionInformationS §5", Strength::kShall,
     "the first line is the XML 1.0 declaration", "cd10",
     "the first line (after a BOM, which is cdi.no-bom's) starts with exactly <?xml "
     "version=\"1.0\"?> (another declaration of XML 1.0 in UTF-8, e.g. encoding=\"utf-8\": "
     "WARN quoting it; another version or encoding, or none: FAIL quoting at most 80 bytes)",
     k::cdi_xml_declaration},
    {"cdi.well-formed", C::kCdi, "ConfigurationDescriptionInformationS §5", Strength::kShall,
     "the CDI is XML 1.0", "cd10",
     "pugixml's parse where the screen settles it, else libxml2's (FAIL quotes libxml2's first "
     "parse error and lists all; stopped at the "
     "invalid UTF-8: SKIP depends on cdi.utf8)",
     k::cdi_well_formed},
    {"cdi.valid", C::kCdi, "ConfigurationDescriptionInformationS §5, §5.1.4", Strength::kShall,
     "the CDI validates against the schema it names and follows the element rules of §5.1.4",
     "cd10",
     "cdi::validate: FAIL with every error (details), WARN with every warning, PASS when "
     "none (not well-formed: SKIP depends on cdi.well-formed)",
     k::cdi_valid},
    {"cdi.schema-location", C::kCdi, "ConfigurationDescriptionInformationS §5", Strength::kNone,
     "the standard shows the root naming the schema URL but sets no rule for other spellings", "",
     "xsi:noNamespaceSchemaLocation names http(s)://openlcb.org/schema/cdi/...xsd (absent: "
     "WARN)",
     k::cdi_schema_location},
    {"acdi.manufacturer-version", C::kAcdi, "ConfigurationDescriptionInformationS §5.1.2",
     Strength::kShall, "with <acdi/>, byte 0 of space 252 equals the fixed attribute", "cd30",
     "read 252 field by field (with <acdi/>): byte 0 == fixed", k::acdi_manufacturer_version},
    {"acdi.user-version", C::kAcdi, "ConfigurationDescriptionInformationS §5.1.2", Strength::kShall,
     "with <acdi/>, byte 0 of space 251 equals the var attribute", "cd30",
     "read 251 field by field (with <acdi/>): byte 0 == var", k::acdi_user_version},
    {"acdi.utf8", C::kAcdi, "ConfigurationDescriptionInformationS §5.1.2, §5.1.4.3",
     Strength::kShall, "the ACDI name fields are CDI strings, which are UTF-8", "",
     "(the same reads) each of the six strings of 252/251, up to its NUL, is valid UTF-8; FAIL "
     "names each invalid one with its bytes in hex",
     k::acdi_utf8},
    {"cdi.acdi-spaces", C::kCdi,
     "ConfigurationDescriptionInformationS §5.1.2; ConfigurationDescriptionInformationTN §2.5.1.2",
     Strength::kMay,
     "a node may also describe spaces 252/251 as segments; variables that contradict the ACDI "
     "layout WARN",
     "", "with <acdi/>: no CDI variable in 252, space-251 variables within bytes 1..127",
     k::cdi_acdi_spaces},
    {"acdi.space-info", C::kAcdi,
     "ConfigurationDescriptionInformationS §5.1.2; MemoryConfigurationS §4.16", Strength::kShall,
     "252 bytes 0-124 readable, 251 bytes 0-127 readable and writable; an exact size or read-only "
     "flag is not required (WARN)",
     "cd30",
     "`20 84 FC`, `20 84 FB`: 252 present, read-only, highest 124; 251 present, highest 127",
     k::acdi_space_info},
    {"pip.snip-bit", C::kPip, "SimpleNodeInformationS §6.1; MessageNetworkS §3.3.7",
     Strength::kShall, "a node supporting SNIP sets the SNIP bit", "me30",
     "PIP SNIP bit set iff the node answered SNIP", k::pip_snip_bit},
    {"pip.datagram-bit", C::kPip, "MessageNetworkS §3.3.7, §3.4.3", Strength::kShall,
     "the Datagram bit is set exactly when the node implements datagrams (any OK or Datagram "
     "Rejected shows it does)",
     "me30", "PIP Datagram bit set iff the node answered datagrams", k::pip_datagram_bit},
    {"pip.memory-config-bit", C::kPip, "MessageNetworkS §3.3.7, §3.4.3", Strength::kShall,
     "the Memory Configuration bit is set exactly when the node implements it", "me30",
     "PIP Memory Configuration bit set iff memory configuration answered",
     k::pip_memory_config_bit},
    {"pip.cdi-bit", C::kPip, "MessageNetworkS §3.3.7; MemoryConfigurationS §4.2", Strength::kShall,
     "the CDI bit is set exactly when the node provides a CDI", "me30",
     "PIP CDI bit set iff space 0xFF returned data", k::pip_cdi_bit},
    {"pip.acdi-bit", C::kPip, "ConfigurationDescriptionInformationS §5.1.2", Strength::kShall,
     "<acdi/> is present exactly when the PIP ACDI bit is set", "",
     "PIP ACDI bit set iff the CDI has <acdi/>", k::pip_acdi_bit},
    {"snip.matches-acdi", C::kSnip, "ConfigurationDescriptionInformationS §5.1.2", Strength::kShall,
     "with <acdi/> and SNIP, the SNIP strings equal the ACDI spaces", "",
     "all six SNIP strings equal the ACDI strings; FAIL names the first differing field",
     k::snip_matches_acdi},
    {"snip.matches-cdi", C::kSnip, "ConfigurationDescriptionInformationS §5.1.1", Strength::kShall,
     "with <identification> and SNIP, the SNIP strings equal the tags present", "",
     "the four manufacturer strings equal <identification>; FAIL names the first differing "
     "field",
     k::snip_matches_cdi},
    {"memory.options-acdi-flags", C::kMemory, "MemoryConfigurationS §4.14", Strength::kShall,
     "0x0800/0x0400/0x0200 announce reads of 252, reads and writes of 251", "mc10",
     "Options 0x0800 iff 252 readable, 0x0400 iff 251 readable, 0x0200 iff 251 writable",
     k::memory_options_acdi_flags},
    {"memory.space-info-layout.<sp>", C::kMemory,
     "MemoryConfigurationS §4.16; ConfigurationDescriptionInformationS §5.1.3", Strength::kNone,
     "no clause requires Space Info to cover the CDI layout (consistency only: WARN)", "mc20",
     "`20 84 SP` per space a CDI segment uses: present, highest address + 1 >= end of the "
     "layout in that space",
     k::memory_space_info_layout},
    {"memory.read-byte6-form", C::kMemory, "MemoryConfigurationS §4.2, §4.4", Strength::kShall,
     "any space may be named in byte 6", "mc30",
     "8-byte read of the data space (0xFD preferred) in the byte-6 form: Read Reply OK",
     k::memory_read_byte6_form},
    {"memory.read-short-form", C::kMemory, "MemoryConfigurationS §4.2, §4.4", Strength::kShall,
     "spaces 0xFD-0xFF may be named by the command byte", "mc30",
     "the same read in the short form (0xFD-0xFF): Read Reply OK", k::memory_read_short_form},
    {"memory.reply-form", C::kMemory, "MemoryConfigurationS §4.5", Strength::kNone,
     "both reply forms are defined; nothing ties the reply to the request's form", "mc30",
     "(those reads and the CDI reads) every reply uses the request's form", k::memory_reply_form},
    {"memory.read-short-at-end", C::kMemory, "MemoryConfigurationS §4.5", Strength::kShall,
     "a read reply may carry fewer bytes (at least one); reaching the end of the space is no error",
     "",
     "read 8 at highest-3 of 0xFF: OK with 4 bytes (SKIP \"depends on\" the check that found "
     "the highest address too small)",
     k::memory_read_short_at_end},
    {"memory.unknown-space", C::kMemory,
     "MemoryConfigurationS §4.3, §4.5; MemoryConfigurationTN §2.4.3", Strength::kShall,
     "a read that yields no bytes fails with an error code; 0x1081 is the recommended one (another "
     "code WARNs)",
     "", "read of an unused space (0x50 up): rejected or failed with exactly 0x1081",
     k::memory_unknown_space},
};

// The protocol checks after the topic lists: the lock, the writes to read-only spaces, and the
// checks that judge the whole run so far.
constexpr CheckSpec kLateChecks[] = {
    {"memory.lock", C::kMemory, "MemoryConfigurationS §4.17, §4.18; MemoryConfigurationTN §2.4.17",
     Strength::kShall,
     "when implemented, Lock/Reserve is a test-and-set of a node ID and zeros release it; not "
     "implemented (0x1041) SKIPs",
     "mc40",
     "`20 88` our ID, another ID, zeros: replies ours, ours, 0 (not implemented, 0x1041: SKIP; "
     "another rejection: WARN quoting the code; held or taken meanwhile by another tool: SKIP; "
     "while another lcc-conform run is on the segment: SKIP)",
     k::memory_lock, false, true},
    {"memory.readonly-refused.<sp>", C::kMemory,
     "MemoryConfigurationS §4.2, §4.3, §4.9; MemoryConfigurationTN §2.4.3", Strength::kShall,
     "a write to a read-only space fails with an error code; 0x1083 is recommended (another code "
     "WARNs)",
     "cd40",
     "write of byte 0 of 0xFF and 252 with the value read from it: refused with exactly 0x1083 "
     "(skipped with --read-only)",
     k::memory_readonly_refused},
    {"datagram.temporary-rejects", C::kDatagram, "DatagramTransportS §6.2", Strength::kMay,
     "a receiver may reject a datagram temporarily; the sender resends", "",
     "(whole run) PASS when no datagram was rejected temporarily; WARN with the count when some "
     "were and the retries succeeded",
     k::datagram_temporary_rejects},
    {"message.no-unsolicited", C::kMessage, "", Strength::kNone,
     "an initialized node may send any message; unprompted traffic is only noted (WARN)", "",
     "(observes the whole run, >= 1.2 s) no Verify/Identify/PCER/PSI/SNIP request/Learn frame "
     "originated by the node",
     k::no_unsolicited},
};

// What the node run's phases produce (run = nullptr): the encoding checks under the safety
// backup, the node watch, the link, and the short-read findings.
constexpr CheckSpec kPhaseChecks[] = {
    {"encoding.stored-strings", C::kEncoding, "ConfigurationDescriptionInformationS §5.1.4.3",
     Strength::kShall, "a string variable holds UTF-8 with a NUL within its size", "",
     "the original of every sampled <string>: a NUL within its size and valid UTF-8 (reads "
     "only, so --read-only runs it too)"},
    {"encoding.int", C::kEncoding,
     "ConfigurationDescriptionInformationS §5.1.4.2; MemoryConfigurationS §4.8, §4.4",
     Strength::kShall,
     "an accepted write of a value reads back in the CDI's encoding; refusing a value WARNs",
     "mc80",
     "writes of min, max, 0, map entries, the signedness edge: every read-back equals the "
     "encoding, byte for byte"},
    {"encoding.string", C::kEncoding,
     "ConfigurationDescriptionInformationS §5.1.4.3; MemoryConfigurationS §4.8, §4.4",
     Strength::kShall, "as encoding.int, for strings", "mc80",
     "\"\", size-1 bytes, 2- and 3-byte UTF-8 characters at the end, map entries: as above"},
    {"encoding.eventid", C::kEncoding,
     "ConfigurationDescriptionInformationS §5.1.4.4; MemoryConfigurationS §4.8, §4.4",
     Strength::kShall, "as encoding.int, for event IDs", "mc80",
     "four event IDs and map entries: as above"},
    {"encoding.float", C::kEncoding,
     "ConfigurationDescriptionInformationS §5.1.4.5; MemoryConfigurationS §4.8, §4.4",
     Strength::kShall, "as encoding.int, for floats", "mc80",
     "+0, -0, min, max, 1.5, a half-exact midpoint, 0.1, min+(max-min)/3: as above"},
    {"encoding.blob", C::kEncoding, "ConfigurationDescriptionInformationS §5.1.4.7",
     Strength::kNone, "the blob area has no read-back duty (WARN)", "",
     "two byte patterns (only with --blob, readwrite blobs): as above"},
    {"encoding.original-restored", C::kEncoding, "MemoryConfigurationS §4.8, §4.4",
     Strength::kShall, "an accepted write reads back", "",
     "only as FAIL: a variable's original did not read back after its test values"},
    {"encoding.protected", C::kEncoding, "ConfigurationDescriptionInformationS §5.1.4.1, §5.1.4.6",
     Strength::kNone, "SKIP only: what lcc-conform never writes", "",
     "SKIP listing every protected variable and why (see Safety)"},
    {"encoding.lock", C::kEncoding, "MemoryConfigurationS §4.17", Strength::kMay,
     "Lock/Reserve is optional; not implemented (0x1041) SKIPs", "",
     "only as WARN: the node rejected or ignored Lock/Reserve before the first write"},
    {"encoding.excluded", C::kEncoding, "", Strength::kNone, "SKIP only: what the user left out",
     "", "SKIP: how many variables the user's globs left out"},
    {"encoding.unreadable", C::kEncoding, "MemoryConfigurationS §4.5", Strength::kNone,
     "SKIP only: variables whose original could not be saved", "",
     "SKIP listing every variable whose original could not be read (so is not written)"},
    {"snip.follows-acdi-user-write", C::kSnip,
     "ConfigurationDescriptionInformationS §5.1.2; SimpleNodeInformationS §6.3", Strength::kShall,
     "the SNIP user strings equal space 251, which is writable", "",
     "write of a UTF-8 user name to 251 @1, a SNIP request, the original back: the reply "
     "carries the name"},
    {"encoding.persist-after-reboot", C::kEncoding,
     "MemoryConfigurationS §4.23, §4.24; MemoryConfigurationTN §2.4.24", Strength::kNone,
     "Update Complete, then Reset/Reboot: only the technical note says configuration survives "
     "(WARN)",
     "mc50",
     "(--reboot) test values, 20 A9, Initialization Complete, read back, originals back: "
     "every value survived"},
    {"encoding.read-only-spaces", C::kEncoding,
     "MemoryConfigurationS §4.2; ConfigurationDescriptionInformationS §5.1.2", Strength::kNone,
     "SKIP only: 252/255 are never written", "",
     "always SKIP: variables in the read-only spaces 252/255 are never written"},
    {"encoding.restore", C::kEncoding, "MemoryConfigurationS §4.8, §4.4", Strength::kShall,
     "an accepted write of the saved bytes reads back; bytes stored past the end of a space WARN",
     "", "every saved byte written back and read again: node memory byte-identical to before"},
    {"node.rebooted", C::kNode, "MessageNetworkS §3.4.1", Strength::kNone,
     "no clause forbids a restart; one not caused by lcc-conform (Update Complete, Reset, a staged "
     "collision) WARNs",
     "", "only as FAIL: the node reserved its alias again during the run"},
    {"node.stopped-answering", C::kNode, "MessageNetworkS §3.4.2", Strength::kShall,
     "a Verify Node ID addressed to the node is answered", "",
     "only as FAIL: the node no longer answers Verify Node ID"},
    {"link.lost", C::kLink, "", Strength::kRun,
     "the run itself: a lost link makes the results incomplete (exit 2)", "",
     "only as FAIL: the link went down during the node's run"},
    {"memory.short-read.<sp>", C::kMemory,
     "MemoryConfigurationS §4.5; MemoryConfigurationTN §2.4.5", Strength::kNone,
     "a reply may carry fewer bytes than asked; short replies away from the end are noted (WARN)",
     "",
     "(every read of the run) no Read Reply OK shorter than asked except at the end of the "
     "space"},
};

std::vector<CheckSpec> build_registry() {
    std::vector<CheckSpec> all;
    auto append = [&all](const auto& part) {
        all.insert(all.end(), std::begin(part), std::end(part));
    };
    append(kEarlyChecks);
    append(k::frame_bus_checks());
    append(k::message_addressing_checks());
    append(k::datagram_protocol_checks());
    append(k::memory_bounds_checks());
    append(k::event_checks());
    append(k::event_robustness_checks());
    append(k::stream_checks());
    append(kLateChecks);
    append(k::final_checks());
    append(kPhaseChecks);
    append(k::event_phase_checks());
    return all;
}

bool matches(const std::string& pattern, std::string_view id) {
    return fnmatch(pattern.c_str(), std::string(id).c_str(), 0) == 0;
}

// The result IDs an entry can produce (a per-space entry: one per space number).
template <typename F>
bool any_result_id(const CheckSpec& spec, F&& f) {
    if (!spec.id.ends_with(kPerSpace)) return f(spec.id);
    const std::string_view base = spec.id.substr(0, spec.id.size() - kPerSpace.size());
    if (f(base)) return true;
    for (unsigned sp = 0; sp <= 0xFF; ++sp) {
        char suffix[4];
        std::snprintf(suffix, sizeof suffix, "%02x", sp);
        if (f(std::string(base) + "." + suffix)) return true;
    }
    return false;
}

bool selected(const CheckSelection& sel, std::string_view id) {
    if (!sel.categories.empty()) {
        const std::string_view first = id.substr(0, id.find('.'));
        const bool in = std::any_of(sel.categories.begin(), sel.categories.end(),
                                    [&](Category c) { return category_name(c) == first; });
        if (!in) return false;
    }
    const auto hit = [&](const std::string& p) { return matches(p, id); };
    if (!sel.only.empty() && std::none_of(sel.only.begin(), sel.only.end(), hit)) return false;
    return std::none_of(sel.skip.begin(), sel.skip.end(), hit);
}

}  // namespace

std::string_view strength_name(Strength strength) {
    switch (strength) {
        case Strength::kShall:
            return "shall";
        case Strength::kShould:
            return "should";
        case Strength::kMay:
            return "may";
        case Strength::kNone:
            return "none";
        case Strength::kRun:
            return "run";
    }
    return "none";
}

void cite(CheckResult& result) {
    const CheckSpec* spec = find_check(result.id);
    if (spec == nullptr) return;
    result.category = spec->category;
    result.section = std::string(spec->section);
    const bool binding = spec->strength == Strength::kShall || spec->strength == Strength::kRun;
    if (binding || result.status != Status::kFail) return;
    result.status = Status::kWarn;
    result.message += " (a WARN, not a FAIL: the standard says \"" +
                      std::string(strength_name(spec->strength)) + "\" here, " +
                      std::string(spec->section) + ")";
}

const std::vector<CheckSpec>& check_registry() {
    static const std::vector<CheckSpec> registry = build_registry();
    return registry;
}

const CheckSpec* find_check(std::string_view result_id) {
    for (const CheckSpec& spec : check_registry()) {
        if (spec.id == result_id) return &spec;
        if (!spec.id.ends_with(kPerSpace)) continue;
        const std::string_view base = spec.id.substr(0, spec.id.size() - kPerSpace.size() + 1);
        if (result_id.size() == base.size() + 2 && result_id.starts_with(base)) return &spec;
    }
    return nullptr;
}

bool is_check_pattern(std::string_view pattern) {
    static constexpr std::array<Category, 13> kAll = {
        C::kFrame, C::kMessage,  C::kPip,  C::kSnip, C::kDatagram, C::kMemory, C::kCdi,
        C::kAcdi,  C::kEncoding, C::kLink, C::kNode, C::kEvents,   C::kStream};
    const std::string_view first = pattern.substr(0, pattern.find('.'));
    return std::any_of(kAll.begin(), kAll.end(),
                       [&](Category c) { return category_name(c) == first; });
}

bool CheckSelection::wants(const CheckSpec& spec) const {
    if (spec.thorough && !thorough) return false;
    if (spec.past_end_writes && !write_past_end) return false;
    return any_result_id(spec, [&](std::string_view id) { return selected(*this, id); });
}

bool CheckSelection::wants_id(std::string_view id) const {
    if (const CheckSpec* spec = find_check(id);
        spec && ((spec->thorough && !thorough) || (spec->past_end_writes && !write_past_end)))
        return false;
    return selected(*this, id);
}

bool CheckSelection::wants_writes() const {
    const auto& all = check_registry();
    return std::any_of(all.begin(), all.end(), [&](const CheckSpec& s) {
        return !s.run &&
               (s.category == C::kEncoding || s.category == C::kEvents ||
                s.id == "snip.follows-acdi-user-write") &&
               wants(s);
    });
}

std::string format_check_list() {
    std::ostringstream out;
    for (const CheckSpec& s : check_registry()) {
        out << s.id << "\t" << category_name(s.category) << "\t" << s.section << "\t"
            << strength_name(s.strength) << "\t" << (s.olcbchecker.empty() ? "-" : s.olcbchecker)
            << "\t" << s.summary << (s.thorough ? " [--thorough]" : "")
            << (s.past_end_writes ? " [--write-past-end]" : "") << "\n";
    }
    return out.str();
}

const std::vector<OlcbCheckerCheck>& olcbchecker_checks() {
    static const std::vector<OlcbCheckerCheck> all = {
        {"fr10", "start-up sequence after a reboot", ""},
        {"fr20", "AME answered", ""},
        {"fr30", "alias collision: CID, then another node's frame with the node's alias", ""},
        {"fr40", "AME with bit 28 clear", ""},
        {"fr50", "capacity: 300 frames back to back around an addressed Verify", ""},
        {"fr60", "2,047 standard (11-bit) frames ignored", ""},
        {"me10", "Initialization Complete after a reboot", ""},
        {"me20", "Verify Node ID global, addressed, addressed to another node", ""},
        {"me30", "Protocol Support Inquiry; to another node silence; 4th byte", ""},
        {"me40", "unknown MTI: global silence, addressed OIR, to another node silence", ""},
        {"me50", "duplicate node ID indicated", ""},
        {"me60", "PIP simple bit agrees with the Verified MTI", ""},
        {"sn10", "SNIP reply", ""},
        {"ev10", "Identify Events addressed", ""},
        {"ev20", "Identify Events global", ""},
        {"ev30", "Identify Producer", ""},
        {"ev40", "Identify Consumer", ""},
        {"ev50", "event identification after start-up",
         "not covered: needs a reboot for every run; the reboot lcc-conform makes (--reboot) is "
         "judged by frame.startup-sequence and encoding.persist-after-reboot"},
        {"ev60", "PCER with payload does not upset the node", ""},
        {"ev70", "Learn Event does not upset the node", ""},
        {"da30", "datagrams of 1, 10 and 72 bytes of no known protocol", ""},
        {"da40", "unknown datagram protocol rejected, no restart in a 30-s soak", ""},
        {"mc10", "Get Configuration Options, write-lengths byte", ""},
        {"mc20", "Get Address Space Information", ""},
        {"mc30", "reads of 2/10/64 bytes in both forms", ""},
        {"mc40", "Lock/Reserve sequence", ""},
        {"mc50", "Reset/Reboot: the node restarts", ""},
        {"mc60", "read past the end of 0xFD fails", ""},
        {"mc70", "write under mask (if advertised)", ""},
        {"mc80", "write, read back, restore one byte", ""},
        {"cd10", "CDI valid against its schema", ""},
        {"cd20", "CDI read to its NUL (datagrams; stream variant)", ""},
        {"cd30", "ACDI spaces agree with SNIP and the CDI", ""},
        {"cd40", "writes to 0xFB byte 0 and to 0xFC refused",
         "the 0xFC half only: the standard lists 251 with its version byte as read and write "
         "(ConfigurationDescriptionInformationS §5.1.2; MemoryConfigurationS §4.1: no space is "
         "partly read-only), so accepting a write of 0xFB byte 0 is no fault"},
        {"st10-st210", "stream transport (lcc-conform as the source, the node as the sink)",
         "covered only as the node's source side in memory-config stream reads (the node "
         "streams to lcc-conform); the checks with lcc-conform as the source are not covered"},
        {"bt, dd, fd, tr, ts", "broadcast time, DCC detector, FDI, train control, train search",
         "not covered: protocols of other node kinds than configurable nodes"},
    };
    return all;
}

namespace {

// "`a`, `b`" of the registry IDs naming an OlcbChecker check in their olcbchecker field.
std::string covering(std::string_view olcb) {
    std::string out;
    for (const CheckSpec& s : check_registry()) {
        std::string_view list = s.olcbchecker;
        bool hit = false;
        while (!list.empty()) {
            const std::size_t comma = list.find(',');
            std::string_view one = list.substr(0, comma);
            while (one.starts_with(' ')) one.remove_prefix(1);
            if (one == olcb) hit = true;
            list = comma == std::string_view::npos ? "" : list.substr(comma + 1);
        }
        if (hit) out += (out.empty() ? "`" : ", `") + std::string(s.id) + "`";
    }
    return out;
}

std::string cell(std::string_view text) {
    std::string out;
    for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

}  // namespace

std::string format_check_markdown() {
    std::ostringstream out;
    out << "| ID | Category | Standard, section | Strength: the clause | OlcbChecker | What is "
           "sent, "
           "what passes |\n"
           "|---|---|---|---|---|---|\n";
    for (const CheckSpec& s : check_registry()) {
        out << "| `" << s.id << "` | " << category_name(s.category) << " | " << cell(s.section)
            << " | **" << strength_name(s.strength) << "**: " << cell(s.clause) << " | "
            << (s.olcbchecker.empty() ? "–" : s.olcbchecker) << " | " << cell(s.summary)
            << (s.thorough ? " (only with `--thorough`)" : "")
            << (s.past_end_writes ? " (only with `--write-past-end`)" : "")
            << (s.run ? "" : " (produced by the node run's phases)") << " |\n";
    }
    out << "\n| OlcbChecker | What it checks | lcc-conform |\n|---|---|---|\n";
    for (const OlcbCheckerCheck& c : olcbchecker_checks()) {
        const std::string by = covering(c.id);
        out << "| " << c.id << " | " << cell(c.title) << " | " << (by.empty() ? "" : by)
            << (by.empty() || c.not_why.empty() ? "" : "; ") << cell(c.not_why) << " |\n";
    }
    return out.str();
}

}  // namespace olcb::conform
