// The encoding checks' registry entries: what the node run's encoding phase reports (one variable
// at a time under the safety backup, run/encoding_run.cpp), the variables it leaves alone and the
// restore.
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {

std::vector<CheckSpec> encoding_checks() {
    return {
        {"encoding.stored-strings", 780, Category::kEncoding,
         "ConfigurationDescriptionInformationS §5.1.4.3", Strength::kShall,
         "a string variable holds UTF-8 with a NUL within its size", "",
         "the original of every sampled <string>: a NUL within its size and valid UTF-8 (reads "
         "only, so --read-only runs it too)"},
        {"encoding.int", 790, Category::kEncoding,
         "ConfigurationDescriptionInformationS §5.1.4.2; MemoryConfigurationS §4.8, §4.4",
         Strength::kShall,
         "an accepted write of a value reads back in the CDI's encoding; refusing a value WARNs",
         "mc80",
         "writes of min, max, 0, map entries, the signedness edge: every read-back equals the "
         "encoding, byte for byte"},
        {"encoding.string", 800, Category::kEncoding,
         "ConfigurationDescriptionInformationS §5.1.4.3; MemoryConfigurationS §4.8, §4.4",
         Strength::kShall, "as encoding.int, for strings", "mc80",
         "\"\", size-1 bytes, 2- and 3-byte UTF-8 characters at the end, map entries: as above"},
        {"encoding.eventid", 810, Category::kEncoding,
         "ConfigurationDescriptionInformationS §5.1.4.4; MemoryConfigurationS §4.8, §4.4",
         Strength::kShall, "as encoding.int, for event IDs", "mc80",
         "four event IDs and map entries: as above"},
        {"encoding.float", 820, Category::kEncoding,
         "ConfigurationDescriptionInformationS §5.1.4.5; MemoryConfigurationS §4.8, §4.4",
         Strength::kShall, "as encoding.int, for floats", "mc80",
         "+0, -0, min, max, 1.5, a half-exact midpoint, 0.1, min+(max-min)/3: as above"},
        {"encoding.blob", 830, Category::kEncoding, "ConfigurationDescriptionInformationS §5.1.4.7",
         Strength::kNone, "the blob area has no read-back duty (WARN)", "",
         "two byte patterns (only with --blob, readwrite blobs): as above"},
        {"encoding.original-restored", 840, Category::kEncoding, "MemoryConfigurationS §4.8, §4.4",
         Strength::kShall, "an accepted write reads back", "",
         "only as FAIL: a variable's original did not read back after its test values"},
        {"encoding.protected", 850, Category::kEncoding,
         "ConfigurationDescriptionInformationS §5.1.4.1, §5.1.4.6", Strength::kNone,
         "SKIP only: what lcc-conform never writes", "",
         "SKIP listing every protected variable and why (see Safety)"},
        {"encoding.lock", 860, Category::kEncoding, "MemoryConfigurationS §4.17", Strength::kMay,
         "Lock/Reserve is optional; not implemented (0x1041) SKIPs", "",
         "only as WARN: the node rejected or ignored Lock/Reserve before the first write"},
        {"encoding.excluded", 870, Category::kEncoding, "", Strength::kNone,
         "SKIP only: what the user left out", "",
         "SKIP: how many variables the user's globs left out"},
        {"encoding.unreadable", 880, Category::kEncoding, "MemoryConfigurationS §4.5",
         Strength::kNone, "SKIP only: variables whose original could not be saved", "",
         "SKIP listing every variable whose original could not be read (so is not written)"},
        {"encoding.persist-after-reboot", 900, Category::kEncoding,
         "MemoryConfigurationS §4.23, §4.24; MemoryConfigurationTN §2.4.24", Strength::kNone,
         "Update Complete, then Reset/Reboot: only the technical note says configuration survives "
         "(WARN)",
         "mc50",
         "(--reboot) test values, 20 A9, Initialization Complete, read back, originals back: "
         "every value survived"},
        {"encoding.read-only-spaces", 910, Category::kEncoding,
         "MemoryConfigurationS §4.2; ConfigurationDescriptionInformationS §5.1.2", Strength::kNone,
         "SKIP only: 252/255 are never written", "",
         "always SKIP: variables in the read-only spaces 252/255 are never written"},
        {"encoding.restore", 920, Category::kEncoding, "MemoryConfigurationS §4.8, §4.4",
         Strength::kShall,
         "an accepted write of the saved bytes reads back; bytes stored past the end of a space "
         "WARN",
         "", "every saved byte written back and read again: node memory byte-identical to before"},
    };
}

}  // namespace olcb::conform::checks
